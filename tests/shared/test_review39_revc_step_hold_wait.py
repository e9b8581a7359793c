"""The main thread's StepHold while it waits for numba's compiler lock (review 39, REVC).

``compile_gc`` begins the main thread's ``StepHold`` (navkit's ``SIGINT``
handler in front of the user's) as numba reports a compiler-lock acquire,
before the wait for the lock, and ends it at the outermost release. While
another thread holds the lock, the main thread's wait runs other signals'
handlers, and two of their common uses go wrong:

* a handler that raises (a ``signal.alarm`` timeout) ends the wait with no
  release to follow: the call fails with the handler's exception, and navkit's
  handler stays the ``SIGINT`` handler afterwards (``signal.getsignal``
  returns ``StepHold.hold``; the user's is put back only at the next Ctrl-C);
* a handler that compiles (a kernel of its own) acquires and releases the lock
  inside the wait; its outermost release ends the hold, and the waiting
  compile then runs with no hold at all (a Ctrl-C in its lock steps is again
  the ``KeyboardInterrupt`` that left a lock held for good).

Each runs in a fresh interpreter (a worker thread holds the lock until the
handler runs).
Strict xfails until review 40 (STEPHOLD): ``compile_gc._wrap_acquire`` ends the
hold when the wait ends in an exception, and a release ends it only with no
acquire waiting further out (``compile_gc._end_lock_hold``).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from subprocess_probe import LOCK_WAIT_SENDER

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_SETUP = (
    LOCK_WAIT_SENDER
    + r"""
import signal, threading, time
import numba
from numba.extending import overload
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import global_compiler_lock

def probe(x):
    pass

seen = []

@overload(probe)
def probe_typing(x):
    seen.append(signal.getsignal(signal.SIGINT))  # the handler during the compile
    return lambda x: x

held, in_handler = threading.Event(), threading.Event()

def hold_the_lock():
    with global_compiler_lock:
        held.set()
        in_handler.wait(60)

def start_the_wait(alarm):
    # The worker holds the lock until SIGALRM's handler runs; SIGALRM is sent once the
    # main thread is seen waiting for the lock (no timers: a loaded machine can pause
    # the main thread past them, and the signal then lands before or after the wait).
    def on_alarm(signum, frame):
        in_handler.set()
        return alarm(signum, frame)

    signal.signal(signal.SIGALRM, on_alarm)
    worker = threading.Thread(target=hold_the_lock)
    worker.start()
    held.wait(60)
    threading.Thread(target=send_in_the_lock_wait, args=(signal.SIGALRM,)).start()
    return worker
"""
)

_RAISING = (
    _SETUP
    + r"""
def alarm(signum, frame):
    raise TimeoutError

@numba.njit
def kernel(x):
    return x + 1

worker = start_the_wait(alarm)
try:
    kernel(1)
except TimeoutError:
    pass
worker.join()
print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)
"""
)

_COMPILING = (
    _SETUP
    + r"""
def alarm(signum, frame):
    numba.njit(lambda x: x + 1)(1)

@numba.njit
def kernel(x):
    return probe(x)

worker = start_the_wait(alarm)
kernel(1)
worker.join()
print(getattr(seen[0], "__qualname__", "") == "StepHold.hold")
"""
)


def _run(code: str) -> str:
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False
    )
    assert done.returncode == 0, done.stderr
    return done.stdout.strip().splitlines()[-1]


def test_an_exception_in_the_wait_for_the_lock_puts_the_users_handler_back() -> None:
    assert _run(_RAISING) == "True"


def test_a_compile_in_a_handler_during_the_wait_leaves_the_hold_to_the_waiting_compile() -> None:
    assert _run(_COMPILING) == "True"
