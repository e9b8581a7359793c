"""One DiffOdometry over a route driven leg by leg, a Simulation a leg (review 34, long runs).

A robot that runs for days is simulated in pieces: each leg a ``Simulation``
started at the pose the last one ended at, with one odometry carried through
(its estimate, drift and all, goes on). The robot's encoders count from 0 in
every run, but the ``DiffOdometry`` kept the counters it latched at the end of
the last leg, and took the difference to the new leg's first reading (0) as
motion: the estimate jumped back by the whole distance counted before, a
silent wrong run (3 m here; on a 16-bit counter, modulo its range). A
``PlanarFusion`` reused so is refused (``FusionEstimator.check_start``); an
odometry can go on, and should: the run forgets the latched counters, as
``reset()`` does, and its first reading only latches them. The refusal of a
``PlanarFusion`` now names the way to carry its estimate on into the next leg.
"""

from __future__ import annotations

import copy
import math
import re
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import box

from navkit.estimation import DiffOdometry, OmniOdometry, PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Compass, Imu, Observation, Robot, Simulation, Trace, WheelEncoders, World

DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)
WORLD = World([box(-20.0, -20.0, 20.0, 20.0).exterior])


def arc(obs: Observation) -> Twist2D:
    return Twist2D(0.5, 0.0, 0.2)


def robot(bits: int | None) -> Robot:
    return Robot(drive=DRIVE, footprint=0.2, encoders=WheelEncoders(bits=bits))


def leg(odometry: DiffOdometry, rob: Robot, start: Pose2D, duration: float) -> Trace:
    return Simulation(WORLD, rob, arc, start=start, estimator=odometry, duration=duration).run()


@pytest.mark.parametrize(("robot_bits", "odometry_bits"), [(16, 16), (16, None), (None, None)])
def test_an_odometry_carried_from_leg_to_leg_goes_on_without_a_jump(
    robot_bits: int | None, odometry_bits: int | None
) -> None:
    rob = robot(robot_bits)
    tpr = 1024.0  # WheelEncoders' default
    start = Pose2D(0.0, 0.0, 0.0)
    odometry = DiffOdometry(DRIVE, ticks_per_rev=tpr, bits=odometry_bits, pose=start)
    first = leg(odometry, rob, start, 6.0)
    assert first.metrics.estimate_error < 0.01
    # The next leg starts where the robot is, with the odometry as it is.
    end = Pose2D(*first.poses[-1])
    carried = Pose2D(*first.estimates[-1])
    assert odometry.pose == carried
    fresh = DiffOdometry(DRIVE, ticks_per_rev=tpr, bits=odometry_bits, pose=carried)
    again = leg(odometry, rob, end, 4.0)
    alone = leg(fresh, rob, end, 4.0)
    np.testing.assert_array_equal(again.poses, alone.poses)
    # The same estimates as an odometry built at the carried pose (to rounding: the
    # carried one sums its motion from the first leg's start).
    np.testing.assert_allclose(again.estimates, alone.estimates, rtol=0.0, atol=1e-12)
    # So the estimate follows the robot, off by the first leg's drift only.
    assert again.metrics.estimate_error < first.metrics.estimate_error + 0.01
    assert math.hypot(*(again.estimates[1, :2] - carried.as_array()[:2])) < 0.01


def test_a_copy_of_a_simulation_run_after_it_starts_its_counters_again() -> None:
    rob = robot(16)
    start = Pose2D(1.0, 2.0, 0.5)
    odometry = DiffOdometry(DRIVE, ticks_per_rev=1024.0, bits=16, pose=start)
    sim = Simulation(WORLD, rob, arc, start=start, estimator=odometry, duration=3.0)
    twin = copy.copy(sim)  # shares the estimator (and the odometry)
    sim.run()
    carried = odometry.pose
    trace = twin.run()
    fresh = DiffOdometry(DRIVE, ticks_per_rev=1024.0, bits=16, pose=carried)
    alone = Simulation(WORLD, rob, arc, start=start, estimator=fresh, duration=3.0).run()
    np.testing.assert_allclose(trace.estimates, alone.estimates, rtol=0.0, atol=1e-12)


def test_a_new_odometry_runs_as_before() -> None:
    # Forgetting nothing: a new odometry's first reading only latches anyway, and one
    # latched at the robot's first counters (0) reads the same run.
    rob = robot(16)
    start = Pose2D(0.0, 0.0, 0.0)
    plain = DiffOdometry(DRIVE, ticks_per_rev=1024.0, bits=16, pose=start)
    latched = DiffOdometry(DRIVE, ticks_per_rev=1024.0, bits=16, pose=start)
    latched.update(0, 0)
    a = leg(plain, rob, start, 2.0)
    b = leg(latched, rob, start, 2.0)
    np.testing.assert_array_equal(a.estimates, b.estimates)
    assert a.metrics.estimate_error < 0.01


def test_a_fusion_filter_refused_for_a_new_leg_says_how_to_carry_it_on() -> None:
    # A PlanarFusion cannot go back to the new run's 0 s: it is refused, and the
    # message names the way to carry its estimate on, which then works.
    rob = Robot(drive=DRIVE, footprint=0.2, encoders=WheelEncoders(), compass=Compass(), imu=Imu())
    start = Pose2D(0.0, 0.0, 0.0)
    fusion = PlanarFusion(pose=start, t0=0.0)
    first = Simulation(WORLD, rob, arc, start=start, estimator=fusion, duration=4.0).run()
    end = Pose2D(*first.poses[-1])
    with pytest.raises(ValueError, match=re.escape("fusion.reset(fusion.x, fusion.P, t0=0.0)")):
        Simulation(WORLD, rob, arc, start=end, estimator=fusion, duration=4.0).run()
    carried = fusion.x
    fusion.reset(fusion.x, fusion.P, t0=0.0)
    again = Simulation(WORLD, rob, arc, start=end, estimator=fusion, duration=4.0).run()
    assert np.allclose(again.estimates[0], carried[:3], rtol=0.0, atol=1e-6)
    assert again.metrics.estimate_error < 0.02


def test_an_omni_odometry_goes_on_from_leg_to_leg_as_the_sim_guide_says() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    rob = Robot(drive=drive, footprint=0.25, encoders=WheelEncoders(), compass=Compass())
    odometry = OmniOdometry(drive)
    first = Simulation(WORLD, rob, arc, start=(0.0, 0.0, 0.0), estimator=odometry,
                       duration=4.0).run()  # fmt: skip
    carried = odometry.pose
    again = Simulation(WORLD, rob, arc, start=first.poses[-1], estimator=odometry,
                       duration=4.0).run()  # fmt: skip
    np.testing.assert_array_equal(again.estimates[0], carried.as_array())
    assert again.metrics.estimate_error < first.metrics.estimate_error + 0.05
    guide = " ".join((Path(__file__).resolve().parents[2] / "docs/guides/sim.md").read_text(
        encoding="utf-8").split())  # fmt: skip
    assert "an `OmniOdometry` or a `DiffOdometry` goes on as it is" in guide
    assert "`fusion.reset(fusion.x, fusion.P, t0=0.0)` before each new leg" in guide
