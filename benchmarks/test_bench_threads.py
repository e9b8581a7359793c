"""navkit's long kernels beside other threads: callback latency and two planners at once.

Run with ``python -m pytest benchmarks/test_bench_threads.py --benchmark-only``,
or ``python benchmarks/test_bench_threads.py`` for the figures alone (also
against another checkout: ``PYTHONPATH=/other/src python benchmarks/...``).

The long kernels release the GIL (``navkit._shared.jit.RELEASES_GIL``):

* ``latency``: a 200 Hz callback thread (a ``PlanarFusion.update_yaw_rate``
  per tick, as an IMU subscription) runs 3 s while another thread plans with
  Field D* on an 800 x 800 grid over and over (about 0.2 s a plan), as a ROS 2
  timer callback in a ``MultiThreadedExecutor``. Recorded: the worst and the
  99th-percentile lateness of a tick (its call's start after its scheduled
  time), and their ratios to the same callback run with no plan (in
  ``extra_info``). With the GIL held by the plan the worst lateness is about
  a plan's length. The two runs alternate, ``LATENESS_ROUNDS`` = 3 times each
  (the order reversed every other round); the ratios are the medians of the
  per-round ratios, each over ``SECONDS`` of ticks, and every busy round must
  have finished a plan, of the right cost.
* ``throughput``: A* plans on two 1000 x 1000 maps, each map's plans in a
  thread of its own, against the same plans one after another in one thread,
  alternately, ``SPEEDUP_ROUNDS`` = 5 times each; ``extra_info["speedup"]`` is
  the median per-round serial time over the threaded one (2 at best on 2 free
  cores, 1 when the kernels hold the GIL), ``cpu_per_s`` the process's CPU
  seconds per second while the threads plan (likewise, median). Every plan's
  cost is checked against the first plan of its map.

Both figures are wall-clock by nature (lateness; the gain of a second thread),
so they are not this thread's CPU time as in the other ratio benchmarks; the
alternation makes the machine's load fall on both sides alike. Compare ratios
from one run, alternating runs of the versions compared.
"""

from __future__ import annotations

import statistics
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import PlanarFusion
from navkit.planning import AStarPlanner, FieldDStar

TICK = 0.005  # 200 Hz
SECONDS = 3.0


def _costs(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = rng.uniform(1.0, 3.0, (n, n))
    costs[rng.random((n, n)) < 0.2] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    return costs


#: Rounds of each figure: every round runs both sides (the order reversed every
#: other round), and the ratios are medians of the per-round ratios.
LATENESS_ROUNDS = 3
SPEEDUP_ROUNDS = 5
FIELD_GOAL = (800, 800)


def callback_lateness(
    seconds: float = SECONDS, *, planning: bool
) -> tuple[np.ndarray, list[float]]:
    """Each 200 Hz tick's lateness, s, with or without Field D* plans in another thread.

    Also the costs of the plans the other thread finished meanwhile (none
    without ``planning``).
    """
    fusion = PlanarFusion()
    fusion.update_yaw_rate(0.0, 0.1, variance=1e-4)  # compiled before the clock starts
    costs = _costs(800, 0)
    FieldDStar(costs).plan((0, 0), FIELD_GOAL)
    stop = threading.Event()
    plan_costs: list[float] = []

    def planner() -> None:
        while not stop.is_set():
            plan_costs.append(FieldDStar(costs).plan((0, 0), FIELD_GOAL).cost)

    worker = threading.Thread(target=planner)
    if planning:
        worker.start()
        time.sleep(0.05)  # the first plan under way
    late = []
    start = time.perf_counter()
    k = 0
    try:
        while True:
            k += 1
            due = start + k * TICK
            if due - start > seconds:
                break
            wait = due - time.perf_counter()
            if wait > 0:
                time.sleep(wait)
            now = time.perf_counter()
            late.append(now - due)
            fusion.update_yaw_rate(k * TICK, 0.1, variance=1e-4)
            # A callback late by several ticks runs once, as an executor serving
            # the latest timer event: skip the ticks it missed.
            k = max(k, int((time.perf_counter() - start) / TICK))
    finally:
        stop.set()
        if planning:
            worker.join()
    return np.asarray(late), plan_costs


def _plan_all(planner: AStarPlanner, plans: int) -> list[float]:
    return [planner.plan((0, 0), (999, 999)).cost for _ in range(plans)]


def _serial(planners: list[AStarPlanner], plans: int) -> tuple[float, list[list[float]]]:
    """Wall seconds of every planner's ``plans`` plans in this thread; their costs."""
    t0 = time.perf_counter()
    costs = [_plan_all(p, plans) for p in planners]
    return time.perf_counter() - t0, costs


def _threaded(planners: list[AStarPlanner], plans: int) -> tuple[float, float, list[list[float]]]:
    """Wall seconds of the same plans, one thread per planner; CPU s per s; the costs."""
    costs: list[list[float]] = [[] for _ in planners]

    def run(i: int) -> None:
        costs[i] = _plan_all(planners[i], plans)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(planners))]
    t0, cpu0 = time.perf_counter(), time.process_time()
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    threaded = time.perf_counter() - t0
    return threaded, (time.process_time() - cpu0) / threaded, costs


