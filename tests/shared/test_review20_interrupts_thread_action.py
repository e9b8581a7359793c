"""A ``SIGINT`` action installed from another thread during a deferral (review 20).

``interrupts_deferred`` ends its block with ``signal.signal(SIGINT, previous)``,
which sets the system's action to Python's handler. A C library that installs
its own action with ``sigaction`` from another thread while the block runs (a
ROS 2 program calling ``rclpy.init()`` in a worker thread while the main thread
makes navkit's first kernel call) had that action overwritten at the block's
end: the same loss of Ctrl-C the outside-handler fix of review 19 cured for an
action installed before the block. Now the action found at the end is kept when
it is not the block's own, and a Ctrl-C held by the block is handed to it.

The probes set "ignore" through the C library from a thread inside the block
(Python does not see it); it must still be in force after the block.
"""

from __future__ import annotations

import os
import sys

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    os.name != "posix" or sys.platform == "emscripten", reason="sigaction is POSIX"
)

_PROBE = """
import ctypes, json, os, signal, sys, threading, time
libc = ctypes.CDLL(None)
libc.signal.restype = ctypes.c_void_p
libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
from navkit._shared.interrupts import interrupts_deferred

def install() -> None:
    libc.signal(signal.SIGINT, ctypes.c_void_p(1))  # SIG_IGN, unseen by Python

try:
    with interrupts_deferred():
        if sys.argv[1] == "held":
            os.kill(os.getpid(), signal.SIGINT)  # held by the block
            time.sleep(0.05)
        worker = threading.Thread(target=install if sys.argv[2] == "install" else None)
        worker.start()
        worker.join()
    time.sleep(0.05)
    os.kill(os.getpid(), signal.SIGINT)  # after the block: the action in force decides
    time.sleep(0.05)
    print(json.dumps("ignored"))
except KeyboardInterrupt:
    print(json.dumps("KeyboardInterrupt"))
"""


@pytest.mark.parametrize("held", ["held", "none"])
def test_an_action_installed_by_another_thread_during_the_block_survives(held: str) -> None:
    assert probe_outcome(_PROBE, held, "install") == "ignored"


@pytest.mark.parametrize("held", ["held", "none"])
def test_without_an_outside_action_python_s_handler_is_back(held: str) -> None:
    # The control: the same run with a thread that installs nothing raises.
    assert probe_outcome(_PROBE, held, "nothing") == "KeyboardInterrupt"


_EARLY = """
import ctypes, json, os, signal, sys, time
libc = ctypes.CDLL(None)
libc.signal.restype = ctypes.c_void_p
libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
libc.signal(signal.SIGINT, ctypes.c_void_p(1))  # SIG_IGN, unseen by Python
from navkit._shared import interrupts
real = interrupts._system_action
calls = []

def reading():
    calls.append(1)
    if len(calls) == 2:  # the block's own action, read just after it is installed
        signal.raise_signal(signal.SIGINT)  # held
        signal.raise_signal(signal.SIGINT)  # the second: delivered at once
    return real()

interrupts._system_action = reading
try:
    with interrupts.interrupts_deferred():
        pass
except KeyboardInterrupt:
    print(json.dumps("KeyboardInterrupt"))
    sys.exit(0)
interrupts._system_action = real
os.kill(os.getpid(), signal.SIGINT)
time.sleep(0.05)
print(json.dumps("ignored"))
"""


def test_a_second_ctrl_c_before_the_block_reads_its_action_keeps_the_outside_one() -> None:
    # Both presses go to the outside "ignore", which stays in force after.
    assert probe_outcome(_EARLY) == "ignored"
