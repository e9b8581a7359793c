"""The simulation loop: latency, estimators, reproducibility, metrics, ends of runs, bad input."""

from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from shapely.geometry import LineString, box

from navkit.estimation import DiffOdometry, OmniOdometry, PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.sim import (
    Circle,
    Compass,
    EncoderReading,
    Imu,
    Lidar,
    MovingObstacle,
    Observation,
    Robot,
    ScanReading,
    Simulation,
    WheelEncoders,
    World,
)

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
ROOM = World(box(-1.0, -3.0, 9.0, 3.0).exterior)


class GoTo:
    """Turn toward a goal and drive to it, on the estimate when there is one."""

    def __init__(self, goal: tuple[float, float], *, use_truth: bool = False) -> None:
        self.goal = goal
        self.use_truth = use_truth
        self.seen: list[Observation] = []

    def __call__(self, obs: Observation) -> Twist2D:
        self.seen.append(obs)
        pose = obs.true_pose if self.use_truth or obs.estimate is None else obs.estimate
        dx, dy = self.goal[0] - pose.x, self.goal[1] - pose.y
        err = (math.atan2(dy, dx) - pose.theta + math.pi) % (2 * math.pi) - math.pi
        v = 0.0 if abs(err) > 0.5 else min(0.4, math.hypot(dx, dy))
        return Twist2D(v, 0.0, max(-1.5, min(1.5, 2.0 * err)))


def full_robot(**kwargs: Any) -> Robot:
    return Robot(
        drive=DIFF,
        footprint=0.2,
        max_wheel_speed=20.0,
        max_wheel_acceleration=40.0,
        wheel_slip=0.02,
        encoders=WheelEncoders(ticks_per_rev=2048, bits=16),
        imu=Imu(gyro_noise=0.01, accel_noise=0.05),
        compass=Compass(noise=0.02),
        lidar=Lidar(n_beams=90, angle_jitter=0.002, dropout=0.01),
        **kwargs,
    )


def fusion_at(pose: Pose2D) -> PlanarFusion:
    return PlanarFusion(x0=[pose.x, pose.y, pose.theta, 0.0, 0.0, 0.0], t0=0.0)


def test_runs_are_reproducible() -> None:
    start = Pose2D(0.0, 0.0, 0.0)

    def once(seed: int) -> Any:
        sim = Simulation(ROOM, full_robot(), GoTo((6.0, 1.5)), start=start, goal=(6.0, 1.5),
                         estimator=fusion_at(start), seed=seed, record_scans=True)  # fmt: skip
        return sim.run()

    a, b, c = once(5), once(5), once(6)
    for name in ("times", "poses", "estimates", "commands"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    # Field by field with NaN equal to NaN (this run has no reference path: NaN
    # cross-track figures). ``a.metrics == b.metrics`` held before Python 3.13 only
    # because both NaNs are ``math.nan`` itself; 3.13's dataclass ``__eq__`` compares
    # the fields with ``==`` one by one, without tuples' identity shortcut.
    np.testing.assert_equal(dataclasses.astuple(a.metrics), dataclasses.astuple(b.metrics))
    np.testing.assert_array_equal(a.scans[-1].scan.ranges, b.scans[-1].scan.ranges)
    assert not np.array_equal(a.poses, c.poses)
    assert a.metrics.reached and a.metrics.reason == "goal reached"
    assert a.metrics.estimate_error < 0.1


def test_latency_delivers_stale_readings() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, lidar=Lidar(n_beams=8, latency=0.5, noise=None),
                  encoders=WheelEncoders(latency=0.08))  # fmt: skip
    ctrl = GoTo((5.0, 0.0), use_truth=True)
    Simulation(ROOM, robot, ctrl, start=(0, 0, 0), duration=3.0, stop_at_goal=False).run()
    for obs in ctrl.seen:
        if obs.t < 0.5 - 1e-9:
            assert obs.scan is None
        else:
            assert obs.scan is not None
            assert 0.5 - 1e-9 <= obs.t - obs.scan.stamp < 0.6
        if obs.t >= 0.08:
            assert obs.encoders is not None
            assert 0.08 - 1e-9 <= obs.t - obs.encoders.stamp < 0.08 + 0.02 + 1e-9
    # ``new`` holds every reading once, in delivery order.
    scans = [r for obs in ctrl.seen for r in obs.new if isinstance(r, ScanReading)]
    stamps = [r.stamp for r in scans]
    assert stamps == sorted(stamps) and len(set(stamps)) == len(stamps)
    assert len(scans) == 26  # taken at 0.0 ... 2.5 s, delivered by 3.0 s


