"""The fuzz watchdog does not count numba's compile time as the call's (review 39, FLAKY).

A hostile value can take a call down a branch, or to a dtype, whose kernel no earlier
call compiled: with a cold numba cache, ``ExtendedKalmanFilter.predict`` with NaN in
``Q`` compiled three kernels in 4.6 s of wall-clock time on a loaded 2-core machine,
inside the 10 s (``CALL_TIMEOUT_S``) that the watchdog allows a call before it counts
as a hang (the first valid call of a spec gets 600 s; this is a later one). While a
thread holds numba's compiler lock, the bound is ``COMPILE_TIMEOUT_S``, and the call's
own seconds start again when numba lets go of it. Time outside the compile still
counts: a call that hangs after a compile is still a hang. Since review 45 the bound
is CPU time, with a wall-clock backstop for a call that waits: numba's time counts
towards neither.
"""

from __future__ import annotations

import signal
import time
from collections.abc import Callable

import fuzz_engine
import pytest
from fuzz_engine import Hang, watchdog

from navkit._shared.jit import load_numba

pytestmark = pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="needs setitimer")

#: The watchdog's bounds in these tests (s of CPU time, and of wall-clock time): well
#: above a loaded machine's pauses between numba letting go of its lock and the block's end.
SHORT = 1.0
#: The watchdog's CPU and wall-clock timers (getattr: Windows has none, the tests skip).
_TIMERS = tuple(getattr(signal, name, -1) for name in ("ITIMER_PROF", "ITIMER_REAL"))


def _compute(cpu_s: float) -> None:
    """Run Python code until the process has used ``cpu_s`` more seconds of CPU time."""
    end = time.process_time() + cpu_s
    while time.process_time() < end:
        pass


#: Ways a block runs past both of the watchdog's bounds: computing, or waiting.
_PAST: dict[str, Callable[[float], None]] = {"computing": _compute, "waiting": time.sleep}


def _fresh_kernel() -> object:
    """A kernel no call has compiled yet (a new function each time, cache off)."""
    load_numba()
    import numba

    def total(n: int) -> float:
        s = 0.0
        for i in range(n):
            s += (i * 7) % 5 - 0.5
        return s

    return numba.njit(cache=False)(total)


def test_a_real_compile_runs_under_the_compile_bound() -> None:
    from numba.core import event

    kernel = _fresh_kernel()
    left: list[float] = []

    class During(event.Listener):  # type: ignore[misc]
        def on_start(self, _event: object) -> None:
            left.extend(signal.getitimer(which)[0] for which in _TIMERS)

        def on_end(self, _event: object) -> None:
            pass

    with event.install_listener("numba:compile", During()), watchdog(30.0, wall=40.0):
        assert kernel(10) == sum((i * 7) % 5 - 0.5 for i in range(10))  # type: ignore[operator]
        cpu, wall = (signal.getitimer(which)[0] for which in _TIMERS)
    assert len(left) == 2 and min(left) > 40.0  # the compile's bound, not the call's
    # The call's own bounds again (a CPU timer reads back in ticks: 30.004).
    assert 0.0 < cpu <= 30.05 < wall <= 40.0
    assert [signal.getitimer(which) for which in _TIMERS] == [(0.0, 0.0)] * 2  # none left set


def test_numba_holding_its_lock_longer_than_the_bound_is_not_a_hang() -> None:
    load_numba()
    from numba.core.compiler_lock import global_compiler_lock

    started = time.perf_counter()
    cpu = time.process_time()
    with watchdog(SHORT, wall=SHORT), global_compiler_lock:  # as a compile or a cache load does
        _compute(1.5 * SHORT)
        time.sleep(1.5 * SHORT)
    assert time.perf_counter() - started >= 3 * SHORT
    assert time.process_time() - cpu >= 1.5 * SHORT


@pytest.mark.parametrize("how", list(_PAST))
def test_the_calls_own_time_after_numbas_still_counts(how: str) -> None:
    load_numba()
    from numba.core.compiler_lock import global_compiler_lock

    with pytest.raises(Hang), watchdog(SHORT, wall=SHORT):
        with global_compiler_lock:
            time.sleep(SHORT / 10)
        _PAST[how](30 * SHORT)  # a hang after the compile
    assert [signal.getitimer(which) for which in _TIMERS] == [(0.0, 0.0)] * 2


@pytest.mark.parametrize("how", list(_PAST))
def test_a_call_without_a_compile_still_hangs_at_the_bound(how: str) -> None:
    load_numba()
    with pytest.raises(Hang), watchdog(SHORT, wall=SHORT):
        _PAST[how](30 * SHORT)


def test_the_compile_bound_is_generous_but_finite() -> None:
    bound = getattr(fuzz_engine, "COMPILE_TIMEOUT_S", None)
    assert bound is not None and 60.0 <= bound < float("inf")


def test_a_listener_call_still_under_way_as_the_block_ends_sets_no_timer() -> None:
    # Another thread's compile reports its end as the watchdog's block ends: its
    # on_end, run after the watchdog cleared the timer, set it again (a SIGALRM
    # then met the handler put back: by default, the end of the process).
    load_numba()
    from numba.core import event

    with watchdog(30 * SHORT):
        listener = event._registered["numba:compiler_lock"][-1]
        listener.on_start(None)  # that thread takes numba's lock
    try:
        listener.on_end(None)  # and lets go of it after the block
        assert [signal.getitimer(which) for which in _TIMERS] == [(0.0, 0.0)] * 2
    finally:
        for which in _TIMERS:
            signal.setitimer(which, 0)
