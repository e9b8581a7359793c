"""A PlanarFusion whose clock is past the run's start is refused, not silently starved.

A simulation starts at t = 0 and feeds a ``PlanarFusion`` every reading at its
delivery time. A filter whose time is already later (built with ``t0=5.0``, or
reused from an earlier run) refused every reading up to that time as out of
order, and the run went on with an estimate standing still: a silent wrong
result (found by a user's-eye review: a loop of trials that kept one filter).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Imu, Observation, Robot, Simulation, World

WORLD = World([box(0.0, 0.0, 6.0, 4.0).exterior])
ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,
              compass=Compass(), imu=Imu())  # fmt: skip
START = (1.0, 1.0, 0.0)


def forward(obs: Observation) -> Twist2D:
    return Twist2D(0.4, 0.0, 0.0)


def simulation(fusion: PlanarFusion, duration: float = 1.0) -> Simulation:
    return Simulation(WORLD, ROBOT, forward, start=START, estimator=fusion, duration=duration)


def test_a_filter_reused_from_an_earlier_run_is_refused_and_left_unchanged() -> None:
    fusion = PlanarFusion(pose=START, t0=0.0)
    first = simulation(fusion).run()
    assert first.metrics.estimate_error < 0.05  # the first run tracked the robot
    before = (fusion.t, fusion.x.tolist(), fusion.P.tolist())
    with pytest.raises(ValueError, match=r"estimator: .*PlanarFusion's time is 1 s.*t0=0\.0"):
        simulation(fusion)
    assert (fusion.t, fusion.x.tolist(), fusion.P.tolist()) == before


@settings(deadline=None, max_examples=15)
@given(t0=st.floats(1e-9, 1e6))
def test_a_filter_starting_after_the_run_is_refused(t0: float) -> None:
    with pytest.raises(ValueError, match=r"estimator: .*refuse every reading"):
        simulation(PlanarFusion(pose=START, t0=t0))


@pytest.mark.parametrize("t0", [None, 0.0, -0.0, -0.01])
def test_a_filter_starting_at_or_before_the_run_follows_the_robot(t0: float | None) -> None:
    fusion = PlanarFusion(pose=START) if t0 is None else PlanarFusion(pose=START, t0=t0)
    trace = simulation(fusion, duration=2.0).run()
    assert fusion.t is not None and math.isclose(fusion.t, 2.0, abs_tol=0.02)
    moved = trace.estimates[-1, 0] - START[0]
    assert moved > 0.7  # 0.4 m/s for 2 s, less the wheels' spin-up
    assert np.all(np.isfinite(trace.estimates[1:]))
    assert trace.metrics.estimate_error < 0.05