@pytest.mark.parametrize("kind", ["fusion", "diff", "omni"])
def test_estimators_follow_the_robot(kind: str) -> None:
    start = Pose2D(0.0, -1.0, 0.3)
    if kind == "omni":
        drive: Any = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        robot = Robot(drive=drive, footprint=0.25, compass=Compass(),
                      encoders=WheelEncoders(ticks_per_rev=4096, bits=16))  # fmt: skip
        est: Any = OmniOdometry(drive, pose=start)
    else:
        robot = Robot(drive=DIFF, footprint=0.2, imu=Imu(),
                      encoders=WheelEncoders(ticks_per_rev=4096, bits=16))  # fmt: skip
        est = (
            fusion_at(start) if kind == "fusion"
            else DiffOdometry(DIFF, ticks_per_rev=4096, bits=16, pose=start)
        )  # fmt: skip
    trace = Simulation(ROOM, robot, GoTo((6.0, 1.0)), start=start, goal=(6.0, 1.0),
                       estimator=est).run()  # fmt: skip
    m = trace.metrics
    assert m.reached and m.collisions == 0
    assert m.estimate_error < 0.02
    assert np.all(np.isfinite(trace.estimates[5:]))
    assert m.final_error_estimated < m.final_error + 0.02


def test_the_estimators_initial_pose_is_seen_before_its_first_reading() -> None:
    """With latency the first reading arrives late; the estimator's pose exists from t = 0."""
    start = Pose2D(1.0, 0.5, 0.3)
    robot = Robot(drive=DIFF, footprint=0.2, encoders=WheelEncoders(latency=0.2))
    est = DiffOdometry(DIFF, ticks_per_rev=WheelEncoders().ticks_per_rev, pose=start)
    ctrl = GoTo((5.0, 0.5), use_truth=True)
    trace = Simulation(ROOM, robot, ctrl, start=start, duration=0.5, estimator=est).run()
    early = [obs for obs in ctrl.seen if obs.t < 0.2 - 1e-9]
    assert early and all(obs.encoders is None and obs.estimate == start for obs in early)
    np.testing.assert_array_equal(trace.estimates[:20], np.tile([1.0, 0.5, 0.3], (20, 1)))
    assert np.all(np.isfinite(trace.estimates))


def test_trace_estimates_never_hold_later_readings() -> None:
    """Row k holds the estimate after the readings delivered by step k, none delivered later.

    Encoders at 50 Hz, control at 20 Hz: several readings reach the estimator at each
    control step; the rows in between must not see the later ones.
    """
    start = Pose2D(0.0, 0.0, 0.2)
    robot = Robot(drive=DIFF, footprint=0.2, encoders=WheelEncoders(ticks_per_rev=4096))
    est = DiffOdometry(DIFF, ticks_per_rev=4096, pose=start)
    ctrl = GoTo((5.0, 1.5), use_truth=True)
    trace = Simulation(ROOM, robot, ctrl, start=start, duration=1.0, estimator=est).run()
    # Replay: the odometry fed with every reading delivered by each row's time.
    readings = [r for obs in ctrl.seen for r in obs.new if isinstance(r, EncoderReading)]
    replay = DiffOdometry(DIFF, ticks_per_rev=4096, pose=start)
    expected, k = [], 0
    for t in trace.times:
        while k < len(readings) and readings[k].stamp <= t + 1e-9:
            replay.update(int(readings[k].ticks[0]), int(readings[k].ticks[1]))
            k += 1
        p = replay.pose
        expected.append((p.x, p.y, p.theta))
    assert trace.estimates[:, 0].max() > 0.3  # it moved
    np.testing.assert_array_equal(trace.estimates, np.array(expected))


