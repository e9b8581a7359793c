"""numba's compiler-lock ``acquire`` as navkit wraps it, to end the main thread's StepHold.

``compile_gc._wrap_acquire`` sets a method on numba's one global lock that
calls numba's ``acquire`` and, when the wait for the lock ends in an
exception (another signal's handler raised), ends the main thread's hold of
Ctrl-C (``interrupts.StepHold``); a release ends it only when no acquire
waits further out (``compile_gc._end_lock_hold``). Review 39's two cases are in
``test_review39_revc_step_hold_wait.py``; here the wrapper stays numba's
``acquire`` to every caller (threads, users' direct calls, an ``acquire`` set
before navkit's), an exception after a compile in the handler still ends the
hold, and a signal at every delivery point of an acquire leaves neither the
lock nor the hold behind. Each in a fresh interpreter.
"""

from __future__ import annotations

import sys

import pytest

from subprocess_probe import LOCK_WAIT_SENDER, probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_TRANSPARENT = r"""
import json, signal, threading, time
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import global_compiler_lock, require_global_compiler_lock

lock = global_compiler_lock
out = {
    # The one attribute navkit sets on numba's lock: a method bound to it.
    "keys": sorted(vars(lock)),
    "bound": lock.acquire.__self__ is lock and lock.acquire.__func__.__name__ == "acquire",
}
# The user's direct calls, nested (the lock is re-entrant).
lock.acquire()
lock.acquire()
require_global_compiler_lock()
lock.release()
held_once = lock.is_locked()
lock.release()
out["direct"] = [held_once, lock.is_locked()]

# Another thread holds the lock: the main thread's acquire waits for its release.
order = []
def hold_it():
    with lock:
        order.append("worker in")
        time.sleep(0.3)
        order.append("worker out")
worker = threading.Thread(target=hold_it)
worker.start()
while not order:
    time.sleep(0.01)
with lock:
    order.append("main in")
worker.join()
out["order"] = order

# Users' own kernels compiled in two threads at once.
results = [None, None]
def compile_one(i):
    results[i] = numba.njit(lambda x: x * (i + 2))(10)
threads = [threading.Thread(target=compile_one, args=(i,)) for i in range(2)]
for t in threads:
    t.start()
for t in threads:
    t.join()
out["kernels"] = results + [numba.njit(lambda x: x - 1)(10)]
out["after"] = [lock.is_locked(), signal.getsignal(signal.SIGINT) is signal.default_int_handler]
print(json.dumps(out))
"""


def test_the_wrapped_acquire_is_numbas_acquire_to_every_caller() -> None:
    out = probe_outcome(_TRANSPARENT, timeout=300)
    assert out["keys"] == ["_lock", "acquire"]
    assert out["bound"] is True
    assert out["direct"] == [True, False]
    assert out["order"] == ["worker in", "worker out", "main in"]
    assert out["kernels"] == [20, 30, 9]
    assert out["after"] == [False, True]


_SET_BEFORE = r"""
import json
import numba
from numba.core.compiler_lock import global_compiler_lock

calls = []
numba_acquire = global_compiler_lock.acquire
def own_acquire():  # a program's own acquire, set before navkit is loaded
    calls.append(1)
    numba_acquire()
global_compiler_lock.acquire = own_acquire

from navkit._shared.jit import load_numba

load_numba()
result = numba.njit(lambda x: x + 1)(1)
print(json.dumps([result, len(calls) > 0, global_compiler_lock.is_locked()]))
"""


def test_an_acquire_set_on_the_lock_before_navkit_is_still_called() -> None:
    assert probe_outcome(_SET_BEFORE, timeout=300) == [2, True, False]


_COMPILE_THEN_RAISE = (
    LOCK_WAIT_SENDER
    + r"""
import json, signal, threading, time
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import global_compiler_lock

held, in_handler = threading.Event(), threading.Event()

def hold_the_lock():
    with global_compiler_lock:
        held.set()
        in_handler.wait(60)  # until the handler runs in the main thread's wait

def alarm(signum, frame):
    # In the main thread's wait for the lock: a compile of its own (which takes and
    # lets go of the lock inside the wait), then an exception that ends the wait.
    in_handler.set()
    numba.njit(lambda x: x + 1)(1)
    raise TimeoutError

signal.signal(signal.SIGALRM, alarm)
worker = threading.Thread(target=hold_the_lock)
worker.start()
held.wait(60)
# Sent once the main thread is seen waiting (a timer can fire before or after the wait
# on a loaded machine).
threading.Thread(target=send_in_the_lock_wait, args=(signal.SIGALRM,)).start()

@numba.njit
def kernel(x):
    return x + 2

try:
    kernel(1)
    outcome = "ran"
except TimeoutError:
    outcome = "timed out"
back = signal.getsignal(signal.SIGINT) is signal.default_int_handler
worker.join()
print(json.dumps([outcome, back, kernel(1), global_compiler_lock.is_locked()]))
"""
)


def test_an_exception_after_a_compile_in_the_handler_still_ends_the_hold() -> None:
    # The handler's release leaves the hold to the waiting acquire; its exception
    # then ends that wait, and with it the hold.
    assert probe_outcome(_COMPILE_THEN_RAISE, timeout=300) == ["timed out", True, 3, False]


_EVERY_POINT = r"""
import json, signal, sys
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock

lock = global_compiler_lock
numba_acquire = _CompilerLock.acquire.__code__

def alarm(signum, frame):
    raise TimeoutError

signal.signal(signal.SIGALRM, alarm)

def acquiring(frame):
    # Inside numba's acquire, the lock not yet taken (the wait's side of it).
    if lock.is_locked():
        return False
    while frame is not None:
        if frame.f_code is numba_acquire:
            return True
        frame = frame.f_back
    return False

def with_block():
    with lock:
        pass

def direct():
    lock.acquire()
    try:
        pass
    finally:
        lock.release()

def run(take, signum, stop_at):
    # ``take`` with ``signum`` raised at its stop_at-th delivery point (0: none);
    # SIGALRM (its handler raises) only where an acquire has not taken the lock.
    seen = 0
    raised = False
    def profile(frame, event, arg):
        nonlocal seen, raised
        if event in ("call", "c_return"):
            seen += 1
            if seen >= stop_at > 0 and (signum == signal.SIGINT or acquiring(frame)):
                sys.setprofile(None)
                raised = True
                signal.raise_signal(signum)
    try:
        sys.setprofile(profile)
        try:
            take()
        finally:
            sys.setprofile(None)
        len(())  # a Ctrl-C held in a step comes at the next delivery point
        outcome = "ran"
    except (KeyboardInterrupt, TimeoutError):
        outcome = "raised"
    return seen, raised, outcome

bad = []
tried = 0
for take in (with_block, direct):
    points, _, _ = run(take, signal.SIGINT, 0)
    for signum in (signal.SIGINT, signal.SIGALRM):
        for k in range(1, points + 1):
            _, raised, outcome = run(take, signum, k)
            if not raised:
                continue
            tried += 1
            state = [
                outcome,
                lock.is_locked(),
                signal.getsignal(signal.SIGINT) is signal.default_int_handler,
            ]
            if state[1:] != [False, True]:
                bad.append([take.__name__, int(signum), k, state])
print(json.dumps([tried, bad]))
"""


def test_a_signal_at_every_point_of_an_acquire_leaves_neither_lock_nor_hold() -> None:
    # Before review 40: a SIGALRM handler's exception between the acquire's report
    # (the hold begun) and the lock's wait left navkit's handler in place.
    tried, bad = probe_outcome(_EVERY_POINT, timeout=300)
    assert tried >= 100
    assert bad == []
