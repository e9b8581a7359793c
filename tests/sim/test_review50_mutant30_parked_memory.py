"""Review 50 (MUTANT30): the run kernels' memory of a position decided not at the goal.

``decide_goal`` keeps the position it found not at the goal in ``goal[5:7]``
of the run's goal array, and the kernels answer that same position
themselves (review 50, PARKED). Three mutants of that test survived the
suite, whose parked robot never moves: comparing x and y with ``and``
instead of ``or``, or comparing one coordinate alone. A position that shares
one coordinate with the one remembered is another position: planted here
(a remembered position one metre off in x, or in y, of the parked robot),
every band step is still decided in Python, as with no memory at all. And the
memory starts empty (NaN): a robot turning on the spot exactly at the origin,
on the band and at the goal by the exact test, reaches it when its heading
does (with a memory of zeros, the origin passed as decided not at the goal).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

import navkit.sim._simulation as simulation
from navkit._shared.goal import UNDECIDED, goal_verdict
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from goal_oracle import exact_at_goal

TOLERANCE = 0.1
STOP = 0.5
RATE = 100.0


def _run(
    start: tuple[float, float, float],
    goal: tuple[float, ...] | None,
    *,
    yaw_tolerance: float | None = None,
    turn: bool = False,
) -> Any:
    """A robot driving an arc until ``STOP``, then parked, for a second (or, with
    ``turn``, turning on the spot all along)."""

    def drive(obs: Observation) -> Twist2D:
        if turn:
            return Twist2D(0.0, 0.0, 1.0)
        return Twist2D(0.4, 0.0, 0.3) if obs.t < STOP else Twist2D(0.0, 0.0, 0.0)

    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    walls = box(-3.0, -3.0, 4.0, 3.0).exterior
    sim = Simulation(
        World([walls]), robot, drive, start=start, goal=goal, goal_tolerance=TOLERANCE,
        yaw_tolerance=yaw_tolerance, duration=1.0, rate=RATE,
    )  # fmt: skip
    return sim.run()


def _band_goal(x: float, y: float, theta: float, *, at: bool) -> tuple[float, float]:
    """A goal ahead of (x, y) (heading ``theta``) whose offset is on the band, at the
    goal exactly or not."""
    for angle in theta + np.linspace(-1.0, 1.0, 201):
        gy = y + TOLERANCE * math.sin(angle)
        base = x + TOLERANCE * math.cos(angle)
        for nudge in (0, 1, -1, 2, -2, 3, -3):
            gx = base + nudge * math.ulp(base)
            if goal_verdict(x, y, gx, gy, TOLERANCE) == UNDECIDED and (
                exact_at_goal(x, y, gx, gy, TOLERANCE) == at
            ):
                return gx, gy
    raise AssertionError("no goal on the band")


def _deciding(monkeypatch: pytest.MonkeyPatch, offset: tuple[float, float] | None) -> list[bool]:
    """Count ``decide_goal``'s answers; after each, the memory planted ``offset`` off
    the robot's position (None: wiped, as before review 50)."""
    made: list[bool] = []
    decide = simulation.decide_goal

    def planting(*args: Any) -> bool:
        made.append(decide(*args))
        state, goal = args[2], args[3]
        if offset is None:
            goal[5:7] = np.nan
        else:
            goal[5] = state[0] + offset[0]
            goal[6] = state[1] + offset[1]
        return made[-1]

    monkeypatch.setattr(simulation, "decide_goal", planting)
    return made


@pytest.mark.parametrize("offset", [(0.0, 1.0), (1.0, 0.0)], ids=["y-off", "x-off"])
def test_a_position_sharing_one_coordinate_is_decided_again(
    monkeypatch: pytest.MonkeyPatch, offset: tuple[float, float]
) -> None:
    start = (1.0, 1.0, 0.2)
    free = _run(start, None)
    x, y, theta = (float(v) for v in free.poses[-1])
    parked = sum(1 for px, py, _ in free.poses if float(px) == x and float(py) == y)
    assert parked > 50
    goal = _band_goal(x, y, theta, at=False)
    with monkeypatch.context() as patch:
        forgotten = _deciding(patch, None)
        before = _run(start, goal)
    planted = _deciding(monkeypatch, offset)
    after = _run(start, goal)
    # Every parked step decided in Python, never at the goal: no memory answers it.
    assert len(forgotten) >= parked - 1
    assert planted == forgotten
    assert not any(planted)
    assert np.array_equal(after.poses, before.poses)
    assert np.array_equal(after.times, before.times)


def test_a_robot_at_the_origin_on_the_band_reaches_the_goal() -> None:
    # Not at the goal at the start (its heading, checked in Python then); turning
    # on the spot, it stays at the origin (exactly) and the kernel meets the goal's
    # heading there, on the band and at the goal by the exact test.
    gx, gy = _band_goal(0.0, 0.0, 0.0, at=True)
    trace = _run((0.0, 0.0, 0.0), (gx, gy, 0.5), yaw_tolerance=0.1, turn=True)
    assert np.all(trace.poses[:, :2] == 0.0)
    assert trace.metrics.time_to_goal is not None
    assert 0.3 < trace.metrics.time_to_goal < 0.5
