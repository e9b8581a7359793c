"""One world, robot and LiDAR for many runs and scans, against fresh ones (review 53, REUSE).

A World keeps a scanner per LiDAR (its beam table and noise arrays, at most 16,
then cleared) and the moving obstacles' placement at the last time queried;
the Simulation docstring promises that no run changes the World or the Robot
(runs may share them). A Simulation runs once, so a process runs one
Simulation per leg or trial on the same World, Robot and a tracker given each
leg's path: each run must give, bit for bit, the trace of the same run on a
World and Robot built afresh; each scan that of a fresh world.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.control import FollowTheCarrot
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Lidar,
    MovingObstacle,
    Robot,
    Simulation,
    TrackerController,
    WheelEncoders,
    World,
)


def _world() -> World:
    ball = MovingObstacle.constant_velocity(0.2, start_xy=(4.5, 0.5), velocity_xy=(-0.3, 0.2))
    return World([box(0.0, 0.0, 5.0, 3.0).exterior, box(2.2, 1.8, 2.6, 2.2)], moving=[ball])


def _robot() -> Robot:
    return Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.15,
        wheel_slip=0.02,
        encoders=WheelEncoders(ticks_per_rev=1024.0, rate=50.0),
        lidar=Lidar(n_beams=90, range_max=4.0, rate=10.0, angle_jitter=0.002, dropout=0.05),
    )


_LEGS = [
    ((0.5, 0.5, 0.0), [(0.5, 0.5), (2.0, 0.6), (3.5, 1.2)], 1),
    ((3.5, 1.2, 0.5), [(3.5, 1.2), (1.0, 2.5)], 2),
    ((1.0, 2.5, 3.0), [(1.0, 2.5), (0.6, 0.6), (4.0, 0.5)], 3),
]


def _leg(world: World, robot: Robot, tracker: FollowTheCarrot, leg: Any) -> tuple[Any, ...]:
    start, path, seed = leg
    tracker.set_path(path)
    trace = Simulation(
        world, robot, TrackerController(tracker, control_rate=20.0, use_estimate=False),
        start=start, goal=path[-1], control_rate=20.0, duration=6.0, seed=seed,
        end_on_collision=False,
    ).run()  # fmt: skip
    scans = tuple(reading.scan.ranges.tobytes() for reading in trace.scans)
    return (trace.poses.tobytes(), trace.commands.tobytes(), scans, trace.metrics.reason,
            trace.metrics.collisions)  # fmt: skip


def test_legs_run_on_one_world_robot_and_tracker_equal_fresh_ones() -> None:
    world, robot, tracker = _world(), _robot(), FollowTheCarrot(max_speed=0.6)
    for leg in _LEGS + _LEGS[::-1]:
        got = _leg(world, robot, tracker, leg)
        assert got == _leg(_world(), _robot(), FollowTheCarrot(max_speed=0.6), leg)


_LIDARS = [
    Lidar(n_beams=n, range_max=r, noise=None, mount=(0.1 * k, 0.0, 0.3 * k))
    for k, (n, r) in enumerate([(7, 3.0), (36, 4.0), (90, 6.0)])
]
_QUERY = st.tuples(
    st.integers(0, len(_LIDARS) - 1),
    st.floats(0.3, 4.7), st.floats(0.3, 2.7), st.floats(-3.1, 3.1),  # the pose
    st.sampled_from([0.0, 1.0, 2.5, 2.5, 7.0]),  # repeated times: the placement kept
    st.sampled_from([None, 5, 6]),
)  # fmt: skip


@settings(max_examples=40, deadline=None)
@given(queries=st.lists(_QUERY, min_size=1, max_size=12), extra=st.integers(0, 20))
def test_scans_of_a_reused_world_equal_a_fresh_worlds(
    queries: list[tuple[int, float, float, float, float, int | None]], extra: int
) -> None:
    world = _world()
    # More LiDARs than the world keeps scanners for (16): the cache is cleared on the way.
    for k in range(extra):
        Lidar(n_beams=3 + k, noise=None).scan(world, (1.0, 1.0, 0.0), t=float(k))
    for index, x, y, theta, t, seed in queries:
        lidar = _LIDARS[index]
        noisy = Lidar(n_beams=lidar.n_beams, range_max=lidar.range_max, mount=lidar.mount)
        for sensor, draws in ((lidar, seed), (noisy, 0 if seed is None else seed)):
            got = sensor.scan(world, (x, y, theta), t=t, seed=draws)
            want = sensor.scan(_world(), (x, y, theta), t=t, seed=draws)
            assert got.ranges.tobytes() == want.ranges.tobytes()
            assert np.array_equal(got.angles(), want.angles())
