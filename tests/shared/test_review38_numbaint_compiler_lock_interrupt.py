"""A Ctrl-C as numba lets go of its compiler lock leaves it held for good (review 38, NUMBAINT).

Found by NUMBAINT's hunt for interrupts that break numba for the process: numba's
``global_compiler_lock`` is a Python context manager (``_CompilerLock.__exit__``
calls ``release``, which releases the ``RLock`` and then reports the event that
``navkit._shared.compile_gc`` listens to). CPython runs a pending signal handler
on entering a Python function, so a Ctrl-C arriving as ``__exit__`` (or
``release``) is entered raises ``KeyboardInterrupt`` before the lock is let go:
the main thread keeps numba's compiler lock for the rest of the process. Every
compile and cache load in another thread then waits for ever (a ROS 2 executor's
callbacks), a fork from another thread waits for ever in navkit's fork hook, and
during a navkit kernel's compile navkit's pause of the garbage collector and its
compile shortcuts never end (they end at the outermost release): the collector
stays off for good. About one delivery point per use of the lock (several per
compile and cache load), so a real Ctrl-C lands there rarely, but then silently.

Fixed in review 39 (NUMBAINT2): while the main thread holds numba's compiler
lock, navkit's handler holds a Ctrl-C back only inside the locks' own steps and
the object-cache callbacks (``navkit._shared.interrupts.StepHold``, begun by
``navkit._shared.compile_gc``), and delivers it at the next delivery point after.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import rollout
from subprocess_probe import UNHELD_SIGINT, probe_outcome

_PROBE = r"""
import gc, json, os, signal, sys, threading
import numba
import numpy as np
from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba
from navkit.geometry import rollout

load_numba()
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock

fired = []

""" + UNHELD_SIGINT + r"""
def profile(frame, event, arg):
    # A Ctrl-C as numba's compiler lock is let go, in a navkit kernel's cold compile,
    # where navkit holds nothing back (Python's own handler in place).
    if (
        event == "call"
        and frame.f_code is _CompilerLock.__exit__.__code__
        and unheld()
    ):
        fired.append(True)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)
    first = "ran"
except KeyboardInterrupt:
    first = "interrupted"
finally:
    sys.setprofile(None)
state = {
    "lock held": global_compiler_lock.is_locked(),
    "collector on": gc.isenabled(),
    "shortcuts on": compile_shortcuts.active(),
}

@numba.njit
def user(x):
    return x + 1

box = []
thread = threading.Thread(target=lambda: box.append(user(1)), daemon=True)
thread.start()
thread.join(60)
state["thread compiles"] = box == [2]
again = rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)[-1, 0].item()
print(json.dumps([bool(fired), first, state, round(again, 9)]))
os._exit(0)  # the thread may still wait for the lock
"""


def test_a_ctrl_c_as_numbas_compiler_lock_is_let_go_leaves_it_free(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # a cold compile in the probe
    fired, first, state, again = probe_outcome(_PROBE, timeout=300)
    assert fired, "numba's compiler lock is no longer a Python context manager"
    assert first == "interrupted"
    expected = rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)[-1, 0].item()
    assert again == round(expected, 9)  # the kernel itself works again
    assert state == {
        "lock held": False,
        "collector on": True,
        "shortcuts on": False,
        "thread compiles": True,
    }
