"""A PlanarFusion used by another run after this Simulation was built (review 26, last release).

Review 25 refused, when a ``Simulation`` is built, a ``PlanarFusion`` whose time
is past the run's start: it would refuse every reading up to that time as out of
order and the estimate would stand still. The check ran only at construction.
Two simulations built with one filter, then run one after the other (a list of
trials built first, run in a loop), pass it; the second run's filter is then
past 0 s, and its estimate stood still at the first run's end (0.60 m off the
robot here), a silent wrong run. The run should refuse it as the constructor
does, the filter unchanged.
"""

from __future__ import annotations

import pytest
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


def test_a_filter_run_by_another_simulation_since_construction_is_refused_at_run() -> None:
    fusion = PlanarFusion(pose=START, t0=0.0)
    first = Simulation(WORLD, ROBOT, forward, start=START, estimator=fusion, duration=3.0)
    second = Simulation(WORLD, ROBOT, forward, start=START, estimator=fusion, duration=1.5)
    assert first.run().metrics.estimate_error < 0.05
    before = (fusion.t, fusion.x.tolist(), fusion.P.tolist())
    with pytest.raises(ValueError, match=r"PlanarFusion's time is 3 s"):
        trace = second.run()
        # What happened instead: the estimate stood at the first run's end.
        print(trace.metrics.estimate_error)
    assert (fusion.t, fusion.x.tolist(), fusion.P.tolist()) == before