def test_a_user_estimator_is_read_through_its_pose() -> None:
    """An ``xyt`` attribute of the user's own is not taken for the internal fast path."""

    class Stamps:
        def __init__(self) -> None:
            self.xyt = [0.0, 0.0, 0.0]  # the user's own attribute

        def observe(self, t: float, reading: object) -> None:
            self.xyt[0] = t

        @property
        def pose(self) -> Pose2D:
            return Pose2D(self.xyt[0], 0.0, 0.0)

    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(ROOM, robot, lambda obs: Twist2D(0.1), start=(0, 0, 0), duration=0.2,
                       estimator=Stamps()).run()  # fmt: skip
    # Encoder readings every 0.02 s, each delivered at once.
    np.testing.assert_allclose(trace.estimates[:, 0], np.floor(trace.times / 0.02 + 1e-9) * 0.02)

    class Tuple(Stamps):
        @property
        def pose(self) -> Any:
            return (1.0, 2.0, 0.0)

    with pytest.raises(TypeError, match=r"estimator\.pose must be a Pose2D"):
        Simulation(ROOM, robot, lambda obs: Twist2D(0.1), start=(0, 0, 0), duration=0.2,
                   estimator=Tuple()).run()  # fmt: skip


def test_a_very_slow_controller_runs_without_huge_buffers() -> None:
    """One control step in a short run: the buffers follow the run, not the control period."""
    calls: list[float] = []

    def once(obs: Observation) -> Twist2D:
        calls.append(obs.t)
        return Twist2D(0.3)

    robot = Robot(drive=DIFF, footprint=0.2, wheel_slip=0.01, imu=Imu(), compass=Compass())
    trace = Simulation(ROOM, robot, once, start=(0, 0, 0), duration=2.0, control_rate=1e-9).run()
    assert calls == [0.0] and len(trace) == 201 and trace.metrics.reason == "timeout"
    assert trace.poses[-1, 0] == pytest.approx(0.6, abs=0.01)


def test_a_run_that_cannot_finish_times_out() -> None:
    sim = Simulation(ROOM, Robot(drive=DIFF, footprint=0.2), lambda obs: Twist2D(0.0),
                     start=(0, 0, 0), goal=(5.0, 0.0), duration=2.5)  # fmt: skip
    trace = sim.run()
    m = trace.metrics
    assert (m.reason, m.reached, m.duration) == ("timeout", False, 2.5)
    assert math.isnan(m.time_to_goal) and m.final_error == pytest.approx(5.0)
    assert trace.events[-1].kind == "timeout"
    with pytest.raises(RuntimeError, match="once"):
        sim.run()


def test_wall_clock_timeout() -> None:
    def slow(obs: Observation) -> Twist2D:
        time.sleep(0.01)
        return Twist2D(0.0)

    sim = Simulation(ROOM, Robot(drive=DIFF, footprint=0.2), slow, start=(0, 0, 0),
                     duration=1000.0, wall_timeout=0.1)  # fmt: skip
    m = sim.run().metrics
    assert m.reason == "wall-clock timeout" and m.duration < 100.0


def test_controller_done_ends_the_run() -> None:
    class Brief:
        done = False

        def __call__(self, obs: Observation) -> Twist2D:
            self.done = obs.t >= 1.0
            return Twist2D(0.2)

    m = Simulation(ROOM, Robot(drive=DIFF, footprint=0.2), Brief(), start=(0, 0, 0)).run().metrics
    assert m.reason == "controller done" and m.duration == pytest.approx(1.0)


def test_pushing_into_a_wall_without_ending_the_run() -> None:
    world = World(LineString([(1.0, -1.0), (1.0, 1.0)]))
    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(world, robot, lambda obs: Twist2D(0.5), start=(0, 0, 0), duration=3.0,
                       end_on_collision=False).run()  # fmt: skip
    m = trace.metrics
    assert m.reason == "timeout" and m.collisions == 1 and m.min_clearance == 0.0
    # The robot is held where it was before touching, never inside the wall.
    assert trace.poses[:, 0].max() < 0.8
    assert trace.poses[-1, 0] == pytest.approx(0.8, abs=0.006)


