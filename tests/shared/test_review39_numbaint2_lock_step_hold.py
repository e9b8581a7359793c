"""Ctrl-C during numba's use of its locks: held in the locks' steps only (review 39, NUMBAINT2).

While the main thread holds numba's compiler lock, navkit's handler
(``navkit._shared.interrupts.StepHold``, begun by ``navkit._shared.compile_gc``)
holds a Ctrl-C back only inside the steps that must not be cut short (the
compiler lock's and the LLVM lock's own methods, llvmlite's object-cache
callbacks) and delivers it at the next delivery point after. Review 38's three
tests pin one point each; here a kernel's load from numba's cache is
interrupted at sampled delivery points, a Ctrl-C elsewhere in a compile still
stops it at once, and the handler is back (or never changed) afterwards.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

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

def fresh():
    # A dispatcher of navkit's kernel, as navkit makes them: its first call loads the
    # machine code from numba's cache (filled by the first of them).
    return jit._make_dispatcher(jit._NJIT, dict(jit.CACHED), py_func)

def call(dispatcher):
    out = np.empty((2, 3))
    dispatcher(0.0, 0.0, 0.0, twists, dts, out)
    return out[-1, 0]

expected = call(fresh())  # compiled, and written to the cache

def profiled(dispatcher, stop_at):
    # The call with a real SIGINT raised at its stop_at-th delivery point (0: none),
    # through whatever handler is in place then; how many points it passed.
    seen = 0
    def profile(frame, event, arg):
        nonlocal seen
        if event in ("call", "c_return"):
            seen += 1
            if seen == stop_at:
                sys.setprofile(None)
                signal.raise_signal(signal.SIGINT)
    sys.setprofile(profile)
    try:
        call(dispatcher)
        outcome = "ran"
    except KeyboardInterrupt:
        outcome = "interrupted"
    finally:
        sys.setprofile(None)
    return seen, outcome

probe = fresh()
points, _ = profiled(probe, 0)
loaded = probe.stats.cache_hits
step = max(1, points // int(sys.argv[1]))
bad = []
for k in range(1, points + 1, step):
    dispatcher = fresh()
    _, outcome = profiled(dispatcher, k)
    state = {
        "outcome": outcome,
        "compiler lock held": global_compiler_lock.is_locked(),
        "llvm lock held": bool(ffi.lib._lock._lock._is_owned()),
        "collector on": gc.isenabled(),
        "shortcuts on": compile_shortcuts.active(),
        "handler back": signal.getsignal(signal.SIGINT) is signal.default_int_handler,
        "works": bool(call(dispatcher) == expected),
    }
    if state != {
        "outcome": "interrupted", "compiler lock held": False, "llvm lock held": False,
        "collector on": True, "shortcuts on": False, "handler back": True, "works": True,
    }:
        bad.append([k, state])

# Another thread can take both locks (none is left held by the main thread).
free = []
def take():
    for lock in (global_compiler_lock._lock, ffi.lib._lock._lock):
        if lock.acquire(timeout=10):
            lock.release()
            free.append(True)
thread = threading.Thread(target=take)
thread.start()
thread.join(60)
print(json.dumps([points, sum(loaded.values()), len(range(1, points + 1, step)), bad, free]))
"""


