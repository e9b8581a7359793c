"""Regressions found by a review of navkit.estimation: copies of results, odometry input types."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import DiffOdometry, ExtendedKalmanFilter, UpdateResult
from navkit.kinematics import DiffDrive

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_copied_update_results_keep_a_read_only_residual(
    duplicate: Callable[[Any], Any],
) -> None:
    result = UpdateResult(False, 2.5, np.array([1.0, -2.0]), "rejected by the gate")
    twin = duplicate(result)
    assert type(twin) is UpdateResult
    assert (twin.accepted, twin.nis, twin.reason) == (False, 2.5, "rejected by the gate")
    np.testing.assert_array_equal(twin.residual, [1.0, -2.0])
    with pytest.raises(ValueError, match="read-only"):
        twin.residual[0] = 9.0


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_copying_a_filter_result_leaves_the_original_alone(
    duplicate: Callable[[Any], Any],
) -> None:
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    result = ekf.update([1.0], lambda x: x, [[1.0]], [[1.0]])
    writeable = result.residual.flags.writeable
    twin = duplicate(result)
    assert result.residual.flags.writeable == writeable  # a shallow copy changes no flag
    assert not twin.residual.flags.writeable
    np.testing.assert_array_equal(twin.residual, result.residual)
    assert twin.nis == result.nis and twin.accepted


@pytest.mark.parametrize(
    ("left", "right", "name"),
    [
        ([5], 0, "left_ticks"),
        ((5,), 0, "left_ticks"),
        (0, np.array([5]), "right_ticks"),
        (np.array([5, 6]), 0, "left_ticks"),
    ],
)
def test_diff_odometry_update_refuses_sequences_as_not_integers(
    left: object, right: object, name: str
) -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, encoder_bits=16)
    odo.update(10, 10)
    with pytest.raises(TypeError, match=f"{name} must be one integer counter reading"):
        odo.update(left, right)  # type: ignore[arg-type]
    assert odo.update(1010, 1010).x == pytest.approx(2 * np.pi * 0.1)  # unchanged, still latched


def test_diff_odometry_update_takes_zero_dimensional_readings() -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, encoder_bits=16)
    odo.update(np.array(65000), np.uint16(65000))  # type: ignore[arg-type]
    assert odo.update(np.array(464), 464).x == pytest.approx(2 * np.pi * 0.1)  # type: ignore[arg-type]
