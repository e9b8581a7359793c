"""Review 50 (PARKED): a robot parked on the goal tolerance's band runs at kernel speed.

The run kernels leave a step whose position is on the band 2**-48 (relative)
wide around the goal tolerance's circle to Python (``decide_goal``, the exact
``at_goal``; review 49). A robot that stops there (a controller stopping just
outside the tolerance's circle) stopped the kernel at every step it stood
still: each step decided in Python, about twice as slow. ``decide_goal`` now
hands the position it found not at the goal back to the kernels (``goal[5:7]``
of the run's goal array), which answer that same position themselves.

Checked: one decision for a robot parked for hundreds of steps, where every
step was decided before; and the run, bit for bit (trace, metrics, events,
every reading the controller saw, the random generator's draws), is the run
made when every band step is decided in Python (the memory wiped after each
decision, as before review 50), in a world of segments (``run_edge_segment``)
and with an occupancy grid (``run_segment``).
"""

from __future__ import annotations

import math
import pickle
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
from navkit.mapping import OccupancyGrid
from navkit.sim import (
    Compass,
    Imu,
    Lidar,
    Observation,
    Robot,
    Simulation,
    WheelEncoders,
    World,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from goal_oracle import exact_at_goal

TOLERANCE = 0.1
#: The controller drives until then, s, stands still until ``RESTART`` (or for ever).
STOP = 0.5
RESTART = 3.0
DURATION = 4.0
RATE = 100.0


def _run(
    goal: tuple[float, ...] | None,
    *,
    grid: bool,
    restart: bool = False,
    yaw_tolerance: float | None = None,
) -> tuple[bytes, Any]:
    """A robot with every sensor (noisy) and wheel slip driving an arc, then parked
    (and, with ``restart``, driving again); the pickled trace, every reading the
    controller saw and the random generator's state after the run, and the trace."""
    seen: list[bytes] = []

    def drive(obs: Observation) -> Twist2D:
        seen.append(pickle.dumps((obs.t, obs.new, obs.true_pose)))
        moving = obs.t < STOP or (restart and obs.t >= RESTART)
        return Twist2D(0.4, 0.0, 0.3) if moving else Twist2D(0.0, 0.0, 0.0)

    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15, wheel_slip=0.05,
        encoders=WheelEncoders(), compass=Compass(noise=0.01),
        imu=Imu(gyro_noise=0.01, accel_noise=0.01), lidar=Lidar(n_beams=16),
    )  # fmt: skip
    walls = box(0.0, 0.0, 4.0, 3.0).exterior
    occupancy = OccupancyGrid.empty(width=4.0, height=3.0, resolution=0.1) if grid else None
    rng = np.random.default_rng(7)
    sim = Simulation(
        World([walls], grid=occupancy, unknown_blocks=False), robot, drive,
        start=(1.0, 1.0, 0.2), goal=goal, goal_tolerance=TOLERANCE,
        yaw_tolerance=yaw_tolerance, duration=DURATION, rate=RATE, seed=rng,
    )  # fmt: skip
    assert sim._world._edges_only != grid  # the kernel meant
    trace = sim.run()
    return pickle.dumps((trace, seen, rng.bit_generator.state)), trace


def _parked_goal(grid: bool) -> tuple[tuple[float, float], int]:
    """A goal whose offset from the parked robot is on the band and not at the goal
    (exactly), and the number of steps the robot stands there."""
    _, free = _run(None, grid=grid)
    x, y, theta = (float(v) for v in free.poses[-1])
    parked = sum(
        1 for px, py, _ in free.poses if float(px) == x and float(py) == y
    )  # fmt: skip
    for angle in theta + np.linspace(-1.0, 1.0, 201):
        gy = y + TOLERANCE * math.sin(angle)
        base = x + TOLERANCE * math.cos(angle)
        for nudge in (0, 1, -1, 2, -2):
            gx = base + nudge * math.ulp(base)
            if goal_verdict(x, y, gx, gy, TOLERANCE) == UNDECIDED and not exact_at_goal(
                x, y, gx, gy, TOLERANCE
            ):
                return (gx, gy), parked
    raise AssertionError("no goal on the band")


@pytest.fixture
def decisions(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """The answers of every ``decide_goal`` call the simulator makes."""
    made: list[bool] = []
    decide = simulation.decide_goal

    def counting(*args: Any) -> bool:
        made.append(decide(*args))
        return made[-1]

    monkeypatch.setattr(simulation, "decide_goal", counting)
    return made


def _forgetting(monkeypatch: pytest.MonkeyPatch, made: list[bool]) -> None:
    """``decide_goal`` as before review 50: the kernels keep no position decided."""
    decide = simulation.decide_goal

    def forgetful(*args: Any) -> bool:
        made.append(decide(*args))
        goal = args[3]
        goal[5:7] = np.nan
        return made[-1]

    monkeypatch.setattr(simulation, "decide_goal", forgetful)


@pytest.mark.parametrize("grid", [False, True], ids=["segments", "grid"])
@pytest.mark.parametrize("restart", [False, True], ids=["parked", "parked-then-on"])
def test_a_parked_robot_is_decided_once_and_runs_as_before(
    grid: bool, restart: bool, decisions: list[bool], monkeypatch: pytest.MonkeyPatch
) -> None:
    goal, parked = _parked_goal(grid)
    assert parked > 200
    now, trace = _run(goal, grid=grid, restart=restart)
    # One decision in Python for the whole stay (before review 50: one per step).
    assert decisions == [False]
    if restart:
        # Driven on from there, into the goal: the parked position's memory hides
        # no step inside the tolerance from the kernel.
        assert trace.metrics.reason == "goal reached"
        assert RESTART < trace.metrics.time_to_goal < DURATION
    else:
        assert trace.metrics.reason == "timeout"
        assert not trace.metrics.reached
    # The run with every band step decided in Python, bit for bit.
    before: list[bool] = []
    _forgetting(monkeypatch, before)
    old, _ = _run(goal, grid=grid, restart=restart)
    stood = parked if not restart else int((RESTART - STOP) * RATE) - 20
    assert len(before) >= stood and not any(before)
    assert now == old


def test_a_heading_off_the_goal_decides_the_parked_robot_in_the_kernel(
    decisions: list[bool],
) -> None:
    goal, _ = _parked_goal(False)
    _, free = _run(None, grid=False)
    theta = float(free.poses[-1][2])
    _run((*goal, theta + 1.0), grid=False, yaw_tolerance=0.1)
    assert not decisions
    _run((*goal, theta), grid=False, yaw_tolerance=0.5)
    assert decisions == [False]
