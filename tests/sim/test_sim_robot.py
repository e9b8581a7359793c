"""Robot bodies: wheel limits, slip, radius error, encoders, compass, IMU, footprints."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from shapely.geometry import LineString, Polygon, box

from constant_controller import Constant, run_constant
from navkit.geometry import Twist2D, integrate
from navkit.kinematics import DiffDrive, OmniDrive, tick_delta
from navkit.sim import (
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Lidar,
    MovingObstacle,
    Observation,
    Robot,
    Simulation,
    WheelEncoders,
    World,
)

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)


def test_acceleration_limit_ramps_exactly() -> None:
    """10 rad/s² on 5 cm wheels is 0.5 m/s²: 0.25 m in the 1 s ramp, then 0.5 m/s."""
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_acceleration=10.0)
    trace, _ = run_constant(robot, Twist2D(0.5), 2.0)
    assert trace.metrics.reason == "timeout"
    assert trace.times[-1] == pytest.approx(2.0)
    assert trace.poses[-1, 0] == pytest.approx(0.75, abs=1e-9)
    assert trace.poses[100, 0] == pytest.approx(0.25, abs=1e-9)
    np.testing.assert_allclose(trace.poses[:, 1:], 0.0, atol=1e-12)


def test_wheel_speed_saturation_keeps_the_direction() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_speed=5.0)
    trace, _ = run_constant(robot, Twist2D(1.0, 0.0, 1.0), 2.0)
    scale = 5.0 / ((1.0 + 0.15) / 0.05)  # the right wheel is the fastest
    expected = integrate((0.0, 0.0, 0.0), Twist2D(scale, 0.0, scale), 2.0)
    np.testing.assert_allclose(trace.poses[-1], expected.as_array(), atol=1e-9)
    np.testing.assert_allclose(trace.commands[-1], [1.0, 0.0, 1.0])  # what was asked


@pytest.mark.parametrize("speed", [1e306, 1e308, 1.7e308])
def test_commands_beyond_float64_wheel_speeds_still_saturate(speed: float) -> None:
    """Wheel speeds that overflow float64 are scaled down along the same direction.

    They used to make the wheel commands inf · 0 = NaN and the pose NaN.
    """
    for drive, twist in ((DIFF, Twist2D(speed, 0.0, speed)),
                         (OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2),
                          Twist2D(speed, -speed, speed))):  # fmt: skip
        limited = Robot(drive=drive, footprint=0.2, max_wheel_speed=5.0)
        small = Twist2D(twist.vx / speed, twist.vy / speed, twist.omega / speed)
        want, _ = run_constant(limited, small, 0.5)
        got, _ = run_constant(limited, twist, 0.5)
        np.testing.assert_allclose(got.poses, want.poses, rtol=1e-12, atol=1e-15)
    unlimited = Robot(drive=DIFF, footprint=0.2)
    if speed * 20.0 == math.inf:  # the wheel speed vx / r overflows: nothing to scale to
        with pytest.raises(ValueError, match=r"beyond float64 .* no max_wheel_speed"):
            run_constant(unlimited, Twist2D(speed), 0.1)


def test_encoders_wider_than_52_bits_wrap_as_unsigned_readings() -> None:
    """Backwards from zero, a counter of 53..63 bits reads 2**bits - n (as WheelEncoders.counts)."""
    for bits in (53, 60, 63):
        encoders = WheelEncoders(ticks_per_rev=1024, bits=bits)
        robot = Robot(drive=DIFF, footprint=0.2, encoders=encoders)
        _, ctrl = run_constant(robot, Twist2D(-0.5), 0.5)
        last = ctrl.readings(EncoderReading)[-1]
        angle = -0.5 / 0.05 * last.stamp
        want = encoders.ticks(np.array([angle, angle]))
        assert want.tolist() == [2**bits - 815] * 2  # floor(-10 · 0.5 / 2π · 1024) = -815
        np.testing.assert_array_equal(last.ticks, want)


def test_wheel_radius_error_moves_farther_than_odometry_says() -> None:
    from navkit.estimation import DiffOdometry

    robot = Robot(drive=DIFF, footprint=0.2, wheel_radius_error=0.1,
                  encoders=WheelEncoders(ticks_per_rev=4096, bits=16))  # fmt: skip
    odo = DiffOdometry(DIFF, ticks_per_rev=4096, bits=16)
    ctrl = Constant(Twist2D(0.5))
    trace = Simulation(World(), robot, ctrl, start=(0, 0, 0), duration=1.0, estimator=odo).run()
    assert trace.poses[-1, 0] == pytest.approx(0.55, abs=1e-9)
    assert trace.estimates[-1, 0] == pytest.approx(0.5, abs=2 * 2 * math.pi * 0.05 / 4096)


def test_slip_loses_ground_and_is_reproducible() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, wheel_slip=0.1)
    a, _ = run_constant(robot, Twist2D(0.5), 4.0, seed=3)
    b, _ = run_constant(robot, Twist2D(0.5), 4.0, seed=3)
    c, _ = run_constant(robot, Twist2D(0.5), 4.0, seed=4)
    np.testing.assert_array_equal(a.poses, b.poses)
    assert not np.array_equal(a.poses, c.poses)
    # Half-normal slip: the mean loss is 0.1 * sqrt(2 / π) ≈ 8 %.
    lost = 1.0 - a.metrics.distance / 2.0
    assert 0.06 < lost < 0.10


def test_encoders_quantise_and_wrap() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, encoders=WheelEncoders(ticks_per_rev=100, bits=8))
    trace, ctrl = run_constant(robot, Twist2D(0.5), 4.0)  # 2 m: 6.37 wheel turns, 637 ticks
    readings = ctrl.readings(EncoderReading)
    ticks = np.array([r.ticks for r in readings])
    assert ticks.dtype == np.int64 and ticks.min() >= 0 and ticks.max() < 256
    stamps = np.array([r.stamp for r in readings])
    np.testing.assert_allclose(np.diff(stamps), 0.02, atol=1e-9)  # 50 Hz
    total = tick_delta(ticks[:-1], ticks[1:], bits=8).sum(axis=0)
    turns = trace.poses[-1, 0] / (2 * math.pi * 0.05)
    np.testing.assert_allclose(total + ticks[0], math.floor(turns * 100), atol=1)


def test_compass_reads_degrees_clockwise_from_north() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, compass=Compass(bias=math.radians(2.0)))
    trace, ctrl = run_constant(robot, Twist2D(0.0, 0.0, 1.0), 10.0)
    readings = ctrl.readings(CompassReading)
    assert len(readings) == 201  # 20 Hz from t = 0 to t = 10 s, both ends included
    for r in readings:
        yaw = float(np.interp(r.stamp, trace.times, np.unwrap(trace.poses[:, 2])))
        expected = (math.degrees(math.pi / 2 - yaw) + 2.0) % 360.0
        assert 0.0 <= r.heading_deg < 360.0
        diff = (r.heading_deg - expected + 180.0) % 360.0 - 180.0
        assert abs(diff) < 1e-9


def test_compass_and_imu_noise_statistics() -> None:
    robot = Robot(
        drive=DIFF, footprint=0.2,
        compass=Compass(noise=0.05, rate=100.0),
        imu=Imu(gyro_noise=0.02, gyro_bias=0.01, accel_noise=0.1, accel_bias=-0.05, rate=100.0),
    )  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(0.0, 0.0, 0.0), 100.0)
    heading = np.array([r.heading_deg for r in ctrl.readings(CompassReading)])
    err = np.radians((heading - 90.0 + 180.0) % 360.0 - 180.0)  # facing east reads 90°
    assert abs(err.std() / 0.05 - 1.0) < 0.05 and abs(err.mean()) < 0.005
    imu = ctrl.readings(ImuReading)
    gyro = np.array([r.yaw_rate for r in imu])
    ax = np.array([r.acceleration_x for r in imu])
    assert abs(gyro.mean() - 0.01) < 0.002 and abs(gyro.std() / 0.02 - 1.0) < 0.05
    assert abs(ax.mean() + 0.05) < 0.01 and abs(ax.std() / 0.1 - 1.0) < 0.05


def test_imu_measures_body_acceleration_and_rate() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_acceleration=10.0, imu=Imu())
    _, ctrl = run_constant(robot, Twist2D(0.5, 0.0, 0.5), 2.0)
    imu = ctrl.readings(ImuReading)
    # The wheels (targets 8.5 and 11.5 rad/s) both ramp at 10 rad/s² until 0.85 s:
    # 0.5 m/s² forward and no turning; then the right one alone until 1.15 s.
    both = [r for r in imu if 0.05 < r.stamp < 0.8]
    assert both and all(r.acceleration_x == pytest.approx(0.5, abs=1e-9) for r in both)
    assert all(r.yaw_rate == pytest.approx(0.0, abs=1e-12) for r in both)
    right = [r for r in imu if 0.9 < r.stamp < 1.1]
    assert all(r.acceleration_x == pytest.approx(0.25, abs=1e-9) for r in right)
    after = [r for r in imu if r.stamp > 1.2]
    assert all(r.yaw_rate == pytest.approx(0.5, abs=1e-9) for r in after)
    # Turning at 0.5 rad/s with v = 0.5 m/s: the centripetal 0.25 m/s² to the left.
    assert all(r.acceleration_y == pytest.approx(0.25, abs=1e-9) for r in after)
    assert all(r.acceleration_x == pytest.approx(0.0, abs=1e-9) for r in after)


def test_omnidirectional_robot_moves_sideways() -> None:
    omni = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    robot = Robot(drive=omni, footprint=0.25)
    trace, _ = run_constant(robot, Twist2D(0.0, 0.3, 0.0), 2.0)
    np.testing.assert_allclose(trace.poses[-1], [0.0, 0.6, 0.0], atol=1e-9)
    assert robot.holonomic and robot.n_wheels == 3


def test_differential_robot_refuses_lateral_commands() -> None:
    robot = Robot(drive=DIFF, footprint=0.2)
    with pytest.raises(ValueError, match="sideways"):
        run_constant(robot, Twist2D(0.2, 0.1, 0.0), 1.0)


def test_polygon_footprint_collides_with_its_front_edge() -> None:
    robot = Robot(drive=DIFF, footprint=[[-0.2, -0.15], [0.3, -0.15], [0.3, 0.15],
                                         [-0.2, 0.15]])  # fmt: skip
    world = World(LineString([(2.0, -1.0), (2.0, 1.0)]))
    trace = Simulation(world, robot, Constant(Twist2D(0.5)), start=(0, 0, 0)).run()
    assert trace.metrics.reason == "collision" and trace.metrics.collisions == 1
    # The run stops at the first step whose footprint touches the wall (5 mm steps).
    assert 1.7 - 1e-9 <= trace.poses[-1, 0] <= 1.705 + 1e-9
    assert trace.metrics.min_clearance == 0.0
    assert [e.kind for e in trace.events] == ["collision"]


def test_a_polygon_footprint_with_z_is_the_2d_polygon() -> None:
    flat = [(-0.2, -0.15), (0.3, -0.15), (0.3, 0.15), (-0.2, 0.15)]
    robot = Robot(drive=DIFF, footprint=Polygon([(x, y, 1.0) for x, y in flat]))
    np.testing.assert_array_equal(robot.footprint, flat)
    world = World(LineString([(2.0, -1.0), (2.0, 1.0)]))
    assert world.clearance(Polygon([(x, y, 1.0) for x, y in flat]), (0, 0, 0)) == 1.7
    trace = Simulation(world, robot, Constant(Twist2D(0.5)), start=(0, 0, 0)).run()
    assert trace.metrics.reason == "collision"
    assert 1.7 - 1e-9 <= trace.poses[-1, 0] <= 1.705 + 1e-9


@pytest.mark.parametrize("inf", [math.inf, np.float64(np.inf), np.float32(np.inf)])
def test_an_infinite_limit_of_any_float_type_is_no_limit(inf: Any) -> None:
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_speed=inf, max_wheel_acceleration=inf)
    assert robot.max_wheel_speed == robot.max_wheel_acceleration == math.inf


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"footprint": -0.2}, ValueError),
        ({"footprint": "round"}, TypeError),
        ({"footprint": box(0, 0, 1, 1).exterior}, TypeError),
        ({"footprint": 0.2, "max_wheel_speed": -1.0}, ValueError),
        ({"footprint": 0.2, "max_wheel_acceleration": 0.0}, ValueError),
        ({"footprint": 0.2, "wheel_slip": 1.5}, ValueError),
        ({"footprint": 0.2, "wheel_radius_error": [0.1, 0.2, 0.3]}, ValueError),
        ({"footprint": 0.2, "wheel_radius_error": 0.9}, ValueError),
        ({"footprint": 0.2, "lidar": "rplidar"}, TypeError),
    ],
)
def test_bad_robots(kwargs: dict[str, Any], error: type[Exception]) -> None:
    with pytest.raises(error):
        Robot(drive=DIFF, **kwargs)
    with pytest.raises(TypeError, match="drive"):
        Robot(drive="diff", footprint=0.2)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("factory", "kwargs"),
    [
        (Lidar, {"rate": -10.0}),
        (Lidar, {"n_beams": 0}),
        (Lidar, {"latency": -0.5}),
        (Lidar, {"range_min": 5.0, "range_max": 4.0}),
        (Lidar, {"fov": 7.0}),
        (Lidar, {"dropout": 1.5}),
        (Compass, {"rate": -1.0}),
        (Compass, {"noise": -0.1}),
        (Imu, {"rate": 0.0}),
        (Imu, {"gyro_noise": -1.0}),
        (WheelEncoders, {"rate": -50.0}),
        (WheelEncoders, {"ticks_per_rev": 0.5}),
        (WheelEncoders, {"bits": 80}),
    ],
)
def test_bad_sensor_configuration(factory: Any, kwargs: dict[str, Any]) -> None:
    with pytest.raises(ValueError):
        factory(**kwargs)
    with pytest.raises(TypeError):
        Lidar(n_beams=2.5)  # type: ignore[arg-type]


def test_the_trace_keeps_the_controllers_command_at_a_collision() -> None:
    """Trace.commands is the controller's latest output: a collision stops the wheels only."""
    robot = Robot(drive=DIFF, footprint=0.2)
    world = World(LineString([(2.0, -1.0), (2.0, 1.0)]))
    trace = Simulation(world, robot, Constant(Twist2D(0.5)), start=(0, 0, 0)).run()
    assert trace.metrics.reason == "collision"
    np.testing.assert_array_equal(trace.commands[-1], [0.5, 0.0, 0.0])


