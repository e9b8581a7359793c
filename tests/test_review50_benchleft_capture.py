"""``benchmarks/compare_peers.py`` honours a benchmark's ``pedantic(setup=...)`` (review 50).

Its ``Capture`` stood in for pytest-benchmark's fixture but dropped ``setup=``:
a benchmark giving every round new arguments (``test_bench_astar.timed_fresh``:
new points, scans, maps, each round's answer checked in the next round's setup)
was timed on its first arguments over and over, so a call caching on its input
reported the cache's speed and one wrong after its first call was never
checked. These tests run its machinery (``captured``, ``calibrate``,
``measure``, ``run_workload``) on small fakes, in this process.
"""

from __future__ import annotations

import itertools
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


@pytest.fixture(scope="module")
def peers() -> Iterator[ModuleType]:
    if not (BENCHMARKS / "compare_peers.py").is_file():
        pytest.skip("benchmarks/ is not part of this installation")
    pytest.importorskip("pytest_benchmark")
    sys.path.insert(0, str(BENCHMARKS))
    try:
        import compare_peers

        yield compare_peers
    finally:
        sys.path.remove(str(BENCHMARKS))


def fresh_rounds(answer: Callable[[int], int], seen: list[int]) -> Callable[[Any], int]:
    """A benchmark test in ``timed_fresh``'s pattern: round k's argument is k (new every
    round), ``answer(k)`` is what the timed call returns, the check wants ``k * k``."""

    def test(benchmark: Any) -> int:
        numbers = itertools.count()

        def check(args: tuple[Any, ...], found: int) -> None:
            assert found == args[0] * args[0], f"round {args[0]}: {found}"

        def run(k: int) -> int:
            seen.append(k)
            return answer(k)

        from test_bench_astar import timed_fresh

        return int(timed_fresh(benchmark, run, lambda: (next(numbers),), check, 5))

    return test


def test_every_timed_call_gets_new_arguments_and_every_answer_is_checked(
    peers: ModuleType,
) -> None:
    seen: list[int] = []
    call, first, first_s = peers.captured(fresh_rounds(lambda k: k * k, seen))
    assert isinstance(call, peers.Staged)
    assert (first, seen) == (0, [0]) and first_s > 0.0
    timer = peers.calibrate(call)
    peers.measure([timer])
    timer.finish()
    assert not timer.failed and timer.samples
    # Each call had an argument of its own: an answer kept for one could not stand in.
    assert seen == list(range(len(seen))) and len(seen) > 2


def test_an_answer_wrong_under_the_timer_is_a_mismatch(peers: ModuleType) -> None:
    # Right on its first call, then that answer again: what a call caching its first
    # answer returns.
    seen: list[int] = []
    call, first, _ = peers.captured(fresh_rounds(lambda k: 0, seen))
    assert first == 0
    timer = peers.calibrate(call)
    peers.measure([timer])
    timer.finish()
    assert timer.failed.startswith("round 1: 0")


def test_a_workload_with_a_wrong_timed_answer_fails_its_row(peers: ModuleType) -> None:
    def make(answer: Callable[[int], int]) -> Callable[[], Any]:
        return lambda: peers.captured(fresh_rounds(answer, []))

    work = peers.Workload(
        "fake",
        "k squared",
        peers.Contestant("navkit", make(lambda k: k * k)),
        (
            peers.Contestant("honest", make(lambda k: k * k), None, lambda a, b: "same"),
            peers.Contestant("stale", make(lambda k: 0), None, lambda a, b: "same"),
        ),
    )
    honest, stale = peers.run_workload(work, lambda _text: None)
    assert honest.status == "" and honest.ratio is not None
    assert stale.status == "MISMATCH" and stale.ratio is None
    assert stale.check.startswith("under the timer: round 1: 0")


def test_the_last_timed_answer_is_checked_too(peers: ModuleType) -> None:
    # Wrong from the third call on (k = 2): the last timed call's answer is checked by
    # finish() alone, the setup no call follows.
    call, _, _ = peers.captured(fresh_rounds(lambda k: k * k if k < 2 else -1, []))
    call.timed(1)  # round 1: right
    call.timed(1)  # its setup checks round 1; round 2 answers -1, not yet checked
    timer = peers.Timer(call)
    timer.finish()
    assert timer.failed.startswith("round 2: -1")


def test_setup_with_arguments_is_refused(peers: ModuleType) -> None:
    capture = peers.Capture()
    with pytest.raises(TypeError, match="setup= cannot be combined"):
        capture.pedantic(lambda k: k, args=(1,), setup=lambda: ((2,), {}))


def test_a_plain_call_and_a_setup_returning_none_still_work(peers: ModuleType) -> None:
    capture = peers.Capture()
    assert capture(lambda a, b=0: a + b, 2, b=3) == 5
    assert not isinstance(capture.call, peers.Staged) and capture.call() == 5
    ticks: list[int] = []
    assert capture.pedantic(lambda: len(ticks), setup=lambda: ticks.append(1)) == 1
    assert isinstance(capture.call, peers.Staged)
    capture.call.timed(3)
    assert len(ticks) == 4


def test_times_are_per_input_when_a_round_times_several(
    peers: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    def test(benchmark: Any) -> Any:
        benchmark.extra_info["calls_per_round"] = 4
        return benchmark.pedantic(lambda xs: [x + 1 for x in xs], setup=lambda: (([1] * 4,), {}))

    ticks = itertools.count()
    # A clock that advances one second a reading: every call lasts exactly 1 s.
    monkeypatch.setattr(peers.time, "perf_counter", lambda: float(next(ticks)))
    call, first, first_s = peers.captured(test)
    assert first == [2, 2, 2, 2] and call.per == 4 and first_s == 0.25
    assert call.timed(10) == 2.5  # ten rounds of 1 s, four inputs each


def test_several_calls_a_round_without_a_setup_is_refused(peers: ModuleType) -> None:
    def test(benchmark: Any) -> Any:
        benchmark.extra_info["calls_per_round"] = 4
        return benchmark(lambda: 1)

    with pytest.raises(ValueError, match="calls_per_round without a setup"):
        peers.captured(test)
