"""A masked ``Q``/``R`` is refused whatever the filter saw before (review 11).

The fast paths routed masked ``F``, ``f(x)``, ``H``, ``h(x)`` and ``z`` to the
checked path but not the noise: the kernel compares ``Q``/``R`` with the last
one, so a masked one of the same values went through (mask ignored) while one
of new values was refused.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

F = np.eye(2)
H = np.array([[1.0, 0.0]])


def _f(x: np.ndarray) -> np.ndarray:
    return x.copy()


def _h(x: np.ndarray) -> np.ndarray:
    return x[:1].copy()


def test_a_masked_q_equal_to_the_last_q_is_refused() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    q = 0.1 * np.eye(2)
    ekf.predict(_f, F, q)
    x, p = ekf.x.copy(), ekf.P.copy()
    with pytest.raises(ValueError, match="Q has masked entries"):
        ekf.predict(_f, F, np.ma.array(q, mask=[[True, False], [False, False]]))
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)


def test_a_masked_r_equal_to_the_last_r_is_refused() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    r = np.eye(1)
    ekf.update(np.array([0.5]), _h, H, r)
    x, p = ekf.x.copy(), ekf.P.copy()
    with pytest.raises(ValueError, match="R has masked entries"):
        ekf.update(np.array([0.5]), _h, H, np.ma.array(r, mask=[[True]]))
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)


def test_unmasked_noise_in_a_masked_array_gives_the_plain_result() -> None:
    plain = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    masked = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    for ekf, wrap in ((plain, np.asarray), (masked, np.ma.array)):
        ekf.predict(_f, F, wrap(0.1 * np.eye(2)))
        ekf.update(np.array([0.5]), _h, H, wrap(np.eye(1)))
    np.testing.assert_array_equal(masked.x, plain.x)
    np.testing.assert_array_equal(masked.P, plain.P)