def test_goal_yaw_and_metrics() -> None:
    class Turn:
        def __call__(self, obs: Observation) -> Twist2D:
            return Twist2D(0.0, 0.0, 0.5)

    sim = Simulation(ROOM, Robot(drive=DIFF, footprint=0.2), Turn(), start=(0, 0, 0),
                     goal=(0.0, 0.0, 1.0), yaw_tolerance=0.01)  # fmt: skip
    m = sim.run().metrics
    assert m.reached and m.time_to_goal == pytest.approx(1.98, abs=0.011)
    assert m.distance == pytest.approx(0.0)


def test_cross_track_and_clearance() -> None:
    """Driving along y = 0.1 past a pillar: cross-track 0.1 m to the path y = 0."""
    world = World([Circle((3.0, 1.0), 0.3), box(-2.0, -3.0, 9.0, 3.0).exterior])
    robot = Robot(drive=DIFF, footprint=0.2)
    trace = Simulation(world, robot, lambda obs: Twist2D(0.5), start=(0.0, 0.1, 0.0),
                       goal=(6.0, 0.1), reference_path=[[0.0, 0.0], [7.0, 0.0]]).run()  # fmt: skip
    m = trace.metrics
    assert m.reached
    assert m.cross_track_mean == pytest.approx(0.1, abs=1e-9)
    assert m.cross_track_max == pytest.approx(0.1, abs=1e-9)
    assert m.min_clearance == pytest.approx(1.0 - 0.1 - 0.3 - 0.2, abs=1e-9)
    assert m.distance == pytest.approx(m.time_to_goal * 0.5, abs=0.01)


def test_min_clearance_counts_the_start_pose() -> None:
    """Starting 0.05 m from a wall and driving away: the smallest clearance is the start's."""
    world = World(box(-5.0, -5.0, 5.0, 5.0).exterior)
    robot = Robot(drive=DIFF, footprint=0.15)
    away = Simulation(world, robot, lambda obs: Twist2D(0.5), start=(-4.8, 0.0, 0.0), duration=1.0)
    assert away.run().metrics.min_clearance == pytest.approx(0.05, abs=1e-12)
    # Already at the goal: no step, and the clearance is the start's, not inf.
    there = Simulation(world, robot, lambda obs: Twist2D(0.5), start=(0.0, 0.0, 0.0), goal=(0, 0))
    assert there.run().metrics.min_clearance == pytest.approx(4.85, abs=1e-12)


def test_moving_obstacle_hits_the_robot() -> None:
    ball = MovingObstacle.constant_velocity(0.1, start_xy=(3.0, 2.0), velocity_xy=(0.0, -1.0))
    world = World(moving=[ball])
    robot = Robot(drive=DIFF, footprint=0.2)
    m = Simulation(world, robot, lambda obs: Twist2D(0.0), start=(3.0, 0.0, 0.0),
                   duration=5.0).run().metrics  # fmt: skip
    assert m.reason == "collision" and m.duration == pytest.approx(1.7, abs=0.011)


def test_readings_carry_time_stamps_and_scans_are_recorded() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, lidar=Lidar(n_beams=36), encoders=WheelEncoders())
    ctrl = GoTo((5.0, 0.0), use_truth=True)
    trace = Simulation(ROOM, robot, ctrl, start=(0, 0, 0), duration=1.0, record_scans=True).run()
    assert [round(s.stamp, 9) for s in trace.scans] == [round(0.1 * k, 9) for k in range(11)]
    enc = [r for obs in ctrl.seen for r in obs.new if isinstance(r, EncoderReading)]
    assert [round(r.stamp, 9) for r in enc[:3]] == [0.0, 0.02, 0.04]
    assert not trace.poses.flags.writeable and len(trace) == 101


