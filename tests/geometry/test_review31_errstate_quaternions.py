"""Quaternions give NumPy's default answer whatever the caller's ``np.seterr`` (review 31).

Normalising ``(x, y, z, w)`` squares each component: a valid, normal-range
component below about 1e-154 (1e-252 beside a 1, or any part of a quaternion
one of whose components is 1e200) squares to an underflow, 0 under NumPy's
defaults. After a caller's ``np.seterr(all="raise")`` or ``under="raise"`` (a
NaN hunt) the same calls raised ``FloatingPointError``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from errstate_checks import assert_default_answer
from navkit.geometry import (
    ImuInBase,
    imu_to_base,
    quaternion_to_matrix,
    quaternion_to_yaw,
)

_IDENTITY = [0.0, 0.0, 0.0, 1.0]

_CASES: dict[str, Callable[[], Any]] = {
    "quaternion_to_yaw, z 1e-252": lambda: quaternion_to_yaw(np.array([0.0, 0.0, 1e-252, 1.0])),
    "quaternion_to_yaw, y 1e-200": lambda: quaternion_to_yaw([0.0, 1e-200, 0.0, 1.0]),
    "quaternion_to_yaw, w 1e200": lambda: quaternion_to_yaw([[0.0, 0.0, 1.0, 1e200]]),
    "quaternion_to_matrix, x 1e-200": lambda: quaternion_to_matrix([1e-200, 0.0, 0.0, 1.0]),
    "ImuInBase, x 1e-200": lambda: (
        ImuInBase([1e-200, 0.0, 0.0, 1.0], [0.0, 0.0, 0.1], [0.0, 0.0, 9.8]).orientations
    ),
    "imu_to_base, x 1e-200": lambda: (
        imu_to_base(
            [1e-200, 0.0, 0.0, 1.0], [0.0, 0.0, 0.1], [0.0, 0.0, 9.8], mount=_IDENTITY
        ).orientations
    ),
    "imu_to_base, mount z 1e-200": lambda: (
        imu_to_base(
            _IDENTITY, [0.0, 0.0, 0.1], [0.0, 0.0, 9.8], mount=[0.0, 0.0, 1e-200, 1.0]
        ).linear_accelerations
    ),
}


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_default_answer_whatever_numpys_error_state(name: str, mode: str) -> None:
    assert_default_answer(_CASES[name], mode)


def test_a_tiny_yaw_component_still_gives_its_yaw() -> None:
    with np.errstate(all="raise"):
        yaw = quaternion_to_yaw([0.0, 0.0, 1e-252, 1.0])
    assert yaw == 2e-252  # 2 atan2(z, w), exact at this size
