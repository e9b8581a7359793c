"""Review 49 (GOALTAIL): a run that steps onto the goal tolerance's band stops for Python.

The run kernels decide "goal reached" by ``math.hypot`` away from the
tolerance's circle (``navkit._shared.goal.goal_verdict``); on the band 2**-48
(relative) wide around it they return ``GOAL_UNDECIDED``, and the simulator
decides with the exact ``at_goal`` in Python (``decide_goal``) and resumes the
kernel at that step. The resumed run must be the run the kernel would have
made itself: the same poses, commands, sensor readings and slip draws, the goal
reached at the first step the exact test says so. Checked on runs whose pose
at a moving step lies on the band (offsets a hair inside and outside), in a
world of segments (``run_edge_segment``) and with an occupancy grid
(``run_segment``), against the same run without a goal.
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
    Trace,
    WheelEncoders,
    World,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from goal_oracle import exact_at_goal
from subprocess_probe import probe_outcome

TOLERANCE = 0.1
#: The step whose pose the goal's band passes through (the robot moving).
STEP = 37


def _run(
    goal: tuple[float, ...] | None,
    *,
    grid: bool,
    stop_at_goal: bool = True,
    yaw_tolerance: float | None = None,
) -> tuple[Trace, list[bytes]]:
    """A robot with every sensor and wheel slip driving an arc for 1 s; the trace and
    every observation's time and new readings (pickled, to compare bit for bit)."""
    seen: list[bytes] = []

    def drive(obs: Observation) -> Twist2D:
        seen.append(pickle.dumps((obs.t, obs.new, obs.true_pose)))
        return Twist2D(0.4, 0.0, 0.3)

    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15, wheel_slip=0.05,
        encoders=WheelEncoders(), compass=Compass(noise=0.01),
        imu=Imu(gyro_noise=0.01, accel_noise=0.01), lidar=Lidar(n_beams=16),
    )  # fmt: skip
    walls = box(0.0, 0.0, 4.0, 3.0).exterior
    occupancy = OccupancyGrid.empty(width=4.0, height=3.0, resolution=0.1) if grid else None
    sim = Simulation(
        World([walls], grid=occupancy, unknown_blocks=False), robot, drive,
        start=(1.0, 1.0, 0.2), goal=goal, goal_tolerance=TOLERANCE,
        yaw_tolerance=yaw_tolerance, duration=1.0, stop_at_goal=stop_at_goal,
    )  # fmt: skip
    assert sim._world._edges_only != grid  # the kernel meant
    return sim.run(), seen


def _band_goals(trace: Trace) -> list[tuple[float, float, int]]:
    """Goals ``TOLERANCE`` from the pose at ``STEP``, ahead of it, whose offset is on
    the band, two a hair inside and two a hair outside; each with the first step
    whose pose is at the goal (exactly): ``STEP`` itself or the next one."""
    x, y, theta = (float(v) for v in trace.poses[STEP])
    goals: dict[int, list[tuple[float, float, int]]] = {STEP: [], STEP + 1: []}
    for angle in theta + np.linspace(-0.3, 0.3, 61):
        for nudge in (-1, 0, 1):
            gx = x + TOLERANCE * math.cos(angle)
            gy = y + TOLERANCE * math.sin(angle)
            gx = gx + nudge * math.ulp(gx)
            if goal_verdict(x, y, gx, gy, TOLERANCE) != UNDECIDED:
                continue
            first = next(
                k for k, (px, py, _) in enumerate(trace.poses)
                if exact_at_goal(float(px), float(py), gx, gy, TOLERANCE)
            )  # fmt: skip
            goals[first].append((gx, gy, first))
    assert len(goals[STEP]) >= 2 and len(goals[STEP + 1]) >= 2
    return goals[STEP][:2] + goals[STEP + 1][:2]


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


def _same_rows(trace: Trace, free: Trace, rows: int) -> None:
    assert len(trace.times) == rows
    np.testing.assert_array_equal(trace.times, free.times[:rows])
    np.testing.assert_array_equal(trace.poses, free.poses[:rows])
    np.testing.assert_array_equal(trace.commands, free.commands[:rows])


@pytest.mark.parametrize("grid", [False, True], ids=["segments", "grid"])
def test_a_run_through_the_band_is_the_run_without_a_goal(
    grid: bool, decisions: list[bool]
) -> None:
    free, free_seen = _run(None, grid=grid)
    assert free.metrics.reason == "timeout"
    for gx, gy, first in _band_goals(free):
        decisions.clear()
        # Going on past the goal: every step, reading and slip draw as without it.
        trace, seen = _run((gx, gy), grid=grid, stop_at_goal=False)
        assert decisions == [False]  # the band's step, decided in Python: the run goes on
        _same_rows(trace, free, len(free.times))
        assert seen == free_seen
        assert trace.metrics.reached
        assert trace.metrics.time_to_goal == free.times[first]
        # Stopping there: the run without a goal, up to that step.
        decisions.clear()
        trace, seen = _run((gx, gy), grid=grid)
        assert decisions == [first == STEP]  # the run ends there, or at the next step
        assert trace.metrics.reason == "goal reached"
        assert trace.metrics.time_to_goal == free.times[first]
        _same_rows(trace, free, first + 1)
        assert seen == free_seen[: len(seen)]
        assert len(seen) >= first // 5  # (20 Hz control at 100 Hz physics)


def test_a_heading_off_the_goal_is_decided_in_the_kernel(decisions: list[bool]) -> None:
    free, _ = _run(None, grid=False)
    gx, gy, _ = _band_goals(free)[0]
    theta = float(free.poses[STEP][2])
    # The heading is checked before the band stops the kernel: no Python decision.
    trace, _ = _run((gx, gy, theta + 1.0), grid=False, yaw_tolerance=0.1)
    assert not decisions
    assert trace.metrics.reason == "timeout"
    # A heading within its tolerance: the band stops the kernel as without one.
    trace, _ = _run((gx, gy, theta), grid=False, yaw_tolerance=0.5)
    assert decisions
    assert trace.metrics.reason == "goal reached"


_IR_PROBE = """
import json
from shapely.geometry import box
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, World
from navkit.sim import _segment_kernels as kernels

Simulation(
    World([box(0.0, 0.0, 4.0, 3.0).exterior]),
    Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15),
    lambda _obs: Twist2D(0.4, 0.0, 0.0), start=(1.0, 1.0, 0.0), goal=(1.5, 1.2), duration=0.05,
).run()
run = kernels.run_edge_segment
ir = "".join(run.inspect_llvm().values())
# Veltkamp's 2**27 + 1 (Dekker's exact products) as LLVM writes the double.
print(json.dumps([sum(run.stats.cache_misses.values()), "0x41A0000002000000" in ir,
                  "@hypot" in ir]))
"""


@pytest.mark.slow
def test_the_run_kernels_compile_no_exact_arithmetic(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A first use with an empty cache (the kernel compiled in the probe, so its
    # LLVM IR is there to read): the verdict's hypot is inlined, the exact tail
    # (and its sixth of a second of first-use compilation) is not.
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    compiled, dekker, hypot = probe_outcome(_IR_PROBE)
    assert compiled == 1
    assert hypot
    assert not dekker
