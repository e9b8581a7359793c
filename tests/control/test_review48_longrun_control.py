"""Long runs of the controllers: state kept over 10^4 to 10^5 calls (review 48, LONGRUN).

The path trackers keep a progress along the path and latch ``done``; over a long
looping path (laps of one circle, so every lap passes the same points) the progress
must only grow, the tracker must reach the end of the last lap (not stop at an
earlier lap's end point) and stay done, and its memory must not grow with the calls.
The potential-field controller keeps a stall clock, a PID integral and the previous
velocity: pushed against a wall for 10^5 steps they stay bounded and the clock
counts the steps' time to 1e-9 of itself.
"""

from __future__ import annotations

import gc
import math
import tracemalloc
from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.geometry import Pose2D, Twist2D, integrate

_TRACKERS: list[tuple[type[Any], dict[str, Any]]] = [
    (RegulatedPurePursuit, {"max_speed": 1.0}),
    (FollowTheCarrot, {"max_speed": 1.0}),
    (OnOffTracker, {"max_speed": 1.0}),
]


def _laps(laps: int, radius: float = 5.0, spacing: float = 0.05) -> np.ndarray:
    s = np.arange(0.0, laps * 2.0 * math.pi * radius, spacing)
    return np.column_stack([radius * np.sin(s / radius), radius - radius * np.cos(s / radius)])


def _follow(tracker: Any, path: np.ndarray, dt: float, limit: int) -> tuple[Pose2D, int, int]:
    """Drive ``tracker`` along ``path`` until done: the last pose, the steps, memory growth.

    The growth is measured over steps 2000 to 3000 (tracemalloc slows every step
    several times): a tracker that kept anything per call would show it there.
    """
    tracker.set_path(path)
    pose = Pose2D(0.0, 0.0, 0.0)
    progress = 0.0
    steps = 0
    grown = 0
    while not tracker.done:
        if steps == 2000:
            gc.collect()
            tracemalloc.start()
            early, _ = tracemalloc.get_traced_memory()
        pose = integrate(pose, tracker.step(pose, dt), dt)
        assert tracker.progress >= progress
        progress = tracker.progress
        steps += 1
        assert steps < limit
        if steps == 3000:
            gc.collect()
            grown = tracemalloc.get_traced_memory()[0] - early
            tracemalloc.stop()
    return pose, steps, grown


def _check_latched(tracker: Any, pose: Pose2D) -> None:
    for _ in range(500):
        assert tracker.step(pose, 0.02) == Twist2D(0.0, 0.0, 0.0)
        assert tracker.done


@pytest.mark.parametrize(("kind", "options"), _TRACKERS, ids=lambda v: getattr(v, "__name__", ""))
def test_trackers_finish_a_looping_path_and_stay_done(
    kind: type[Any], options: dict[str, Any]
) -> None:
    path = _laps(2)
    tracker = kind(**options)
    pose, steps, grown = _follow(tracker, path, 0.02, 200_000)
    length = float(np.sum(np.hypot(*np.diff(path, axis=0).T)))
    # At the end of the last lap, not of an earlier one (every lap ends at the start).
    assert tracker.progress > length - 0.5
    assert steps * 0.02 * 1.0 > length - 0.5  # no faster than max_speed
    assert math.dist((pose.x, pose.y), path[-1]) < tracker.goal_tolerance + 1e-9
    assert grown < 8_000
    _check_latched(tracker, pose)


@pytest.mark.slow
@pytest.mark.parametrize(("kind", "options"), _TRACKERS, ids=lambda v: getattr(v, "__name__", ""))
def test_trackers_on_a_six_kilometre_path(kind: type[Any], options: dict[str, Any]) -> None:
    # 200 laps, 125,664 points: about 3·10^5 steps (RPP about a minute).
    path = _laps(200)
    tracker = kind(**options)
    pose, _, grown = _follow(tracker, path, 0.02, 1_000_000)
    assert tracker.progress > 2.0 * math.pi * 5.0 * 200 - 0.5
    assert grown < 8_000
    _check_latched(tracker, pose)


def _stalled(steps: int, dt: float) -> None:
    # A wall between the robot and the goal: the controller pushes against it. The
    # stall clock counts the steps to 1e-9 of itself, the integral and the command
    # stay within their limits, and memory does not grow (measured over 1000 steps
    # from the 2000th: tracemalloc slows every step several times).
    controller = PotentialFieldController(ki=1.0, integral_limit=0.5, stall_timeout=2.0)
    wall = np.column_stack([np.full(41, 0.25), np.linspace(-1.0, 1.0, 41)])
    pose, goal = Pose2D(0.0, 0.0, 0.0), Pose2D(1.0, 0.0, 1.0)
    for k in range(1, steps + 1):
        if k == 2000:
            gc.collect()
            tracemalloc.start()
            early, _ = tracemalloc.get_traced_memory()
        command = controller.step(pose, goal, dt, obstacles=wall)
        assert math.hypot(command.vx, command.vy) <= controller.max_speed
        # The PID's integral is clamped: kp·e + ki·limit at most (e = 1 rad here).
        assert abs(command.omega) <= min(controller.max_omega, 3.0 * 1.0 + 1.0 * 0.5 + 1e-12)
        if k == 3000:
            gc.collect()
            grown = tracemalloc.get_traced_memory()[0] - early
            tracemalloc.stop()
    assert grown < 4_000
    assert controller.stalled
    # The pose never moves: every step's time counts, from the second.
    assert controller.stall_time == pytest.approx((steps - 1) * dt, rel=1e-9)


def test_potential_field_stalled_for_five_thousand_steps() -> None:
    _stalled(5000, 0.02)


@pytest.mark.slow
def test_potential_field_stalled_for_two_hundred_thousand_steps() -> None:
    # 2·10^5 sums of 1 ms (about a minute): the clock's slack, 1e-9, still holds.
    _stalled(200_000, 1e-3)
