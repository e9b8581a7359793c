"""The EKF's update buffer holds no block it does not need (review 47, SMALLS).

Each measurement size m has a buffer of max(n, m)² float64 blocks (``new_rbuf``).
The LDLᵀ factor of the check of the new P had a block of its own, though H P,
read last when the new P is made, is free by then: it now holds it, 10 blocks
for 11 (a 360-beam scan update: 10.4 MB for 11.4 MB). Results are the same bit
for bit (checked against the previous code on 1200 random updates; the suite's
EKF tests pin the paths: cancelled, gated, ill-conditioned S).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels


@pytest.mark.parametrize(("n", "m"), [(3, 360), (360, 3), (6, 6)])
def test_the_buffer_is_ten_blocks(n: int, m: int) -> None:
    big = max(n, m)
    assert kernels.new_rbuf(n, m).nbytes == 10 * big * big * 8


def test_the_new_covariance_is_checked_after_h_p_is_read() -> None:
    # The check's factor overwrites H P: an update whose new P is made from a
    # P H^T equal to the one NumPy gives (the Joseph form, to rounding), and a
    # second update with the same buffer as a fresh filter's.
    rng = np.random.default_rng(47)
    n, m = 4, 7
    a = rng.normal(size=(n, n))
    p0 = a @ a.T + np.eye(n)
    h = rng.normal(size=(m, n))
    r = np.diag(rng.uniform(0.5, 2.0, size=m))
    z = rng.normal(size=m)
    ekf = ExtendedKalmanFilter(np.zeros(n), p0)
    assert ekf.update(z, lambda x: h @ x, h, r).accepted
    s = h @ p0 @ h.T + r
    k = np.linalg.solve(s, h @ p0).T
    joseph = (np.eye(n) - k @ h) @ p0 @ (np.eye(n) - k @ h).T + k @ r @ k.T
    np.testing.assert_allclose(ekf.P, joseph, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(ekf.x, k @ z, rtol=1e-10, atol=1e-12)
    again = ExtendedKalmanFilter(ekf.x, ekf.P)
    assert again.update(z, lambda x: h @ x, h, r).accepted
    assert ekf.update(z, lambda x: h @ x, h, r).accepted
    assert np.array_equal(ekf.P, again.P) and np.array_equal(ekf.x, again.x)
