"""Path trackers' steps on a 10 km route of 10^5 poses against a 20 m one (review 37).

Run with ``python -m pytest benchmarks/test_bench_trackers.py --benchmark-only``.

A ROS-style global plan holds a pose every few centimetres: 10^5 of them for a
10 km route. Each step of ``RegulatedPurePursuit`` and ``FollowTheCarrot`` searches
the path only near the robot (2 m of path ahead of its previous closest point, or
up to where it last steered; a binary search finds the window's first segment), so a
step on the long route should cost what it costs on a short one. The test drives the
robot 100 steps along the first metres of both routes (the same points: the short
route is the long one's first 200 poses) and times the steps only (``set_path``
copies the path, O(N), once), alternately in one loop, 21 rounds, this thread's
CPU time. ``extra_info`` holds ``long_over_short`` per tracker, the median
per-round ratio (1.0-1.1 in session 41: the binary search's 17 halvings
against 8); it fails above 3 (a step that walked the whole path would be
hundreds of times slower).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import FollowTheCarrot, RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

N_LONG = 100_000
N_SHORT = 200
STEPS = 100
DT = 0.05


def route(n: int) -> np.ndarray:
    """A gently winding route with a pose every 0.1 m."""
    x = 0.1 * np.arange(n)
    return np.column_stack([x, 0.5 * np.sin(x / 5.0)])


def drive(make: Callable[[], Any], path: np.ndarray) -> Callable[[], tuple[float, list[Any]]]:
    """A run: a tracker given ``path`` (untimed), then ``STEPS`` timed steps."""

    def run() -> tuple[float, list[Any]]:
        tracker = make()
        tracker.set_path(path)
        pose = Pose2D(0.0, 0.1, 0.0)
        commands = []
        c0 = time.thread_time()
        for _ in range(STEPS):
            cmd = tracker.step(pose, DT)
            pose = integrate(pose, cmd, DT)
            commands.append(cmd)
        return time.thread_time() - c0, commands

    return run


@pytest.mark.benchmark(group="trackers-long-path")
@pytest.mark.parametrize("make", [RegulatedPurePursuit, FollowTheCarrot])
def test_step_cost_does_not_grow_with_the_path(benchmark: Any, make: Any) -> None:
    long_run = drive(make, route(N_LONG))
    short_run = drive(make, route(N_SHORT))
    # The same commands on both routes (their first metres are the same points).
    assert long_run()[1] == short_run()[1]

    def rounds() -> dict[str, float]:
        ratios = []
        for i in range(21):
            first, second = (long_run, short_run) if i % 2 == 0 else (short_run, long_run)
            a, _ = first()
            b, _ = second()
            t_long, t_short = (a, b) if i % 2 == 0 else (b, a)
            ratios.append(t_long / max(t_short, 1e-9))
        return {"long_over_short": float(np.median(ratios))}

    info = benchmark.pedantic(rounds, rounds=1, iterations=1)
    benchmark.extra_info.update(info)
    assert info["long_over_short"] < 3.0
