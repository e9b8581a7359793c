"""Review 48 (SIMGOAL): a run reaches its goal exactly where the controller is done.

The simulator's run kernel decided "reached" by ``math.hypot(dx, dy) <=
goal_tolerance`` (libm's hypot, as ``np.hypot``), the controllers exactly
(``dx² + dy² <= t²`` in real arithmetic, review 47): a robot standing an offset
a hair beyond the tolerance, which hypot rounds onto it, was "goal reached" for
the run while its controller was not done. The kernel now calls the
controllers' test (see ``test_review48_simgoal_exact.py``).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from shapely.geometry import box

from navkit.control._goal import at_goal, resolution
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

TOLERANCE = 0.1


def _exact(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """The controllers' test in rational arithmetic."""
    dx, dy = gx - px, gy - py
    t = Fraction(max(tolerance, resolution(gx, gy)))
    return Fraction(dx) ** 2 + Fraction(dy) ** 2 <= t * t


def _stopped_run(goal: tuple[float, float] | None) -> Simulation:
    """A robot that drives 0.5 s along +x and stops (the pose then stands, exactly)."""

    def drive(obs: Observation) -> Twist2D:
        return Twist2D(0.4 if obs.t < 0.5 else 0.0, 0.0, 0.0)

    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    world = World([box(0.0, 0.0, 3.0, 2.0).exterior])
    return Simulation(
        world, robot, drive, start=(0.5, 1.0, 0.0), goal=goal, goal_tolerance=TOLERANCE,
        duration=1.5, rate=100.0, control_rate=20.0,
    )  # fmt: skip


@pytest.fixture(scope="module")
def stop_pose() -> tuple[float, float]:
    trace = _stopped_run(None).run()
    final = trace.poses[-1]
    # The pose stands for the last half second, exactly (the goal is checked there).
    assert np.array_equal(trace.poses[-50:], np.repeat(trace.poses[-1:], 50, axis=0))
    return float(final[0]), float(final[1])


def _disagreeing_goals(px: float, py: float, n: int) -> list[tuple[float, float, bool]]:
    """Goals ahead of the stop pose (every earlier pose is farther), the offset on the
    tolerance's circle, where libm's hypot (numba's, np.hypot) misjudges it: nearly
    always an offset a hair too long that it rounds onto the tolerance."""
    found: list[tuple[float, float, bool]] = []
    for angle in np.linspace(-1.2, 1.2, 4001):
        gx = px + TOLERANCE * math.cos(angle)
        gy = py + TOLERANCE * math.sin(angle)
        for nudge in (0, 1, -1):
            gx2 = gx + nudge * math.ulp(gx)
            want = _exact(px, py, gx2, gy, TOLERANCE)
            if (float(np.hypot(px - gx2, py - gy)) <= TOLERANCE) != want:
                found.append((gx2, gy, want))
        if len(found) >= n:
            break
    return found


def test_a_run_reaches_the_goal_exactly_where_the_controller_is_done(
    stop_pose: tuple[float, float],
) -> None:
    px, py = stop_pose
    goals = _disagreeing_goals(px, py, 6)
    assert len(goals) == 6
    for gx, gy, want in goals:
        assert at_goal(px, py, gx, gy, TOLERANCE) == want  # the controllers' test
        trace = _stopped_run((gx, gy)).run()
        assert trace.metrics.reached == want, (gx, gy)
        assert (trace.metrics.reason == "goal reached") == want


def test_a_run_starts_at_its_goal_exactly_where_the_controller_is_done() -> None:
    # The robot stands on its start; the goal a hair beyond the tolerance from it.
    px, py = 0.7000000000000002, 1.0
    goals = [(gx, gy) for gx, gy, want in _disagreeing_goals(px, py, 3) if not want]
    assert goals
    for gx, gy in goals:
        sim = Simulation(
            World([box(0.0, 0.0, 3.0, 2.0).exterior]),
            Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15),
            lambda _obs: Twist2D(0.0, 0.0, 0.0), start=(px, py, 0.0), goal=(gx, gy),
            goal_tolerance=TOLERANCE, duration=0.1,
        )  # fmt: skip
        assert not at_goal(px, py, gx, gy, TOLERANCE)
        assert not sim.run().metrics.reached, (gx, gy)
