"""Lines of the EKF and compass calibration that tests/estimation did not reach (review 32)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import navkit.estimation._ekf as ekf_module
from navkit.estimation import CompassCalibration, ExtendedKalmanFilter


def test_compass_calibration_repr_shows_its_start() -> None:
    cal = CompassCalibration(unwrap=True)
    assert repr(cal) == "CompassCalibration(unwrap=True, <no reading yet>)"
    cal(45.0)
    assert repr(cal) == "CompassCalibration(unwrap=True, <initial 45.0 deg>)"


def test_non_iterable_angle_indices_are_refused_by_name() -> None:
    with pytest.raises(TypeError, match="angle_states must be a sequence of integer indices"):
        ExtendedKalmanFilter(np.zeros(2), np.eye(2), angle_states=5)  # type: ignore[arg-type]
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    with pytest.raises(TypeError, match="angle_measurements must be a sequence of integer"):
        ekf.update(
            [0.0],
            lambda x: x[:1],
            np.array([[1.0, 0.0]]),
            [[1.0]],
            angle_measurements=5,  # type: ignore[arg-type]
        )


def _raises_type_error(x: Any) -> Any:
    raise TypeError("the model's own error")


def test_a_models_own_type_error_propagates_unchanged() -> None:
    # Not relabelled "f must be callable": the callable was called and failed.
    ekf = ExtendedKalmanFilter([1.0, 2.0], np.eye(2))
    with pytest.raises(TypeError, match=r"^the model's own error$"):
        ekf.predict(_raises_type_error, np.eye(2), 0.1 * np.eye(2))
    with pytest.raises(TypeError, match=r"^the model's own error$"):
        ekf.update([0.0], _raises_type_error, np.array([[1.0, 0.0]]), [[1.0]])
    np.testing.assert_array_equal(ekf.x, [1.0, 2.0])
    np.testing.assert_array_equal(ekf.P, np.eye(2))
    ekf.predict(lambda x: x, np.eye(2), 0.1 * np.eye(2))  # not left busy
    np.testing.assert_array_equal(ekf.P, 1.1 * np.eye(2))


def _many_sizes(angle_tuples: bool) -> ExtendedKalmanFilter:
    n = 20
    ekf = ExtendedKalmanFilter(np.linspace(0.0, 1.0, n), np.eye(n))
    sizes = [*range(1, 19), 1, 2]  # 18 sizes, then two evicted ones again
    for k, m in enumerate(sizes):
        H = np.eye(m, n)
        angles = (k % m,) if angle_tuples else ()
        ekf.update(
            0.5 * np.ones(m),
            lambda x, m=m: x[:m],
            H,
            0.2 * np.eye(m),
            angle_measurements=tuple(angles),
        )
    return ekf


@pytest.mark.parametrize("angle_tuples", [False, True])
@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_evicting_the_per_size_caches_changes_no_result(
    monkeypatch: pytest.MonkeyPatch, angle_tuples: bool
) -> None:
    evicted = _many_sizes(angle_tuples)
    assert len(evicted._rbufs) <= ekf_module._CACHE_SIZE
    assert len(evicted._meas_angles) <= ekf_module._CACHE_SIZE
    monkeypatch.setattr(ekf_module, "_CACHE_SIZE", 1000)
    kept = _many_sizes(angle_tuples)
    assert len(kept._rbufs) == 18
    np.testing.assert_array_equal(evicted.x, kept.x)
    np.testing.assert_array_equal(evicted.P, kept.P)
