"""Eighth review of the simulator: encoder tick boundaries, LiDAR pose bound, DelayLine copies."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from constant_controller import run_constant
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import EncoderReading, Lidar, Robot, WheelEncoders, World
from navkit.sim._latency import DelayLine
from navkit.sim._world import MAX_POSE_COORD

_TPR = st.integers(1, 100_000).map(float)


def _boundary(k: float, tpr: float) -> float:
    """The documented boundary angle of tick ``k``: ``(k / ticks_per_rev) * (2 * math.pi)``."""
    return (k / tpr) * (2.0 * math.pi)


@settings(max_examples=60)
@given(tpr=_TPR, n=st.integers(-10_000, 10_000))
def test_whole_turns_read_whole_revolutions_of_ticks(tpr: float, n: int) -> None:
    # floor(n * 2π · tpr / 2π) used to read n·tpr - 1 where the product rounded down
    # (n = -13 with 1024 ticks: -13313).
    encoders = WheelEncoders(ticks_per_rev=tpr, bits=None)
    angles = np.array([n * 2 * math.pi, n * (2 * math.pi)])
    assert encoders.ticks(angles).tolist() == [n * int(tpr)] * 2


def test_whole_turns_at_1024_ticks_that_used_to_read_one_less() -> None:
    encoders = WheelEncoders(ticks_per_rev=1024, bits=None)
    for n in (-47, -29, -26, -13):
        assert encoders.ticks(np.array([n * 2 * math.pi])).tolist() == [n * 1024]


@settings(max_examples=60)
@given(tpr=st.floats(1.0, 1e6), k=st.integers(-(10**6), 10**6))
def test_each_tick_starts_at_its_boundary_angle(tpr: float, k: int) -> None:
    """Tick ``k`` reads from its boundary angle on, ``k - 1`` just below it."""
    encoders = WheelEncoders(ticks_per_rev=tpr, bits=None)
    at = _boundary(float(k), tpr)
    below = math.nextafter(at, -math.inf)
    # Ticks at least 2π / 1e6 rad apart, far more than ulp(|angle| <= 2π · 1e6): the
    # float just below a boundary lies above the previous one.
    assert _boundary(float(k - 1), tpr) <= below
    assert encoders.ticks(np.array([at, below])).tolist() == [k, k - 1]


def test_simulated_encoders_follow_the_same_tick_rule() -> None:
    # Wheels of 1/16 m at 8π m/s turn 128π rad/s: at 64 Hz exactly one turn (2 * math.pi)
    # per step, all products and sums exact, so after 11 steps the angle is exactly
    # 11 * 2 * math.pi. The kernel's floor(angle * 360 / 2π) read 3959 there.
    drive = DiffDrive(track=0.3, wheel_radius=0.0625)
    encoders = WheelEncoders(ticks_per_rev=360, bits=None, rate=64.0)
    robot = Robot(drive=drive, footprint=0.2, encoders=encoders)
    _, ctrl = run_constant(robot, Twist2D(8.0 * math.pi), 0.25, rate=64.0, control_rate=64.0)
    readings = ctrl.readings(EncoderReading)
    assert len(readings) == 17
    for k, reading in enumerate(readings):
        assert reading.stamp * 64.0 == k
        angle = k * 2 * math.pi
        assert reading.ticks.tolist() == [360 * k] * 2
        assert reading.ticks.tolist() == encoders.ticks(np.array([angle, angle])).tolist()


_ROOM = World(box(0.0, 0.0, 4.0, 3.0).exterior)


@pytest.mark.parametrize(
    "pose",
    [(1e13, 0.0, 0.0), (0.0, -2e12, 0.0), (-1.7e308, 1.0, 0.0), Pose2D(1e12, 1.5e12, 0.0)],
)
def test_lidar_refuses_poses_beyond_the_simulator_bound(pose: Any) -> None:
    # It used to scan from 1e13 m (all beams +inf) although World.raycast and
    # Simulation refuse such poses.
    lidar = Lidar(n_beams=4, noise=None)
    with pytest.raises(ValueError, match="pose"):
        lidar.scan(_ROOM, pose)


def test_lidar_scans_at_the_pose_bound() -> None:
    lidar = Lidar(n_beams=4, noise=None)
    for x, y in ((MAX_POSE_COORD, -MAX_POSE_COORD), (-MAX_POSE_COORD, MAX_POSE_COORD)):
        ranges = lidar.scan(_ROOM, (x, y, 0.0)).ranges
        np.testing.assert_array_equal(ranges, np.full(4, np.inf))


def test_delay_line_copies_hold_their_own_queue(duplicate: Callable[[Any], Any]) -> None:
    # copy.copy shared the deque: a push to the copy was delivered by the original.
    line: DelayLine[str] = DelayLine(0.5)
    line.push_at(0.5, "a")
    twin = duplicate(line)
    twin.push_at(0.6, "b")
    assert (len(line), len(twin)) == (1, 2)
    assert line.pop_due(10.0) == [(0.5, "a")]
    assert twin.pop_due(10.0) == [(0.5, "a"), (0.6, "b")]
    assert twin.delay == line.delay == 0.5


class _TaggedLine(DelayLine[str]):
    __slots__ = ("tag",)
    tag: str


def test_delay_line_subclass_copies_keep_their_slots() -> None:
    import copy

    line = _TaggedLine(0.25)
    line.tag = "lidar"
    line.push_at(1.25, "x")
    twin = copy.copy(line)
    assert type(twin) is _TaggedLine and twin.tag == "lidar"
    twin.pop_due(2.0)
    assert len(line) == 1 and len(twin) == 0