def test_a_ctrl_c_anywhere_in_a_kernels_cache_load_leaves_numba_working(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Before the fix: the compiler lock or the LLVM lock left held at some points,
    # and a Ctrl-C in the object-cache callback crashed the process (SIGSEGV).
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    points, hits, samples, bad, free = probe_outcome(_LOAD_SAMPLES, "150", timeout=600)
    assert hits == 1  # the probe's dispatcher loaded from the cache
    assert points > 300 and samples >= 100
    assert bad == []
    assert free == [True, True]


_MID_COMPILE = r"""
import gc, json, signal, sys, traceback
import numpy as np
from navkit._shared.jit import load_numba
from navkit.geometry import rollout
from numba.core.compiler_lock import global_compiler_lock
from numba.core.typeinfer import TypeInferer

load_numba()
held = []

def profile(frame, event, arg):
    # A Ctrl-C as numba's type inference runs, in a cold compile: no lock step.
    if event == "call" and frame.f_code is TypeInferer.propagate.__code__:
        handler = signal.getsignal(signal.SIGINT)
        held.append(type(getattr(handler, "__self__", None)).__name__)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)
    where = None
except KeyboardInterrupt:
    where = [f.name for f in traceback.extract_tb(sys.exc_info()[2])]
finally:
    sys.setprofile(None)
after = [
    global_compiler_lock.is_locked(),
    gc.isenabled(),
    signal.getsignal(signal.SIGINT) is signal.default_int_handler,
]
again = rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)[-1, 0].item()
print(json.dumps([held, where, after, round(again, 9)]))
"""


def test_a_ctrl_c_elsewhere_in_a_compile_stops_it_at_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    held, where, after, again = probe_outcome(_MID_COMPILE, timeout=300)
    assert held == ["StepHold"]  # navkit's handler was in place (the lock held)
    # Raised there and then (inside type inference), not held to the compile's end.
    assert where is not None and "propagate" in where
    assert after == [False, True, True]
    assert again == pytest.approx(0.494807918509, abs=1e-9)


_HANDLERS = r"""
import json, signal, threading
import numba
import numpy as np
from navkit._shared.jit import load_numba

load_numba()
seen = {}

class Watch(numba.core.event.Listener):
    def on_start(self, ev):
        holder = getattr(signal.getsignal(signal.SIGINT), "__self__", None)
        name = "StepHold" if type(holder).__name__ == "StepHold" else "other"
        seen.setdefault(threading.current_thread().name, []).append(name)
    def on_end(self, ev):
        pass

numba.core.event.register("numba:compile", Watch())

def compile_one(offset):
    @numba.njit
    def kernel(x):
        return x + offset
    return kernel(1)

calls = []
def note(signum, frame):  # a program's handler that only notes the Ctrl-C
    calls.append(signum)

results = {}
handlers = (("ignored", signal.SIG_IGN), ("noted", note), ("python", signal.default_int_handler))
for offset, (name, handler) in enumerate(handlers):
    signal.signal(signal.SIGINT, handler)
    results[name] = compile_one(offset)
    results[name + " back"] = signal.getsignal(signal.SIGINT) == handler
signal.signal(signal.SIGINT, note)
# A Ctrl-C during a compile goes to a handler that does not raise: noted once, compile done.
@numba.njit
def kernel(x):
    return x * 3
class Fire(numba.core.event.Listener):
    def on_start(self, ev):
        signal.raise_signal(signal.SIGINT)
    def on_end(self, ev):
        pass
fire = Fire()
numba.core.event.register("numba:compile", fire)
results["noted mid-compile"] = kernel(2)
numba.core.event.unregister("numba:compile", fire)
results["noted back"] = signal.getsignal(signal.SIGINT) is note
signal.signal(signal.SIGINT, signal.default_int_handler)
def in_thread():
    results["thread"] = compile_one(10)
thread = threading.Thread(target=in_thread, name="worker")
thread.start()
thread.join()
print(json.dumps([seen, results, len(calls)]))
"""


def test_the_hold_is_only_where_a_ctrl_c_could_raise_in_the_main_thread() -> None:
    seen, results, noted = probe_outcome(_HANDLERS, timeout=300)
    # Nothing for SIG_IGN, a worker thread (no signal lands there); navkit's hold in
    # front of a Python handler, put back after.
    assert seen["worker"] == ["other"]
    assert seen["MainThread"] == ["other", "StepHold", "StepHold", "StepHold"]
    assert results == {
        "ignored": 1, "ignored back": True, "noted": 2, "noted back": True,
        "python": 3, "python back": True, "noted mid-compile": 6, "thread": 11,
    }  # fmt: skip
    assert noted == 1


_AFTER_IGNORED = r"""
import json, signal, threading
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core.compiler_lock import global_compiler_lock

seen = []

class Watch(numba.core.event.Listener):
    def on_start(self, ev):
        holder = getattr(signal.getsignal(signal.SIGINT), "__self__", None)
        seen.append(type(holder).__name__ == "StepHold")
    def on_end(self, ev):
        pass

numba.core.event.register("numba:compile", Watch())
# Ctrl-C ignored while a wait for the lock ends in an exception (no release comes).
signal.signal(signal.SIGINT, signal.SIG_IGN)
real = global_compiler_lock._lock

class Failing:
    def acquire(self, *args):
        raise OSError("the wait failed")
    def __getattr__(self, name):
        return getattr(real, name)

global_compiler_lock._lock = Failing()
try:
    with global_compiler_lock:
        pass
except OSError:
    pass
finally:
    global_compiler_lock._lock = real
signal.signal(signal.SIGINT, signal.default_int_handler)

@numba.njit
def kernel(x):
    return x + 1

print(json.dumps([kernel(1), seen]))
"""


def test_a_lock_taken_with_ctrl_c_ignored_leaves_the_next_compile_held() -> None:
    # Nothing was put in place then, and no release came to say so: the next
    # compile, with Python's handler back, was left without the hold.
    result, seen = probe_outcome(_AFTER_IGNORED, timeout=300)
    assert result == 2
    assert seen == [True]