def test_after_a_collision_the_robot_can_drive_away() -> None:
    """With end_on_collision=False the run goes on: the robot obeys later commands.

    The clearance search was limited by the run's smallest clearance, 0 after the
    first contact, so every later step read as a contact and the robot never moved
    again (nor could a second collision be counted).
    """

    def forward_then_back(obs: Observation) -> Twist2D:
        return Twist2D(0.5 if obs.t < 3.0 else -0.5)

    robot = Robot(drive=DIFF, footprint=0.2)
    world = World(LineString([(1.5, -1.0), (1.5, 1.0)]))
    trace = Simulation(world, robot, forward_then_back, start=(0, 0, 0), duration=5.0,
                       end_on_collision=False).run()  # fmt: skip
    assert trace.metrics.reason == "timeout" and trace.metrics.min_clearance == 0.0
    assert trace.poses[-1, 0] == pytest.approx(0.295, abs=0.01)  # backed off at 0.5 m/s for 2 s
    # Pushing on from where it was put back is the same collision.
    assert trace.metrics.collisions == 1


@pytest.mark.parametrize("shape", [box(-1.0, -1.0, 1.0, 1.0), 1.0])
def test_a_moving_obstacle_landing_over_the_robot_is_a_collision(shape: Any) -> None:
    """An obstacle that jumps onto the robot in one step touches no boundary but holds it."""
    mover = MovingObstacle.scripted(shape, [(-10.0, 0.0), (0.0, 0.0)], times=[1.0, 1.005])
    world = World(box(-20.0, -20.0, 20.0, 20.0).exterior, moving=[mover])
    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(world, robot, Constant(Twist2D(0.0)), start=(0, 0, 0), duration=3.0).run()
    assert trace.metrics.reason == "collision" and trace.metrics.collisions == 1
    assert trace.times[-1] == pytest.approx(1.01)
    assert trace.metrics.min_clearance == 0.0


