"""Masked arrays and memoryviews in the estimation API (review 11).

numba's dispatcher takes any ndarray subclass as its data, so a masked ``F``,
``H`` or model output (``f(x)``, ``h(x)``) went straight into the compiled
predict/update with its masked entries read as numbers; and
``MeasurementLog.from_streams`` raised Python's ``NotImplementedError`` for a
stream given as a 2-D memoryview.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, MeasurementLog

F = np.array([[1.0, 0.1], [0.0, 1.0]])
H = np.array([[1.0, 0.0]])


def _ekf() -> ExtendedKalmanFilter:
    return ExtendedKalmanFilter(np.array([1.0, 2.0]), np.eye(2))


def _masked(a: np.ndarray) -> np.ma.MaskedArray:
    mask = np.zeros(a.shape, dtype=bool)
    mask.flat[0] = True
    return np.ma.array(a, mask=mask)


STEPS: list[tuple[str, Callable[[ExtendedKalmanFilter], object]]] = [
    ("F", lambda e: e.predict(lambda x: F @ x, _masked(F), 0.01 * np.eye(2))),
    ("F", lambda e: e.predict(lambda x: F @ x, lambda x: _masked(F), 0.01 * np.eye(2))),
    ("f(x)", lambda e: e.predict(lambda x: _masked(F @ x), F, 0.01 * np.eye(2))),
    ("H", lambda e: e.update(np.array([1.5]), lambda x: x[:1], _masked(H), np.eye(1))),
    ("H", lambda e: e.update(np.array([1.5]), lambda x: x[:1], lambda x: _masked(H), np.eye(1))),
    ("h(x)", lambda e: e.update(np.array([1.5]), lambda x: _masked(x[:1]), H, np.eye(1))),
]


@pytest.mark.parametrize(("name", "step"), STEPS)
def test_masked_entries_are_refused_and_leave_the_filter_unchanged(
    name: str, step: Callable[[ExtendedKalmanFilter], object]
) -> None:
    ekf = _ekf()
    ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(2))  # the kernels are warm
    ekf.update(np.array([1.5]), lambda x: x[:1], H, np.eye(1))
    x, p = ekf.x.copy(), ekf.P.copy()
    with pytest.raises(ValueError, match="^" + re.escape(name) + " has masked entries"):
        step(ekf)
    assert np.array_equal(ekf.x, x)
    assert np.array_equal(ekf.P, p)


def test_masked_arrays_without_masked_entries_are_their_data() -> None:
    plain, masked = _ekf(), _ekf()
    plain.predict(lambda x: F @ x, F, 0.01 * np.eye(2))
    masked.predict(lambda x: np.ma.array(F @ x), np.ma.array(F), 0.01 * np.eye(2))
    plain.update(np.array([1.5]), lambda x: x[:1], H, np.eye(1))
    masked.update(np.array([1.5]), lambda x: np.ma.array(x[:1]), np.ma.array(H), np.eye(1))
    assert np.array_equal(masked.x, plain.x)
    assert np.array_equal(masked.P, plain.P)


def test_a_stream_as_a_memoryview_equals_the_stream_as_an_array() -> None:
    odometry = np.array([[0.0, 0.1, 0.2], [1.0, 1.0, 1.0], [0.1, 0.1, 0.1]])
    plain = MeasurementLog.from_streams(odometry=odometry)  # type: ignore[arg-type]
    viewed = MeasurementLog.from_streams(odometry=odometry.data)  # type: ignore[arg-type]
    for field in ("times", "values", "variances", "observed"):
        assert np.array_equal(getattr(viewed, field), getattr(plain, field))


def test_a_stream_memoryview_of_the_wrong_width_is_a_value_error() -> None:
    with pytest.raises(ValueError, match=r"^yaw must be a tuple of 2 arrays, got 3"):
        MeasurementLog.from_streams(yaw=np.zeros((3, 1)).data)  # type: ignore[arg-type]


def test_angle_indices_as_a_two_d_memoryview_are_a_type_error() -> None:
    indices = np.zeros((1, 1), dtype=np.int64).data
    with pytest.raises(TypeError, match=r"^angle_measurements must hold integers"):
        _ekf().update(np.zeros(1), lambda x: x[:1], H, np.eye(1), angle_measurements=indices)