def test_closed_loop_on_a_real_map(shared_data: Path) -> None:
    """A* on the TurtleBot3 world, followed on the fused pose: the goal, without collision."""
    grid = OccupancyGrid.load(shared_data / "ros-map-server-maps/turtlebot3_world/map.yaml")
    start = Pose2D(-2.0, -0.5, 0.0)
    goal = (1.8, 0.6)
    route = MapPlanner(grid, robot_radius=0.25).plan(start, goal)
    points = [tuple(p) for p in route.points]

    class Follow:
        def __init__(self) -> None:
            self.k = 1

        def __call__(self, obs: Observation) -> Twist2D:
            pose = obs.estimate or obs.true_pose
            while self.k < len(points) - 1 and math.dist(points[self.k], (pose.x, pose.y)) < 0.2:
                self.k += 1
            return GoTo(points[self.k])(obs)

    robot = full_robot()
    trace = Simulation(World(grid=grid), robot, Follow(), start=start, goal=goal,
                       estimator=fusion_at(start), reference_path=route, duration=120.0).run()
    m = trace.metrics
    assert m.reached and m.collisions == 0, m
    assert m.cross_track_max < 0.3


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"rate": -100.0}, ValueError, "rate"),
        ({"control_rate": 0.0}, ValueError, "control_rate"),
        ({"control_rate": 200.0}, ValueError, "must not exceed"),
        ({"duration": -1.0}, ValueError, "duration"),
        ({"duration": 1e6, "rate": 1000.0}, ValueError, "physics steps"),
        ({"start": (0.5, 2.9, 0.0)}, ValueError, "starts inside an obstacle"),
        ({"start": "origin"}, TypeError, "start"),
        ({"start": (1e300, 0.0, 0.0)}, ValueError, r"^start must lie within ±1e\+12 m"),
        ({"goal_tolerance": 0.0}, ValueError, "goal_tolerance"),
        ({"goal": (1.0, 2.0), "yaw_tolerance": 0.1}, ValueError, "heading"),
        ({"goal": (1.0, 2.0, 3.0, 4.0)}, ValueError, "goal"),
        ({"estimator": "ekf"}, TypeError, "estimator"),
        ({"seed": -1}, ValueError, "seed"),
        ({"seed": 1.5}, TypeError, "seed"),
        ({"reference_path": [[1.0, 2.0, 3.0]]}, ValueError, "reference_path"),
        ({"wall_timeout": -1.0}, ValueError, "wall_timeout"),
    ],
)
def test_bad_simulation_configuration(kwargs: dict[str, Any], error: type[Exception],
                                      match: str) -> None:  # fmt: skip
    args: dict[str, Any] = {"start": (0.0, 0.0, 0.0), **kwargs}
    with pytest.raises(error, match=match):
        Simulation(ROOM, Robot(drive=DIFF, footprint=0.2), lambda obs: Twist2D(0.0), **args)


def test_bad_simulation_parts() -> None:
    robot = Robot(drive=DIFF, footprint=0.2)
    with pytest.raises(TypeError, match="world"):
        Simulation("room", robot, lambda obs: Twist2D(0.0), start=(0, 0, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="robot"):
        Simulation(ROOM, DIFF, lambda obs: Twist2D(0.0), start=(0, 0, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="controller"):
        Simulation(ROOM, robot, Twist2D(0.0), start=(0, 0, 0))  # type: ignore[arg-type]
    fast = Robot(drive=DIFF, footprint=0.2, imu=Imu(rate=500.0))
    with pytest.raises(ValueError, match=r"robot\.imu\.rate"):
        Simulation(ROOM, fast, lambda obs: Twist2D(0.0), start=(0, 0, 0))
    with pytest.raises(TypeError, match="None"):
        Simulation(ROOM, robot, lambda obs: None, start=(0, 0, 0)).run()  # type: ignore[arg-type,return-value]
    with pytest.raises(ValueError, match="compass"):
        Simulation(ROOM, Robot(drive=OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2),
                               footprint=0.2), lambda obs: Twist2D(0.0), start=(0, 0, 0),
                   estimator=OmniOdometry(OmniDrive.three_wheel(wheel_radius=0.05,
                                                                base_radius=0.2)))  # fmt: skip