def test_a_held_robot_hit_again_by_a_moving_obstacle_counts_two_collisions() -> None:
    """A standing robot hit by two balls in turn: two collisions, the second one counted.

    After the first contact, with end_on_collision=False, every later step used
    to read as a contact, so the second ball was never counted.
    """
    path = [(1.0, 0.0), (0.25, 0.0), (1.0, 0.0)]
    balls = [MovingObstacle.scripted(0.1, path, times=[t, t + 0.5, t + 1.0]) for t in (0.5, 2.0)]
    world = World(moving=balls)
    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(world, robot, Constant(Twist2D(0.0)), start=(0, 0, 0), duration=4.0,
                       end_on_collision=False).run()  # fmt: skip
    assert trace.metrics.collisions == 2
    times = [e.t for e in trace.events if e.kind == "collision"]
    # Each ball touches the disc when its centre reaches x = 0.3 m, 0.7 m in at 1.5 m/s.
    assert times == pytest.approx([0.5 + 0.7 / 1.5, 2.0 + 0.7 / 1.5], abs=0.011)


def test_every_collision_gets_its_event_beyond_a_thousand() -> None:
    """A ball hitting a standing robot ten times a second for two minutes: 1200 events.

    The kernel wrote the collision times into a buffer of 1024, so later ones
    were counted but had no event, though Trace.events promises every one.
    """
    ball = MovingObstacle.scripted(0.1, [(1.0, 0.0), (0.25, 0.0), (1.0, 0.0)],
                                   times=[0.0, 0.05, 0.1], after="loop")  # fmt: skip
    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(World(moving=[ball]), robot, Constant(Twist2D(0.0)), start=(0, 0, 0),
                       duration=120.0, end_on_collision=False).run()  # fmt: skip
    events = [e.t for e in trace.events if e.kind == "collision"]
    assert trace.metrics.collisions > 1100
    assert len(events) == trace.metrics.collisions
    assert events == sorted(events) and events[-1] > 119.0
