"""``interrupts_deferred`` and a SIGINT action set outside Python (review 19).

A C library may install its own ``SIGINT`` handler with ``sigaction``: rclpy's
``rclpy.init()`` does (it wakes the executor's wait and chains to Python's
handler), as do embedding applications. Python's ``signal.getsignal`` does not
see it (it reports the handler Python last installed), so
``interrupts_deferred`` put *Python's* handler back at the end of its block
(``signal.signal(SIGINT, previous)``) and the outside one was gone for the rest
of the process: after navkit's first kernel use (``load_numba``) a ROS 2
node's ``spin()`` no longer woke on Ctrl-C. Before session 22 navkit never
touched the handler.

The probe sets the action to "ignore" through the C library (no compiler
needed), which Python does not know of; it must still be "ignore" after the
block; and a Ctrl-C held during the block must reach it (here: be ignored).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    os.name != "posix" or sys.platform == "emscripten", reason="sigaction is POSIX"
)

_PROBE = """
import ctypes, json, os, signal, sys, time
libc = ctypes.CDLL(None)
libc.signal.restype = ctypes.c_void_p
libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
libc.signal(signal.SIGINT, ctypes.c_void_p(1))  # SIG_IGN, set where Python does not see it
if sys.argv[1] == "block":
    from navkit._shared.interrupts import interrupts_deferred
    with interrupts_deferred():
        pass
else:
    from navkit._shared.jit import load_numba
    load_numba()
try:
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(0.05)
    print(json.dumps("ignored"))
except KeyboardInterrupt:
    print(json.dumps("KeyboardInterrupt"))
"""


def test_the_probe_sees_the_outside_action_without_navkit() -> None:
    # The control: with nothing of navkit's run, the signal is ignored.
    script = _PROBE.replace('if sys.argv[1] == "block":', "if False:").replace(
        "    load_numba()", "    pass"
    )
    assert probe_outcome(script, "none") == "ignored"


@pytest.mark.parametrize("where", ["block", "load_numba"])
def test_an_outside_sigint_action_survives(where: str) -> None:
    assert probe_outcome(_PROBE, where) == "ignored"


_HELD = """
import ctypes, json, os, signal, sys, time
libc = ctypes.CDLL(None)
libc.signal.restype = ctypes.c_void_p
libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
libc.signal(signal.SIGINT, ctypes.c_void_p(int(sys.argv[1])))  # unseen by Python
from navkit._shared.interrupts import interrupts_deferred
try:
    with interrupts_deferred():
        os.kill(os.getpid(), signal.SIGINT)  # held: it goes to the outside action after
        time.sleep(0.05)
    time.sleep(0.05)
    print(json.dumps("after the block"))
except KeyboardInterrupt:
    print(json.dumps("KeyboardInterrupt"))
"""


def test_a_held_ctrl_c_goes_to_an_outside_ignore() -> None:
    assert probe_outcome(_HELD, "1") == "after the block"  # SIG_IGN


def test_a_held_ctrl_c_goes_to_an_outside_default_action() -> None:
    # The system's default action for SIGINT ends the process, as without navkit.
    script = _HELD.replace("sys.argv[1]", "0")
    done = subprocess.run(
        [sys.executable, "-c", script], env=dict(os.environ), capture_output=True,
        text=True, timeout=120, check=False,
    )  # fmt: skip
    assert done.returncode == -signal.SIGINT, (done.returncode, done.stdout, done.stderr)
    assert "after the block" not in done.stdout
