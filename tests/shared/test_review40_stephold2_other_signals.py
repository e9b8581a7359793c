"""Other signals' handlers in the steps of numba's compiler lock: held like Ctrl-C (review 40).

While the main thread holds numba's compiler lock, ``interrupts.StepHold``
(begun by ``compile_gc``) held only ``SIGINT`` in the steps that must not be
cut short (``compile_gc._lock_steps``). A handler of another signal that raises
(a ``signal.alarm`` time-out, a service's ``SIGTERM`` handler raising
``SystemExit``) run there did what a Ctrl-C did before review 39: at the
return of the lock's own ``acquire`` inside numba's ``acquire`` it left the
compiler lock held for good (every later compile in another thread waited for
ever), and between the lock's ``release`` and the release listener it left
navkit's ``SIGINT`` handler in place after the call (STEPHOLD's finding). Every
signal whose handler is a Python callable is now held there too, and delivered
just after, once; ``SIG_IGN`` and ``SIG_DFL`` are left alone. So are they in
two steps inside the lock where navkit deferred Ctrl-C alone
(``interrupts_deferred``): numba's registry refresh and the collector's pause
as a navkit kernel's compile starts. Each probe runs in a fresh interpreter.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_EVERY_POINT = r"""
import json, signal, sys
from navkit._shared import compile_gc
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock

lock = global_compiler_lock
releasing = {_CompilerLock.release.__code__, _CompilerLock.__exit__.__code__}
calls = []

def alarm(signum, frame):  # a time-out
    calls.append(signum)
    raise TimeoutError

def term(signum, frame):  # a service's SIGTERM handler
    calls.append(signum)
    raise SystemExit(3)

signal.signal(signal.SIGALRM, alarm)
signal.signal(signal.SIGTERM, term)

def side(frame):
    # Whether the point is in the lock's letting go (release, __exit__) or before.
    while frame is not None:
        if frame.f_code in releasing:
            return "release"
        frame = frame.f_back
    return "acquire"

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
    # ``take`` with ``signum`` raised at its stop_at-th delivery point (0: none).
    seen = 0
    where = None
    def profile(frame, event, arg):
        nonlocal seen, where
        if event in ("call", "c_return"):
            seen += 1
            if seen == stop_at:
                sys.setprofile(None)
                where = side(frame)
                signal.raise_signal(signum)
    del calls[:]
    try:
        sys.setprofile(profile)
        try:
            take()
        finally:
            sys.setprofile(None)
        len(())  # a signal held in a step comes at the next delivery point
        outcome = "ran"
    except (TimeoutError, SystemExit):
        outcome = "raised"
    return seen, where, outcome

def clean_up():
    # What a bad point left, undone: the next points start as the first did.
    while lock.is_locked():
        lock._lock.release()
    hold = compile_gc._LOCK_HOLD[0]
    if hold is not None:
        hold.end()
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGALRM, alarm)
    signal.signal(signal.SIGTERM, term)

tried = {"acquire": 0, "release": 0}
bad = {"acquire": [], "release": []}
for take in (with_block, direct):
    points, _, _ = run(take, signal.SIGALRM, 0)
    for signum in (signal.SIGALRM, signal.SIGTERM):
        for k in range(1, points + 1):
            _, where, outcome = run(take, signum, k)
            if where is None:
                continue
            tried[where] += 1
            state = [
                outcome,
                calls == [signum],  # its handler ran once
                lock.is_locked(),
                signal.getsignal(signal.SIGINT) is signal.default_int_handler,
                signal.getsignal(signal.SIGALRM) is alarm,
                signal.getsignal(signal.SIGTERM) is term,
            ]
            if state != ["raised", True, False, True, True, True]:
                bad[where].append([take.__name__, int(signum), k, state])
                clean_up()
print(json.dumps([tried, bad]))
"""


@pytest.fixture(scope="module")
def every_point() -> list[dict[str, object]]:
    """A SIGALRM and a SIGTERM, their handlers raising, at every delivery point of a take."""
    return probe_outcome(_EVERY_POINT, timeout=300)  # type: ignore[no-any-return]


def test_a_raising_handler_as_numba_takes_its_lock_leaves_it_free(
    every_point: list[dict[str, object]],
) -> None:
    # Before: at the return of the lock's own acquire inside numba's acquire (the
    # lock just taken, the with block not yet entered) the exception left the
    # compiler lock held for good, and navkit's SIGINT handler in place.
    tried, bad = every_point
    assert tried["acquire"] >= 60
    assert bad["acquire"] == []


def test_a_raising_handler_as_numba_lets_go_of_its_lock_ends_the_hold(
    every_point: list[dict[str, object]],
) -> None:
    # Before: between the lock's release and the release listener's end of the
    # hold, the exception left navkit's SIGINT handler in place after the call.
    tried, bad = every_point
    assert tried["release"] >= 30
    assert bad["release"] == []


_HANDLERS_DURING = r"""
import json, signal
import numba
from navkit._shared.jit import load_numba

