"""Review 41 (REVSIG): a Ctrl-C as navkit's load of numba lets go of numba's compiler lock.

``jit.load_numba`` (a process's first kernel call) takes numba's compiler lock
and installed ``compile_gc``'s listeners inside it, so the main thread's hold
of signals in the lock's steps (``interrupts.StepHolds``) did not span that
lock: it was begun by a nested acquire, in front of the Ctrl-C deferral
around numba's initialisation, which ended first and put Python's handler back
over it. A Ctrl-C as ``load_numba`` let go of the lock (numba's ``release``
entered, the lock not yet let go) left numba's compiler lock held by the main
thread for good: every later compile or cache load in another thread waited
for ever. The listeners are now installed before the lock is taken. In a fresh
interpreter; the Ctrl-C is raised at the chosen point by a profile function,
not on a timer.
"""

from __future__ import annotations

import sys

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_CTRL_C_AS_THE_LOAD_LETS_GO = r"""
import json, signal, sys, threading
import numba
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock as lock
from navkit._shared import compile_gc
from navkit._shared.jit import load_numba, numba_loaded

release = _CompilerLock.release.__code__
sent = []

def profile(frame, ev, arg):
    # A Ctrl-C as load_numba's own hold of numba's lock is let go (numba's release
    # entered, the lock held once, navkit's listeners installed).
    if ev == "call" and frame.f_code is release and not sent and compile_gc._INSTALLED:
        if "count=1" in repr(lock._lock):
            sent.append(1)
            sys.setprofile(None)
            signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    try:
        load_numba()
    finally:
        sys.setprofile(None)
    len(())  # a Ctrl-C held in a step comes at the next delivery point
    outcome = "ran"
except KeyboardInterrupt:
    outcome = "interrupted"

# Another thread's compile (it would wait for ever for a lock the main thread kept).
results = []
if not lock.is_locked():
    worker = threading.Thread(target=lambda: results.append(numba.njit(lambda x: x + 1)(1)))
    worker.daemon = True
    worker.start()
    worker.join(120)
print(json.dumps([
    outcome,
    sent,
    lock.is_locked(),
    numba_loaded(),
    signal.getsignal(signal.SIGINT) is signal.default_int_handler,
    results,
]))
"""


def test_a_ctrl_c_as_load_numba_lets_go_of_the_compiler_lock_leaves_it_free() -> None:
    outcome, sent, locked, loaded, back, results = probe_outcome(_CTRL_C_AS_THE_LOAD_LETS_GO)
    assert sent == [1]
    assert outcome == "interrupted"  # delivered, just after the step
    assert locked is False  # was True: held by the main thread for good
    assert loaded is True
    assert back is True
    assert results == [2]  # another thread compiles