def _lateness_figures(rounds: int = LATENESS_ROUNDS) -> dict[str, float]:
    """The callback alone and beside plans, alternately, ``rounds`` times each.

    Wall-clock lateness is the thing measured (this thread waits, it does not
    compute), so the sides share the machine's load by alternating. The ratios
    are the medians of the per-round ratios; the milliseconds the medians over
    rounds of each round's figure (each over ``SECONDS`` of ticks). Every busy
    round must have finished at least one plan, each costing what the first
    plan cost: a figure "beside a plan" with no plan run, or with wrong plans,
    fails instead of being reported.
    """
    reference = FieldDStar(_costs(800, 0)).plan((0, 0), FIELD_GOAL).cost
    figures: dict[str, list[float]] = {}
    for i in range(rounds):
        sides = [False, True] if i % 2 == 0 else [True, False]
        late = {}
        for planning in sides:
            late[planning], plan_costs = callback_lateness(planning=planning)
            if planning:
                assert plan_costs, "no Field D* plan finished beside the callback"
                assert all(c == reference for c in plan_costs), (plan_costs, reference)
            else:
                assert not plan_costs
        idle, busy = late[False], late[True]
        for key, value in (
            ("idle_worst_ms", 1e3 * float(idle.max())),
            ("idle_p99_ms", 1e3 * float(np.percentile(idle, 99))),
            ("planning_worst_ms", 1e3 * float(busy.max())),
            ("planning_p99_ms", 1e3 * float(np.percentile(busy, 99))),
            ("worst_ratio", float(busy.max() / idle.max())),
            ("p99_ratio", float(np.percentile(busy, 99) / np.percentile(idle, 99))),
        ):
            figures.setdefault(key, []).append(value)
    return {key: float(np.median(values)) for key, values in figures.items()}


def _speedup_figures(rounds: int = SPEEDUP_ROUNDS, plans: int = 4) -> dict[str, float]:
    """Serial and threaded A* plans alternately, ``rounds`` times each.

    ``speedup`` and ``cpu_per_s`` are the medians of the per-round figures
    (serial ÷ threaded wall seconds: the threads' gain is in wall time, so
    this thread's CPU time would not show it); ``serial_s`` and
    ``threaded_s`` the medians of each side. Every plan of both sides must
    cost what that map's first plan cost.
    """
    planners = [AStarPlanner(_costs(1000, seed), method="astar") for seed in (1, 2)]
    # Compiled, and each thread's scratch is grown, before any timing.
    reference = [[p.plan((0, 0), (999, 999)).cost] * plans for p in planners]
    figures: dict[str, list[float]] = {}
    for i in range(rounds):
        spent: dict[str, float] = {}
        for side in ("serial", "threaded") if i % 2 == 0 else ("threaded", "serial"):
            if side == "serial":
                spent["serial"], costs = _serial(planners, plans)
            else:
                spent["threaded"], spent["cpu_per_s"], costs = _threaded(planners, plans)
            assert costs == reference, (side, costs, reference)
        figures.setdefault("serial_s", []).append(spent["serial"])
        figures.setdefault("threaded_s", []).append(spent["threaded"])
        figures.setdefault("speedup", []).append(spent["serial"] / spent["threaded"])
        figures.setdefault("cpu_per_s", []).append(spent["cpu_per_s"])
    return {key: float(np.median(values)) for key, values in figures.items()}


@pytest.mark.benchmark(group="threads")
def test_callback_latency_beside_a_plan(benchmark: Any) -> None:
    figures: dict[str, float] = {}

    def run() -> None:
        figures.update(_lateness_figures())

    benchmark.pedantic(run, rounds=1, iterations=1)
    benchmark.extra_info.update(figures)


@pytest.mark.benchmark(group="threads")
def test_two_threads_planning_on_two_maps(benchmark: Any) -> None:
    figures: dict[str, float] = {}

    def run() -> None:
        figures.update(_speedup_figures())

    benchmark.pedantic(run, rounds=1, iterations=1)
    benchmark.extra_info.update(figures)


def _main(runs: int = 3) -> None:
    rows: dict[str, list[float]] = {}
    steps: list[Callable[[], dict[str, float]]] = [_lateness_figures, _speedup_figures]
    for _ in range(runs):
        for step in steps:
            for key, value in step().items():
                rows.setdefault(key, []).append(value)
    for key, values in rows.items():
        shown = ", ".join(f"{v:.3g}" for v in values)
        print(f"{key:20s} median {statistics.median(values):8.3g}   ({shown})")


if __name__ == "__main__":
    _main()
