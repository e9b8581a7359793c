"""Omni-wheel mounting angles written in degrees warn (they make a valid but wrong drive)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from navkit.kinematics import OmniDrive


def test_whole_degrees_warn_and_name_np_radians() -> None:
    with pytest.warns(UserWarning, match="wheel_angles .*look like degrees") as record:
        OmniDrive([30, 150, 270], wheel_radius=0.05, base_radius=0.2)
    assert "np.radians" in str(record[0].message)
    assert record[0].filename == __file__  # points at the caller's line


@pytest.mark.parametrize(
    "angles",
    [
        np.radians([30.0, 150.0, 270.0]),
        [0.0, 2.0, 4.0],  # whole radians within a turn
        [0.5, 7.0, 3.0],  # beyond a turn, not all whole
        [-math.pi, -1.0, 1.0, 3.0],
    ],
)
def test_radian_layouts_do_not_warn(angles: list[float]) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        OmniDrive(angles, wheel_radius=0.05, base_radius=0.2)
    OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
