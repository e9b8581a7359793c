"""A shallow copy of a Simulation with an ``OmniOdometry`` (session 39, SMALLS).

``copy.copy(sim)`` shares the controller and the estimator (documented), and with
them the simulation's adapter around an ``OmniOdometry``, which held the last
compass yaw read. Run after the original, the copy rotated its first wheel
increments (those before its own first compass reading) by the yaw the
original's run had read last, where a new Simulation given the same odometry
takes the odometry's heading: the copy's run depended on state nobody can see
(1.2 cm of estimate here). Decided, as for ``DiffOdometry`` (review 34): each run
starts the adapter afresh (compass yaw and counters), so the copy's run is that
of a new Simulation given the odometry as the original's run left it; the
odometry itself stays shared, as documented.
"""

from __future__ import annotations

import copy

import numpy as np
from shapely.geometry import box

from navkit.estimation import OmniOdometry
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import OmniDrive
from navkit.sim import Compass, Observation, Robot, Simulation, WheelEncoders, World

OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
WORLD = World(box(-5, -5, 5, 5).exterior)
START = Pose2D(0.0, 0.0, 0.0)
# Slow encoders, a fast compass delivered late: the copy's first increments come
# before its first compass reading, and the original's last compass yaw is fresher
# than its odometry's heading (turning at 0.6 rad/s).
ROBOT = Robot(
    drive=OMNI,
    footprint=0.2,
    encoders=WheelEncoders(rate=5.0),
    compass=Compass(rate=50.0, latency=0.5),
)


def _turn(obs: Observation) -> Twist2D:
    return Twist2D(0.2, 0.0, 0.6)


def _simulation(odometry: OmniOdometry) -> Simulation:
    return Simulation(WORLD, ROBOT, _turn, start=START, estimator=odometry, duration=3.0, seed=2)


def test_a_copy_run_after_the_original_runs_as_a_new_simulation() -> None:
    odometry = OmniOdometry(OMNI, pose=START)
    sim = _simulation(odometry)
    twin = copy.copy(sim)  # shares the controller and the odometry
    sim.run()
    carried = odometry.pose
    trace = twin.run()
    alone = _simulation(OmniOdometry(OMNI, pose=carried)).run()
    np.testing.assert_array_equal(trace.poses, alone.poses)
    # The same estimates as an odometry built at the carried pose (to rounding: the
    # carried one sums its motion from the first run's start). Before: 1.2e-2 m apart.
    np.testing.assert_allclose(trace.estimates, alone.estimates, rtol=0.0, atol=1e-12)


def test_the_odometry_stays_shared_and_a_deep_copy_runs_apart() -> None:
    odometry = OmniOdometry(OMNI, pose=START)
    sim = _simulation(odometry)
    deep = copy.deepcopy(sim)
    twin = copy.copy(sim)
    first = sim.run()
    after_first = odometry.pose
    assert after_first != START
    # The deep copy has its own odometry: its run is the original's, bit for bit.
    np.testing.assert_array_equal(deep.run().estimates, first.estimates)
    assert odometry.pose == after_first
    # The shallow copy's run moves the shared odometry on from there.
    twin.run()
    assert odometry.pose != after_first
