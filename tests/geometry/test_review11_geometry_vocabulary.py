"""Renamed geometry keywords: ``imu_to_base(mounting=)`` is now ``mount=``.

``mount`` is the name ``sim.Lidar(mount=)`` uses for a sensor's pose on the
robot; the old keyword still works for a release, with a DeprecationWarning.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from navkit.geometry import imu_to_base, quaternion_to_matrix, rpy_to_quaternion

READINGS = ([0.0, 0.0, 0.6, 0.8], [0.1, 0.0, 0.2], [0.0, -1.0, 9.8])
MOUNT = rpy_to_quaternion(0.1, -0.2, math.pi / 2)


def test_mount_does_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = imu_to_base(*READINGS, mount=MOUNT)
    # v_base = R_m v_imu for the vectors, R_m the mount's rotation matrix.
    rot = quaternion_to_matrix(MOUNT)
    np.testing.assert_allclose(out.angular_velocities, rot @ READINGS[1], atol=1e-15)
    np.testing.assert_allclose(out.linear_accelerations, rot @ READINGS[2], atol=1e-14)


def test_mounting_warns_and_gives_the_same_readings() -> None:
    new = imu_to_base(*READINGS, mount=MOUNT)
    with pytest.warns(DeprecationWarning, match="mounting is deprecated.*use mount") as rec:
        old = imu_to_base(*READINGS, mounting=MOUNT)
    assert rec[0].filename == __file__
    for name in ("orientations", "angular_velocities", "linear_accelerations"):
        np.testing.assert_array_equal(getattr(old, name), getattr(new, name))


def test_both_names_or_neither_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="both mount and its old name mounting"):
        imu_to_base(*READINGS, mount=MOUNT, mounting=MOUNT)
    with pytest.raises(TypeError, match="mount"):
        imu_to_base(*READINGS)
    with pytest.raises(ValueError, match="mount must be a non-zero quaternion"):
        imu_to_base(*READINGS, mount=[0.0, 0.0, 0.0, 0.0])