load_numba()

def alarm(signum, frame):
    raise TimeoutError

signal.signal(signal.SIGALRM, alarm)
signal.signal(signal.SIGUSR1, signal.SIG_IGN)
signal.signal(signal.SIGUSR2, signal.SIG_DFL)
signums = (signal.SIGINT, signal.SIGALRM, signal.SIGUSR1, signal.SIGUSR2)
before = [signal.getsignal(s) for s in signums]
during = []

def name(handler):
    holder = getattr(handler, "__self__", None)
    if type(holder).__name__ == "StepHold":  # navkit's hold: what stands behind it
        return ["held", name(holder.previous)]
    if handler is signal.default_int_handler:
        return "python"
    return "alarm" if handler is alarm else handler.name

class Watch(numba.core.event.Listener):
    def on_start(self, ev):  # a compile, the compiler lock held by the main thread
        during.append([name(signal.getsignal(s)) for s in signums])
    def on_end(self, ev):
        pass

numba.core.event.register("numba:compile", Watch())
result = numba.njit(lambda x: x + 1)(1)
after = [signal.getsignal(s) for s in signums]
print(json.dumps([during[0], after == before, result]))
"""


def test_only_signals_with_python_handlers_are_held_and_theirs_come_back() -> None:
    during, back, result = probe_outcome(_HANDLERS_DURING, timeout=300)
    # signal.getsignal shows navkit's hold in front of a Python handler, as for
    # SIGINT (and during a fork's hooks); SIG_IGN and SIG_DFL are untouched.
    assert during == [
        ["held", "python"],
        ["held", "alarm"],
        "SIG_IGN",
        "SIG_DFL",
    ]
    assert back is True
    assert result == 2


_LOAD_SAMPLES = r"""
import gc, json, signal, sys, threading
import numpy as np
import llvmlite.binding.ffi as ffi
from navkit._shared import compile_shortcuts, jit
from navkit.geometry import _integrate_kernels

jit.load_numba()
from numba.core.compiler_lock import global_compiler_lock

py_func = _integrate_kernels.rollout_kernel.py_func
twists, dts = np.array([[1.0, 0.0, 0.5]]), np.array([0.5])
calls = []

def term(signum, frame):  # a service's SIGTERM handler
    calls.append(signum)
    raise SystemExit(3)

signal.signal(signal.SIGTERM, term)

def fresh():
    # A dispatcher of navkit's kernel, as navkit makes them: its first call loads the
    # machine code from numba's cache (filled by the first of them).
    return jit._make_dispatcher(jit._NJIT, dict(jit.CACHED), py_func)

def call(dispatcher):
    out = np.empty((2, 3))
    dispatcher(0.0, 0.0, 0.0, twists, dts, out)
    return out[-1, 0]

expected = call(fresh())  # compiled, and written to the cache

in_refresh = sys.argv[2] == "deferred"

def refreshing(frame):
    # Whether numba is refreshing its registries, or navkit's hold of that (jit.py's
    # interrupts_deferred) begins or ends.
    while frame is not None:
        code = frame.f_code
        if code.co_name == "refresh" and "numba" in code.co_filename:
            return True
        if code.co_name == "interrupts_deferred" and "navkit" in code.co_filename:
            return True
        manager = frame.f_locals.get("self") if code.co_name in ("__enter__", "__exit__") else None
        if getattr(getattr(manager, "gen", None), "__name__", None) == "interrupts_deferred":
            return True
        frame = frame.f_back
    return False

def profiled(dispatcher, stop_at):
    # The call with a real SIGTERM raised at its stop_at-th delivery point (0: none)
    # of those inside numba's refresh, or of those outside it; how many there are.
    seen = 0
    def profile(frame, event, arg):
        nonlocal seen
        if event in ("call", "c_return") and refreshing(frame) == in_refresh:
            seen += 1
            if seen == stop_at:
                sys.setprofile(None)
                signal.raise_signal(signal.SIGTERM)
    del calls[:]
    sys.setprofile(profile)
    try:
        call(dispatcher)
        len(())
        outcome = "ran"
    except SystemExit:
        outcome = "stopped"
    finally:
        sys.setprofile(None)
    return seen, outcome

