"""OmniOdometry.reset(pose), as DiffOdometry.reset (review 21, API consistency).

Either odometry can be re-anchored the same way (after a localisation fix, at
the start of a new run). OmniOdometry takes increments, so there are no
counters to forget: ``reset()`` changes nothing, ``reset(pose)`` continues as
a new odometry started at ``pose`` would, bit for bit (also far from the
origin, where the steps are summed apart from the start).
"""

from __future__ import annotations

import copy
import inspect
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import OmniDrive

DRIVE = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


def _steps(seed: int, n: int = 40) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    return rng.normal(0.0, 0.3, (n, DRIVE.n_wheels)), rng.uniform(-math.pi, math.pi, n)


def test_the_signature_is_diff_odometrys() -> None:
    assert inspect.signature(OmniOdometry.reset) == inspect.signature(DiffOdometry.reset)


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-6e6, 6e6),
    st.floats(-6e6, 6e6),
    st.floats(-math.pi, math.pi, exclude_min=True),
    st.integers(0, 2**32 - 1),
    st.booleans(),
)
def test_reset_continues_as_a_new_odometry_at_the_pose(
    x: float, y: float, theta: float, seed: int, one_by_one: bool
) -> None:
    increments, yaws = _steps(seed)
    odo = OmniOdometry(DRIVE, pose=(1234.5, -2.25, 0.5))
    odo.update_batch(increments[:10], yaws[:10])  # somewhere else first
    odo.reset(Pose2D(x, y, theta))
    assert odo.pose == Pose2D(x, y, theta)
    fresh = OmniOdometry(DRIVE, pose=(x, y, theta))
    if one_by_one:
        for inc, yaw in zip(increments, yaws, strict=True):
            assert odo.update(inc, float(yaw)) == fresh.update(inc, float(yaw))
    else:
        assert np.array_equal(
            odo.update_batch(increments, yaws), fresh.update_batch(increments, yaws)
        )
    assert odo.pose == fresh.pose
    assert copy.deepcopy(odo).pose == fresh.pose


def test_reset_without_a_pose_changes_nothing() -> None:
    increments, yaws = _steps(7)
    odo = OmniOdometry(DRIVE, pose=(512345.25, 5123456.5, 0.3))
    twin = OmniOdometry(DRIVE, pose=(512345.25, 5123456.5, 0.3))
    for k in range(len(yaws)):
        odo.reset()
        assert odo.update(increments[k], float(yaws[k])) == twin.update(
            increments[k], float(yaws[k])
        )


def test_reset_takes_what_the_constructor_takes() -> None:
    odo = OmniOdometry(DRIVE)
    for pose in (
        [1.0, 2.0, 0.5],
        (1.0, 2.0, 0.5),
        np.array([1.0, 2.0, 0.5]),
        Pose2D(1.0, 2.0, 0.5),
    ):
        odo.reset(pose)
        assert odo.pose == OmniOdometry(DRIVE, pose=pose).pose
    odo.reset((1.0, 2.0, 4.0))  # wrapped, as the constructor wraps it
    assert odo.pose == OmniOdometry(DRIVE, pose=(1.0, 2.0, 4.0)).pose
    assert -math.pi < odo.pose.theta <= math.pi


@pytest.mark.parametrize(
    ("pose", "error"),
    [((math.nan, 0.0, 0.0), ValueError), ((0.0, 0.0), ValueError), ("origin", TypeError)],
)
def test_a_bad_pose_is_refused_and_the_odometry_is_unchanged(
    pose: object, error: type[Exception]
) -> None:
    odo = OmniOdometry(DRIVE, pose=(3.0, 4.0, 0.1))
    increments, yaws = _steps(3, 5)
    odo.update_batch(increments, yaws)
    before = odo.pose
    with pytest.raises(error, match=r"^pose\b"):
        odo.reset(pose)  # type: ignore[arg-type]
    assert odo.pose == before
    twin = OmniOdometry(DRIVE, pose=(3.0, 4.0, 0.1))
    twin.update_batch(increments, yaws)
    assert odo.update(increments[0], 0.2) == twin.update(increments[0], 0.2)
