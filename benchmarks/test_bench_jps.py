"""Jump point search on MovingAI maps against pyastar2d, in the same run.

Run with ``python -m pytest benchmarks/test_bench_jps.py --benchmark-only``.

Maps: ``../shared/data/movingai-grid-benchmarks`` (N. Sturtevant, "Benchmarks
for Grid-Based Pathfinding", IEEE TCIAIG 4(2), 2012): game maps (dao), mazes
of corridor width 1 and 32, rooms and city streets. Skipped when the data is
absent. Each round answers 20 problems of the map's scenario file, spread
evenly over its lengths (every 1/20th of the problems sorted by their published
optimum; the first, checked before the timing, has the longest), and every
round other ones (:func:`queries`): no start/goal pair is asked twice, so a
path kept for an earlier query cannot stand in for a search. Every timed
round's answers are checked, outside the timer.

Contestants:

* navkit JPS through a prepared :class:`AStarPlanner` (``method="jps"``, its
  bit tables built once per map), and one-shot ``astar(..., method="jps")``,
  which validates the grid and builds the tables on every call;
* navkit A* (prepared, no corner cutting), the MovingAI graph;
* ``pyastar2d`` (C++ A*, 8-connected, diagonal steps cost 1 and cut corners,
  so it searches an easier graph than the MovingAI one).

Before any timing, every navkit answer is checked against the published
optimum and every pyastar2d path for validity on its own graph. ``test_ratio``
times JPS (prepared and one-shot) and pyastar2d alternately in one loop (the
order reversed every other round), each with this thread's CPU time, checks
every round's answers the same way, and reports the median of the per-round
ratios (``speedup_*`` in ``extra_info``), which holds on a loaded machine
where absolute times do not.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable
from functools import cache
from typing import Any, NamedTuple

import numpy as np
import pytest

from navkit.planning import AStarPlanner, astar
from test_bench_astar import peer, shared_data, timed_fresh

try:
    import pyastar2d
except ImportError:  # a peer from the bench extra: its tests skip (peer())
    pyastar2d = None

DATA = "movingai-grid-benchmarks"
MAPS = [
    "dao/arena2",
    "dao/den011d",
    "maze/maze512-1-0",
    "maze/maze512-32-9",
    "room/8room_000",
    "street/Berlin_0_512",
    "street/Berlin_0_1024",
]
QUERIES = 20
ROUNDS = 7  # test_ratio's
GROUP_ROUNDS = 20  # the JPS groups' (A* prepared and pyastar2d: 3)
# test_ratio's rounds of queries() start here, after those the groups' tests time
# (round 0 untimed, then a warm-up and GROUP_ROUNDS): a search keeping its answers
# from one test to the next finds none of its problems answered either. The
# smallest scenario file (den011d, 750 problems) has 37 rounds.
RATIO_ROUNDS = GROUP_ROUNDS + 2


class Problem(NamedTuple):
    start: tuple[int, int]
    goal: tuple[int, int]
    optimal: float


@cache
def load(name: str) -> tuple[np.ndarray, tuple[Problem, ...]]:
    """Cost grid (1 passable, inf blocked, read-only) and every problem of map ``name``'s
    scenario file, the longest first."""
    base = shared_data(f"{DATA}/{name}.map").with_suffix("")
    lines = base.with_name(base.name + ".map").read_text(encoding="ascii").splitlines()
    body = lines[lines.index("map") + 1 :]
    grid = np.array([list(row) for row in body if row])
    costs = np.where(np.isin(grid, [".", "G", "S"]), 1.0, np.inf)
    costs.flags.writeable = False
    problems = []
    scenarios = base.with_name(base.name + ".map.scen").read_text(encoding="ascii")
    for line in scenarios.splitlines()[1:]:
        fields = line.split("\t")
        if len(fields) < 9:
            continue
        sx, sy, gx, gy = (int(v) for v in fields[4:8])
        problems.append(Problem((sy, sx), (gy, gx), float(fields[8])))
    problems.sort(key=lambda p: -p.optimal)
    return costs, tuple(problems)


@cache
def queries(name: str, round_: int = 0) -> tuple[Problem, ...]:
    """Round ``round_``'s ``QUERIES`` problems of map ``name``, spread evenly over its lengths.

    The problems sorted by their published optimum fall into ``QUERIES`` runs of
    ``step`` (every 1/20th); round ``k`` takes the ``k``-th of each run (round 0
    the longest problem of all). No start/goal pair comes back in a later round,
    so an answer kept for an earlier query (a cache keyed on start and goal, or
    on the map's array, which the rounds share: a copy per query would cost
    160 MB on Berlin_0_1024) cannot stand in for a search.
    """
    problems = load(name)[1]
    step = max(1, len(problems) // QUERIES)
    if round_ >= step:
        raise ValueError(f"{name}: round {round_} would repeat problems ({step} rounds at most)")
    return problems[round_::step][:QUERIES]


def timed_rounds(
    benchmark: Any,
    name: str,
    run: Callable[[tuple[Problem, ...]], list[Any]],
    check: Callable[[list[Any], tuple[Problem, ...]], None],
    rounds: int,
) -> None:
    """:func:`timed_fresh` of ``run(problems)``: round ``k`` (the warm-up first) on
    :func:`queries` ``(name, k)``, ``k = 1, 2, ...`` (round 0's were answered before
    the timing), every round's answers checked outside the timer."""
    numbers = itertools.count(1)
    timed_fresh(
        benchmark,
        run,
        lambda: (queries(name, next(numbers)),),
        lambda args, answers: check(answers, args[0]),
        rounds,
    )


