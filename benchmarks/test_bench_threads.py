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
  a plan's length.
* ``throughput``: A* plans on two 1000 x 1000 maps, each map's plans in a
  thread of its own, against the same plans one after another in one thread;
  ``extra_info["speedup"]`` is the serial time over the threaded one (2 at
  best on 2 free cores, 1 when the kernels hold the GIL), ``cpu_per_s`` the
  process's CPU seconds per second while the threads plan (likewise).

Timings on a busy machine are noisy: compare ratios from one run, alternating
runs of the versions compared.
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


def callback_lateness(seconds: float = SECONDS, *, planning: bool) -> np.ndarray:
    """Each 200 Hz tick's lateness, s, with or without Field D* plans in another thread."""
    fusion = PlanarFusion()
    fusion.update_yaw_rate(0.0, 0.1, variance=1e-4)  # compiled before the clock starts
    costs = _costs(800, 0)
    FieldDStar(costs).plan((0, 0), (800, 800))
    stop = threading.Event()

    def planner() -> None:
        while not stop.is_set():
            FieldDStar(costs).plan((0, 0), (800, 800))

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
    return np.asarray(late)


def planning_speedup(plans: int = 4) -> tuple[float, float, float]:
    """Seconds of A* plans on two maps: one thread after the other, and one thread each.

    The third figure is the process's CPU seconds per second while the two
    threads plan: up to 2 where both run at once and the machine has two
    cores free for them, 1 at most where the kernels hold the GIL.
    """
    planners = [AStarPlanner(_costs(1000, seed), method="astar") for seed in (1, 2)]

    def run(planner: AStarPlanner) -> None:
        for _ in range(plans):
            planner.plan((0, 0), (999, 999))

    for p in planners:  # compiled, and each thread's scratch is grown below
        p.plan((0, 0), (999, 999))
    t0 = time.perf_counter()
    for p in planners:
        run(p)
    serial = time.perf_counter() - t0
    threads = [threading.Thread(target=run, args=(p,)) for p in planners]
    t0, cpu0 = time.perf_counter(), time.process_time()
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    threaded = time.perf_counter() - t0
    return serial, threaded, (time.process_time() - cpu0) / threaded


def _lateness_figures() -> dict[str, float]:
    idle = callback_lateness(planning=False)
    busy = callback_lateness(planning=True)
    return {
        "idle_worst_ms": 1e3 * float(idle.max()),
        "idle_p99_ms": 1e3 * float(np.percentile(idle, 99)),
        "planning_worst_ms": 1e3 * float(busy.max()),
        "planning_p99_ms": 1e3 * float(np.percentile(busy, 99)),
        "worst_ratio": float(busy.max() / idle.max()),
        "p99_ratio": float(np.percentile(busy, 99) / np.percentile(idle, 99)),
    }


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
        serial, threaded, cores = planning_speedup()
        figures.update(
            serial_s=serial, threaded_s=threaded, speedup=serial / threaded, cpu_per_s=cores
        )

    benchmark.pedantic(run, rounds=1, iterations=1)
    benchmark.extra_info.update(figures)


def _main(runs: int = 3) -> None:
    rows: dict[str, list[float]] = {}
    steps: list[Callable[[], dict[str, float]]] = [
        _lateness_figures,
        lambda: dict(zip(("serial_s", "threaded_s", "cpu_per_s"), planning_speedup(), strict=True)),
    ]
    for _ in range(runs):
        for step in steps:
            for key, value in step().items():
                rows.setdefault(key, []).append(value)
    rows["speedup"] = [s / t for s, t in zip(rows["serial_s"], rows["threaded_s"], strict=True)]
    for key, values in rows.items():
        shown = ", ".join(f"{v:.3g}" for v in values)
        print(f"{key:20s} median {statistics.median(values):8.3g}   ({shown})")


if __name__ == "__main__":
    _main()