probe = fresh()
points, _ = profiled(probe, 0)
step = max(1, points // int(sys.argv[1]))
bad = []
for k in range(1, points + 1, step):
    dispatcher = fresh()
    _, outcome = profiled(dispatcher, k)
    state = {
        "outcome": outcome,
        "once": calls == [signal.SIGTERM],
        "compiler lock held": global_compiler_lock.is_locked(),
        "llvm lock held": bool(ffi.lib._lock._lock._is_owned()),
        "handlers back": [signal.getsignal(signal.SIGINT) is signal.default_int_handler,
                          signal.getsignal(signal.SIGTERM) is term],
        "works": bool(call(dispatcher) == expected),
    }
    if state != {
        "outcome": "stopped", "once": True, "compiler lock held": False,
        "llvm lock held": False, "handlers back": [True, True], "works": True,
    }:
        bad.append([k, state])
        while global_compiler_lock.is_locked():
            global_compiler_lock._lock.release()
        while ffi.lib._lock._lock._is_owned():
            ffi.lib._lock._lock.release()
        signal.signal(signal.SIGINT, signal.default_int_handler)
        signal.signal(signal.SIGTERM, term)
print(json.dumps([points, len(range(1, points + 1, step)), bad]))
"""


def test_a_sigterm_anywhere_in_a_kernels_cache_load_leaves_numba_working(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # As review 39's Ctrl-C test (test_review39_numbaint2_lock_step_hold.py), with a
    # SIGTERM handler raising SystemExit: the compiler lock's and llvmlite's steps are
    # held for it too (before: the LLVM lock or the compiler lock left held, the
    # handlers not back). numba's registry refresh, and navkit's deferral of Ctrl-C
    # around it, are the next test's.
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    points, samples, bad = probe_outcome(_LOAD_SAMPLES, "80", "elsewhere", timeout=600)
    assert points > 300 and samples >= 60
    assert bad == []


def test_a_sigterm_in_numbas_registry_refresh_leaves_numba_working(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # navkit's deferral of Ctrl-C around the refresh (jit._hold_refreshes, review 38)
    # holds SIGINT only: a SIGTERM handler's exception in the refresh ended numba's
    # registry readers for good ("generator raised StopIteration" at every later
    # compile), and one as the deferral ended left its SIGINT handler in place.
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    points, samples, bad = probe_outcome(_LOAD_SAMPLES, "40", "deferred", timeout=600)
    assert points > 100 and samples >= 40
    assert bad == []


_PAUSE_START = r"""
import gc, json, signal, sys
import numba
from navkit._shared import compile_gc, compile_shortcuts, jit

jit.load_numba()
from numba.core.compiler_lock import global_compiler_lock

calls = []

def term(signum, frame):  # a service's SIGTERM handler
    calls.append(signum)
    raise SystemExit(3)

signal.signal(signal.SIGTERM, term)

def small(x):
    return x + 1

small.__module__ = "navkit.probe"  # compiled as one of navkit's kernels (not cached)

def call(dispatcher):
    return dispatcher(1)

def fresh():
    return numba.njit(small)

expected = call(fresh())

def starting(frame):
    # Inside navkit's listener of a navkit kernel's compile start (the collector's
    # pause and the compile shortcuts begun, each recorded).
    while frame is not None:
        if frame.f_code.co_qualname.endswith("CompileStart.on_start"):
            return True
        frame = frame.f_back
    return False

def profiled(stop_at):
    # A SIGTERM at the stop_at-th delivery point inside the listener (0: none).
    seen = 0
    def profile(frame, event, arg):
        nonlocal seen
        if event in ("call", "c_return") and starting(frame):
            seen += 1
            if seen == stop_at:
                sys.setprofile(None)
                signal.raise_signal(signal.SIGTERM)
    del calls[:]
    sys.setprofile(profile)
    try:
        call(fresh())
        len(())
        outcome = "ran"
    except SystemExit:
        outcome = "stopped"
    finally:
        sys.setprofile(None)
    return seen

points = profiled(0)
bad = []
for k in range(1, points + 1, max(1, points // 60)):  # about 60 compiles
    profiled(k)
    state = [
        calls == [signal.SIGTERM],
        global_compiler_lock.is_locked(),
        gc.isenabled(),
        compile_shortcuts.active(),
        signal.getsignal(signal.SIGINT) is signal.default_int_handler,
        signal.getsignal(signal.SIGTERM) is term,
    ]
    if state != [True, False, True, False, True, True]:
        bad.append([k, state])
        if compile_gc._LOCK_HOLD[0] is not None:
            compile_gc._LOCK_HOLD[0].end()
        gc.enable()
        signal.signal(signal.SIGINT, signal.default_int_handler)
        signal.signal(signal.SIGTERM, term)
print(json.dumps([points, bad, bool(call(fresh()) == expected)]))
"""


def test_a_sigterm_as_a_compile_starts_leaves_no_pause_behind(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # navkit's listener of a kernel's compile start pauses the collector and turns
    # the compile shortcuts on, then records both, with Ctrl-C deferred: a SIGTERM
    # handler's exception in between left the collector off for good.
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    points, bad, works = probe_outcome(_PAUSE_START, timeout=300)
    assert points >= 10
    assert bad == []
    assert works is True


_TWO_AT_ONCE = r"""
import json, signal, sys
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock

lock = global_compiler_lock
calls = []

def note(signum, frame):
    calls.append([signum, lock.is_locked()])

def raising(signum, frame):
    calls.append([signum, lock.is_locked()])
    raise TimeoutError

def take():
    with lock:
        calls.append("body")

def run(handler):
    # A SIGTERM, then a SIGALRM (lower), then a second SIGTERM, all at the return of
    # the lock's own acquire inside numba's (a step: every one held).
    signal.signal(signal.SIGALRM, handler)
    signal.signal(signal.SIGTERM, handler)
    del calls[:]
    def profile(frame, event, arg):
        if (
            event == "c_return"
            and frame.f_code is _CompilerLock.acquire.__code__
            and lock.is_locked()
        ):
            sys.setprofile(None)
            for signum in (signal.SIGTERM, signal.SIGALRM, signal.SIGTERM):
                signal.raise_signal(signum)
    raised = 0
    try:
        sys.setprofile(profile)
        try:
            take()
        finally:
            sys.setprofile(None)
    except TimeoutError:
        raised += 1
    for _ in range(3):  # the second, if the first raised, at one of these points
        try:
            len(())
        except TimeoutError:
            raised += 1
    return [raised, calls[:], lock.is_locked()]

print(json.dumps([run(note), run(raising)]))
"""


def test_signals_held_together_come_once_each_in_signal_order() -> None:
    noted, raised = probe_outcome(_TWO_AT_ONCE, timeout=300)
    # Held in the step: the handlers run after it (the with block entered first),
    # SIGALRM (14) before SIGTERM (15), a second SIGTERM folded into the first.
    assert noted == [0, ["body", [14, True], [15, True]], False]
    # Raising: SIGALRM's handler first, SIGTERM's at a later point, once each, the
    # lock let go. (SIGTERM's exception, raised as the with block lets go of the
    # lock for SIGALRM's, takes that one's place, as two signals arriving there
    # would: one exception or two reach the caller.)
    count, calls, held = raised
    assert count in (1, 2) and held is False
    assert [call[0] for call in calls if call != "body"] == [14, 15]


_EXIT_STACK_POP = r"""
import contextlib, json, signal, sys
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import global_compiler_lock

calls = []

def term(signum, frame):
    calls.append(signum)
    raise SystemExit(3)

signal.signal(signal.SIGTERM, term)
exit_code = contextlib.ExitStack.__exit__.__code__

def run(signum):
    # A compile, with ``signum`` raised as numba's dispatcher's ExitStack has just
    # popped the compiler lock's exit callback (the lock's ``__exit__`` next).
    fired = []
    def profile(frame, event, arg):
        if (
            event == "c_return"
            and frame.f_code is exit_code
            and getattr(arg, "__name__", None) == "pop"
            and frame.f_back.f_code.co_name == "compile"
            and global_compiler_lock.is_locked()
            and not fired
        ):
            fired.append(True)
            sys.setprofile(None)
            signal.raise_signal(signum)
    del calls[:]
    sys.setprofile(profile)
    try:
        numba.njit(lambda x: x + signum)(1)
        len(())
        outcome = "ran"
    except (KeyboardInterrupt, SystemExit) as error:
        outcome = type(error).__name__
    finally:
        sys.setprofile(None)
    held = global_compiler_lock.is_locked()
    while global_compiler_lock.is_locked():
        global_compiler_lock._lock.release()
    return [bool(fired), outcome, held]

print(json.dumps([run(signal.SIGINT), run(signal.SIGTERM), calls]))
"""


def test_a_signal_as_numbas_exit_stack_pops_the_locks_exit_leaves_it_free() -> None:
    # Between ExitStack.__exit__'s pop of the compiler lock's exit callback and its
    # call, the callback is in neither the stack nor the frame's ``cb``: the step
    # test did not see it, and a Ctrl-C or a SIGTERM handler's exception there left
    # numba's compiler lock held for good (found at one of ~4500 points of a cache
    # load, sampled).
    ctrl_c, sigterm, calls = probe_outcome(_EXIT_STACK_POP, timeout=300)
    assert ctrl_c == [True, "KeyboardInterrupt", False]
    assert sigterm == [True, "SystemExit", False]
    assert calls == [15]