def run_planner(planner: AStarPlanner, problems: tuple[Problem, ...]) -> list[float]:
    return [planner.plan(p.start, p.goal).length for p in problems]


def run_one_shot(costs: np.ndarray, problems: tuple[Problem, ...]) -> list[float]:
    return [astar(costs, p.start, p.goal, method="jps").length for p in problems]


def run_pyastar2d(weights: np.ndarray, problems: tuple[Problem, ...]) -> list[Any]:
    return [pyastar2d.astar_path(weights, p.start, p.goal, allow_diagonal=True) for p in problems]


def check_optimal(lengths: list[float], problems: tuple[Problem, ...]) -> None:
    for length, p in zip(lengths, problems, strict=True):
        assert length == pytest.approx(p.optimal, rel=1e-6, abs=1e-6), p


def check_pyastar2d(costs: np.ndarray, paths: list[Any], problems: tuple[Problem, ...]) -> None:
    """pyastar2d's paths: found, and valid on its graph (8-connected, corners cut)."""
    from test_bench_movingai import assert_valid_path

    for path, p in zip(paths, problems, strict=True):
        assert path is not None, p
        assert_valid_path(costs, path, p.start, p.goal, corner_cutting=True)


@pytest.mark.parametrize("name", MAPS)
def test_jps_prepared(benchmark: Any, name: str) -> None:
    costs, problems = load(name)[0], queries(name)
    planner = AStarPlanner(costs, method="jps")
    check_optimal(run_planner(planner, problems), problems)
    benchmark.group = name
    timed_rounds(benchmark, name, lambda q: run_planner(planner, q), check_optimal, GROUP_ROUNDS)
    benchmark.extra_info["expanded"] = sum(planner.plan(p.start, p.goal).expanded for p in problems)


@pytest.mark.parametrize("name", MAPS)
def test_jps_one_shot(benchmark: Any, name: str) -> None:
    costs, problems = load(name)[0], queries(name)
    check_optimal(run_one_shot(costs, problems), problems)
    benchmark.group = name
    timed_rounds(benchmark, name, lambda q: run_one_shot(costs, q), check_optimal, GROUP_ROUNDS)


@pytest.mark.parametrize("name", MAPS)
def test_astar_prepared(benchmark: Any, name: str) -> None:
    costs, problems = load(name)[0], queries(name)
    planner = AStarPlanner(costs)
    check_optimal(run_planner(planner, problems), problems)
    benchmark.group = name
    timed_rounds(benchmark, name, lambda q: run_planner(planner, q), check_optimal, 3)
    benchmark.extra_info["expanded"] = sum(planner.plan(p.start, p.goal).expanded for p in problems)


@pytest.mark.parametrize("name", MAPS)
def test_pyastar2d(benchmark: Any, name: str) -> None:
    peer("pyastar2d")
    costs, problems = load(name)[0], queries(name)
    weights = np.where(np.isfinite(costs), 1.0, np.inf).astype(np.float32)
    check_pyastar2d(costs, run_pyastar2d(weights, problems), problems)
    benchmark.group = name
    timed_rounds(
        benchmark,
        name,
        lambda q: run_pyastar2d(weights, q),
        lambda paths, q: check_pyastar2d(costs, paths, q),
        3,
    )


@pytest.mark.parametrize("name", MAPS)
def test_ratio(benchmark: Any, name: str) -> None:
    """JPS and pyastar2d alternately, ``ROUNDS`` times: median per-round speed-ups.

    Each round runs the three contestants on ``QUERIES`` problems of the map (new
    ones every round, none of those the other tests time: :data:`RATIO_ROUNDS`),
    the order reversed every other round, and times each with this thread's
    CPU time (``time.thread_time()``), as the other ratio benchmarks do, so
    machine load and the other threads affect every side alike. Every round's
    answers are checked (outside the timers): a contestant that went wrong
    under the timing fails the test instead of reporting a speed-up.
    """
    peer("pyastar2d")
    costs, problems = load(name)[0], queries(name)
    weights = np.where(np.isfinite(costs), 1.0, np.inf).astype(np.float32)
    planner = AStarPlanner(costs, method="jps")
    check_optimal(run_planner(planner, problems), problems)
    check_optimal(run_one_shot(costs, problems), problems)
    check_pyastar2d(costs, run_pyastar2d(weights, problems), problems)

    def rounds() -> dict[str, float]:
        times: dict[str, list[float]] = {"prepared": [], "one_shot": [], "pyastar2d": []}
        sides: dict[str, Callable[[tuple[Problem, ...]], list[Any]]] = {
            "pyastar2d": lambda q: run_pyastar2d(weights, q),
            "prepared": lambda q: run_planner(planner, q),
            "one_shot": lambda q: run_one_shot(costs, q),
        }
        for i in range(ROUNDS):
            problems = queries(name, RATIO_ROUNDS + i)
            answers = {}
            for key in sides if i % 2 == 0 else list(sides)[::-1]:
                t0 = time.thread_time()
                answers[key] = sides[key](problems)
                times[key].append(time.thread_time() - t0)
            check_optimal(answers["prepared"], problems)
            check_optimal(answers["one_shot"], problems)
            check_pyastar2d(costs, answers["pyastar2d"], problems)
        peer = np.array(times["pyastar2d"])
        return {
            "speedup_prepared": float(np.median(peer / np.array(times["prepared"]))),
            "speedup_one_shot": float(np.median(peer / np.array(times["one_shot"]))),
            "pyastar2d_ms_per_query": float(np.median(peer)) * 1e3 / QUERIES,
        }

    benchmark.group = f"{name} ratio"
    result = benchmark.pedantic(rounds, rounds=1, iterations=1)
    benchmark.extra_info.update(result)
