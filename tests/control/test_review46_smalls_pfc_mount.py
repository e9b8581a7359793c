"""Review 46 (SMALLS): PotentialFieldController with a scan from a mounted LiDAR.

The controller took "a scan taken in the robot frame", but a simulated
``Lidar(mount=...)`` gives scans in the sensor frame, and nothing converted
them: a LiDAR 0.3 m ahead of the centre saw walls 0.3 m nearer than they were.
``step`` and ``desired_velocity`` now take ``mount``. The reference is the
controller's own world-point path, fed ``scan.to_points(pose @ mount)`` (what
the docstring promises), and a simulated LiDAR in a world of walls.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, box

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan
from navkit.sim import Lidar, World

_POSE = st.builds(Pose2D, st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-math.pi, math.pi))
_MOUNT = st.builds(Pose2D, st.floats(-0.4, 0.4), st.floats(-0.4, 0.4), st.floats(-math.pi, math.pi))
_WORLD = World([box(-2.0, -2.0, 2.0, 2.0).exterior, LineString([(0.6, -0.5), (0.6, 0.5)])])


def _scan(ranges: list[float]) -> LaserScan:
    n = len(ranges)
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n,
                     range_min=0.05, range_max=3.0)  # fmt: skip


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0.0, 2.0), min_size=1, max_size=30),
    _POSE,
    _MOUNT,
    st.sampled_from(["omni", "diff"]),
)
def test_a_mounted_scan_steers_as_its_world_points_do(
    ranges: list[float], pose: Pose2D, mount: Pose2D, drive: str
) -> None:
    scan = _scan(ranges)
    target = Pose2D(1.5, 0.5, 0.3)
    points = scan.to_points(pose @ mount)[np.asarray(ranges)[scan.valid_mask()] > 0.0]
    # A beam ending on the robot's centre has no direction: its side (and so its push,
    # or whether it pushes at all) is a rounding error that differs between the paths;
    # near it the direction's rounding (about 1e-15 m / d) exceeds the 1e-9 tolerance.
    assume(bool(np.all(np.hypot(points[:, 0] - pose.x, points[:, 1] - pose.y) >= 1e-5)))
    a = PotentialFieldController(drive=drive)  # type: ignore[arg-type]
    b = PotentialFieldController(drive=drive)  # type: ignore[arg-type]
    for _ in range(3):  # state (velocity limits, PID) carried alike
        got = a.step(pose, target, 0.1, obstacles=scan, mount=mount)
        want = b.step(pose, target, 0.1, obstacles=points)
        np.testing.assert_allclose(
            [got.vx, got.vy, got.omega], [want.vx, want.vy, want.omega], rtol=1e-9, atol=1e-9
        )
    np.testing.assert_allclose(
        a.desired_velocity(pose, (1.5, 0.5), obstacles=scan, mount=mount),
        b.desired_velocity(pose, (1.5, 0.5), obstacles=points),
        rtol=1e-9,
        atol=1e-9,
    )


@pytest.mark.parametrize(
    "mount", [Pose2D(0.3, 0.0, 0.0), Pose2D(-0.25, 0.1, math.pi), Pose2D(0.0, 0.0, -math.pi / 2)]
)
def test_a_simulated_mounted_lidar_with_its_mount_pushes_as_its_hits_do(mount: Pose2D) -> None:
    """A mounted Lidar's scan with ``mount=lidar.mount`` pushes as the points it hit.

    The hits are placed in the world by the simulator itself (the beams' world
    end points, from ``World.raycast`` of the sensor's pose ``pose ⊕ mount``);
    the same scan taken for one in the robot frame (the defect) pushes otherwise.
    (Not compared with an unmounted LiDAR's scan: the two sample the walls at
    different densities, and a point field sums samples.)
    """
    pose = Pose2D(-0.1, 0.05, 0.2)
    lidar = Lidar(n_beams=720, noise=None, mount=mount, range_min=0.0, range_max=5.0)
    scan = lidar.scan(_WORLD, pose)
    sensor = pose @ mount
    hits = _WORLD.raycast(sensor, scan.angles(), range_max=5.0)
    ends = np.column_stack((sensor.x + hits * np.cos(sensor.theta + scan.angles()),
                            sensor.y + hits * np.sin(sensor.theta + scan.angles())))  # fmt: skip
    ends = ends[np.isfinite(hits) & (hits < 5.0)]
    ctl = PotentialFieldController(influence_radius=0.8, k_rep=0.001)
    truth = ctl.desired_velocity(pose, (1.8, 0.0), obstacles=ends)
    with_mount = ctl.desired_velocity(pose, (1.8, 0.0), obstacles=scan, mount=lidar.mount)
    without = ctl.desired_velocity(pose, (1.8, 0.0), obstacles=scan)
    np.testing.assert_allclose(with_mount, truth, rtol=1e-9, atol=1e-12)
    assert float(np.hypot(*(without - truth))) > 0.01


def test_mount_with_world_points_is_checked_but_not_used() -> None:
    pose, target = Pose2D(0.0, 0.0, 0.2), Pose2D(2.0, 0.0, 0.0)
    points = [[0.5, 0.1], [0.3, -0.4]]
    a, b = PotentialFieldController(), PotentialFieldController()
    assert a.step(pose, target, 0.1, obstacles=points, mount=(0.3, 0.0, 1.0)) == b.step(
        pose, target, 0.1, obstacles=points
    )
    assert a.step(pose, target, 0.1, mount=(0.3, 0.0, 1.0)) == b.step(pose, target, 0.1)


@pytest.mark.parametrize(
    ("mount", "error"),
    [
        ((math.nan, 0.0, 0.0), ValueError),
        ((0.0, 0.0, math.inf), ValueError),
        ((2e9, 0.0, 0.0), ValueError),
        ("front", TypeError),
        ((1.0, 2.0), (TypeError, ValueError)),
    ],
)
def test_a_bad_mount_is_refused_naming_it_and_changes_nothing(
    mount: object, error: type[Exception]
) -> None:
    scan = _scan([0.4, 0.5, 0.6])
    ctl = PotentialFieldController()
    ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1, obstacles=scan)
    before = (ctl.previous_velocity.tolist(), ctl.stall_time, ctl.done)
    with pytest.raises(error, match=r"^mount[ :]"):
        ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1, obstacles=scan, mount=mount)
    with pytest.raises(error, match=r"^mount[ :]"):
        ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0), obstacles=scan, mount=mount)
    assert (ctl.previous_velocity.tolist(), ctl.stall_time, ctl.done) == before


def test_no_mount_is_the_identity_bit_for_bit() -> None:
    scan = _scan([0.4, 0.5, math.inf, 0.35, 0.9])
    pose, target = Pose2D(0.1, -0.2, 0.4), Pose2D(2.0, 0.0, 0.0)
    a, b = PotentialFieldController(drive="diff"), PotentialFieldController(drive="diff")
    for _ in range(3):
        assert a.step(pose, target, 0.1, obstacles=scan) == b.step(
            pose, target, 0.1, obstacles=scan, mount=Pose2D(0.0, 0.0, 0.0)
        )
