"""A NumPy array row as the left operand of a pose's operators.

``ScanMapper.update``'s docstring composes a mounting offset as
``robot_odometry @ mount``; with the odometry a row of an array (a
``BagOdometry.poses`` row) that raised NumPy's "matmul: Input operand 1 does
not have enough dimensions", and ``row == pose`` compared each element with
the pose (so ``pose in [row]`` raised "truth value ... ambiguous"). A pose (and
a twist) now sets ``__array_ufunc__ = None``, so NumPy defers to its reflected
operators: ``row @ pose`` composes as ``Pose2D.from_array(row) @ pose`` and
``row == pose`` is False.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D
from navkit.mapping import LaserScan, ScanMapper

MOUNT = Pose2D(0.12, -0.03, 0.25)


def test_an_array_row_composes_as_the_pose_it_holds() -> None:
    poses = np.array([[1.0, 2.0, 0.5], [-3.0, 0.25, -2.9], [1e6, -1e6, math.pi]])
    before = poses.copy()
    for row in poses:
        composed = row @ MOUNT
        assert type(composed) is Pose2D
        assert composed == Pose2D.from_array(row) @ MOUNT  # bit for bit
        assert composed == Pose2D.from_array(row).compose(MOUNT)
    np.testing.assert_array_equal(poses, before)  # inputs unchanged


def test_a_list_and_a_tuple_compose_as_well() -> None:
    expected = Pose2D(1.0, 2.0, 0.5) @ MOUNT
    from_list = [1.0, 2.0, 0.5] @ MOUNT
    from_tuple = (1.0, 2.0, 0.5) @ MOUNT
    assert from_list == expected
    assert from_tuple == expected


def test_the_composition_order_is_left_then_right() -> None:
    # Not commutative: the row is the outer frame.
    row = np.array([0.0, 0.0, math.pi / 2])
    assert (row @ Pose2D(1.0, 0.0, 0.0)).y == pytest.approx(1.0, abs=1e-15)
    assert (Pose2D(1.0, 0.0, 0.0) @ row).x == 1.0


@pytest.mark.parametrize(
    ("left", "error", "words"),
    [
        (np.zeros((2, 3)), ValueError, "left operand of @ must be 1-D"),
        (np.array([1.0, 2.0]), ValueError, "left operand of @ must have length 3"),
        (np.array([1.0, math.nan, 0.0]), ValueError, "left operand of @ must contain only finite"),
        (5, TypeError, "left operand of @ must be a Pose2D or a sequence"),
        ("abc", TypeError, "left operand of @ must be a Pose2D or a sequence"),
    ],
)
def test_a_bad_left_operand_is_named(left: object, error: type[Exception], words: str) -> None:
    with pytest.raises(error, match=words):
        left @ MOUNT  # type: ignore[operator]


def test_an_array_is_not_equal_to_a_pose_or_a_twist() -> None:
    row = np.array([1.0, 2.0, 0.5])
    pose = Pose2D(1.0, 2.0, 0.5)
    twist = Twist2D(1.0, 2.0, 0.5)
    for value in (pose, twist):
        assert (row == value) is False
        assert (value == row) is False
        assert (row != value) is True
        assert (value in [row]) is False  # was "truth value ... is ambiguous"
    assert pose == Pose2D(1.0, 2.0, 0.5)  # poses still compare by value
    assert twist == Twist2D(1.0, 2.0, 0.5)


def test_numpy_still_holds_poses_and_refuses_ufuncs_with_a_type_error() -> None:
    pose = Pose2D(1.0, 2.0, 0.5)
    held = np.asarray(pose)
    assert held.dtype == object and held.shape == () and held.item() is pose
    both = np.array([pose, pose])
    assert both.dtype == object and both.shape == (2,)
    np.testing.assert_array_equal(np.array([pose.as_array(), pose.as_array()]).shape, (2, 3))
    for call in (lambda: np.add(pose, 1.0), lambda: np.isfinite(pose),
                 lambda: np.asarray([1.0, 2.0, 0.5]) + pose,
                 lambda: np.add(Twist2D(1.0), 1.0)):  # fmt: skip
        with pytest.raises(TypeError):
            call()


def test_the_mapper_docstrings_mounting_recipe_runs_on_array_rows() -> None:
    # ScanMapper.update(odometry=robot_odometry @ mount) with the odometry as rows.
    n = 90
    angles = np.linspace(-math.pi, math.pi, n, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n,
                     range_min=0.1, range_max=10.0)  # fmt: skip
    odometry = np.array([[0.0, 0.0, 0.0], [0.02, 0.0, 0.0]])
    by_rows = ScanMapper(resolution=0.1)
    by_poses = ScanMapper(resolution=0.1)
    for row in odometry:
        a = by_rows.update(scan, odometry=row @ MOUNT)
        b = by_poses.update(scan, odometry=Pose2D.from_array(row) @ MOUNT)
        assert a.pose == b.pose
