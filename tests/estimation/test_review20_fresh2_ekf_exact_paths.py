"""Fresh eyes on the EKF's exact-NIS paths (review 20): inputs the commit's tests left out.

An update whose computed S = H P Hᵀ + R rounds to a matrix that is not positive
definite (a state measured twice, each far more precisely than it is known)
takes the information form and the NIS in exact rational arithmetic
(``finish_singular_s``); a gated update with an ill-conditioned S is redone so
(``retry_gated``). Here: covariances with subnormal and 1e100 entries, an angle
state, a dense R, a row of zeros in H, the measurement size limit (8 vs 9), an
exact NIS beyond float64, and copies of a filter after such an update. The
reference is exact arithmetic on the float inputs (tests/exact_fractions.py).
"""

from __future__ import annotations

import copy
import math
import pickle
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter, FusionStatus
from navkit.estimation._ekf_kernels import (
    _EXACT_ELIMINATION_MAX,
    _INV_DIAG,
    _S,
    _VEC,
    GATED,
    retry_gated,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def _exact(x: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray):  # type: ignore[no-untyped-def]
    """Exact posterior (x, P) and NIS for the residual ``y`` the filter takes."""
    return exact_update(x, p, h, r, y)


def _assert_close(ekf: ExtendedKalmanFilter, x0: np.ndarray, x_exact, p_exact, angles=()) -> None:  # type: ignore[no-untyped-def]
    n = ekf.dim
    sigma = [float(p_exact[i][i]) ** 0.5 for i in range(n)]
    for i in range(n):
        for j in range(n):
            error = abs(float(p_exact[i][j] - Fraction(ekf.P[i, j])))
            assert error <= 1e-12 * sigma[i] * sigma[j], (i, j, ekf.P[i, j], float(p_exact[i][j]))
        target = float(x_exact[i])
        if i in angles:
            target = math.remainder(target, 2.0 * math.pi)
        size = abs(target) + abs(float(x0[i]))
        assert abs(target - ekf.x[i]) <= 0.25 * sigma[i] + 16 * 2.0**-52 * size, (i, ekf.x[i])


def _twice(p: np.ndarray, k: int, m: int, scales: list[float]) -> np.ndarray:
    """H measuring state ``k`` m times (rows multiples of one state)."""
    h = np.zeros((m, p.shape[0]))
    h[:, k] = scales[:m]
    return h


_SCALES = [1.0, -1.0, 2.0, 0.5, 1.0, -2.0, 1.0, 0.25, 1.0]


@pytest.mark.parametrize("off", [5e-324, 2.5e-308, -1e-310, 0.0])
def test_subnormal_covariance_entries_take_the_exact_path(off: float) -> None:
    # P entries 1e100 beside subnormal ones: the exact NIS works on ~2000-bit integers.
    p0 = np.array([[1e100, off, 0.0], [off, 1.0, 0.0], [0.0, 0.0, 1e-100]])
    h = _twice(p0, 0, 3, _SCALES)
    rr = np.diag([1e-20, 3e-20, 2e-20])
    x0 = np.array([5.0, -1.0, 2.0])
    z = h @ np.array([7.0, 0.0, 0.0]) + np.array([1e-10, -1e-10, 0.0])
    ekf = ExtendedKalmanFilter(x0, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    x_exact, p_exact, nis = _exact(x0, p0, h, rr, z - h @ x0)
    assert result.nis == float(nis)
    _assert_close(ekf, x0, x_exact, p_exact)


def test_an_angle_state_measured_twice_is_wrapped() -> None:
    p0 = np.diag([1.0, 1e20])
    h = _twice(p0, 1, 2, _SCALES)
    rr = np.diag([1e-20, 1e-20])
    x0 = np.array([0.0, 3.0])
    z = np.array([3.5, -3.5])  # state 1 at 3.5 rad: wrapped to 3.5 - 2π
    ekf = ExtendedKalmanFilter(x0, p0, angle_states=(1,))
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    assert -math.pi < ekf.x[1] <= math.pi
    x_exact, p_exact, nis = _exact(x0, p0, h, rr, z - h @ x0)
    assert result.nis == float(nis)
    _assert_close(ekf, x0, x_exact, p_exact, angles=(1,))


def test_a_dense_r_and_a_row_of_zeros() -> None:
    p0 = np.diag([1e16, 4.0])
    h = np.array([[1.0, 0.0], [0.0, 0.0], [2.0, 0.0]])  # the middle row measures nothing
    rr = np.array([[1e-4, 0.0, 5e-5], [0.0, 1.0, 0.0], [5e-5, 0.0, 4e-4]])
    x0 = np.array([1.0, 2.0])
    z = np.array([3.0, 0.5, 6.00002])
    ekf = ExtendedKalmanFilter(x0, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    x_exact, p_exact, nis = _exact(x0, p0, h, rr, z - h @ x0)
    assert abs(result.nis - float(nis)) <= 1e-8 * float(nis)
    _assert_close(ekf, x0, x_exact, p_exact)


@pytest.mark.parametrize("m", [8, 9, _EXACT_ELIMINATION_MAX + 1])
def test_the_measurement_size_limit(m: int) -> None:
    # Review 40: every size whose exact arithmetic eliminates at most
    # _EXACT_ELIMINATION_MAX rows (more than 8 components raised before); a diagonal R
    # of any size takes the information route, an R of one dense block of more rows
    # (here: a chain of correlated neighbours) none.
    p0 = np.diag([1e20, 1.0, 1.0])
    h = _twice(p0, 0, m, _SCALES * 3)
    rr = np.diag(np.linspace(1.0, 2.0, m) * 1e-20)
    if m > _EXACT_ELIMINATION_MAX:
        rr += np.diag(np.full(m - 1, 0.25e-20), 1) + np.diag(np.full(m - 1, 0.25e-20), -1)
    x0 = np.zeros(3)
    z = h @ np.array([1.0, 0.0, 0.0])
    ekf = ExtendedKalmanFilter(x0, p0)
    if m > _EXACT_ELIMINATION_MAX:
        with pytest.raises(FilterError, match="innovation covariance S"):
            ekf.update(z, lambda s: h @ s, h, rr)
        np.testing.assert_array_equal(ekf.x, x0)
        np.testing.assert_array_equal(ekf.P, p0)
        return
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    x_exact, p_exact, nis = _exact(x0, p0, h, rr, z - h @ x0)
    assert result.nis == float(nis)
    _assert_close(ekf, x0, x_exact, p_exact)


def test_an_exact_nis_beyond_float64_is_an_overflow_and_changes_nothing() -> None:
    p0 = np.diag([1e100, 1.0])
    h = np.array([[1.0, 0.0], [1.0, 0.0]])
    rr = np.diag([1e-300, 1e-300])
    # Two readings 1e155 deviations apart (along S's smallest eigenvector: NIS 2e310),
    # of a state far enough from 0 that the information form's state is trusted.
    x0 = np.array([1e10, 0.0])
    z = np.array([1e10 + 1e5, 1e10 - 1e5])
    ekf = ExtendedKalmanFilter(x0, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert not result.accepted
    assert result.status == FusionStatus.OVERFLOW
    assert result.nis == math.inf
    np.testing.assert_array_equal(ekf.x, x0)
    np.testing.assert_array_equal(ekf.P, p0)


def test_copies_after_the_exact_path_go_on_alike() -> None:
    p0 = np.diag([1e20, 1.0])
    h = _twice(p0, 0, 2, _SCALES)
    rr = np.diag([1e-20, 1e-20])
    ekf = ExtendedKalmanFilter(np.zeros(2), p0, angle_states=(1,))
    assert ekf.update(np.ones(2), lambda s: h @ s, h, rr).accepted
    twins = [pickle.loads(pickle.dumps(ekf)), copy.copy(ekf), copy.deepcopy(ekf)]
    z = np.array([1.0 + 1e-10, 1.0 - 1e-10])
    results = [f.update(z, lambda s: h @ s, h, rr, gate=1.0) for f in [ekf, *twins]]
    for twin, result in zip(twins, results[1:], strict=True):
        assert result.status == results[0].status
        assert result.nis == results[0].nis
        np.testing.assert_array_equal(twin.x, ekf.x)
        np.testing.assert_array_equal(twin.P, ekf.P)
        assert twin.angle_states == (1,)


@settings(max_examples=60, deadline=None)
@given(
    p_scale=st.floats(-100.0, 100.0),
    h_value=st.floats(1e-30, 1e30),
    r_ratio=st.floats(-20.0, 20.0),
    y_value=st.floats(1.0, 1e10),
)
def test_a_gated_scalar_measurement_keeps_the_kernels_verdict(
    p_scale: float, h_value: float, r_ratio: float, y_value: float
) -> None:
    # retry_gated skips m = 1 at once: its one pivot is S itself (S₀₀ / D₀ = 1), so
    # the check on max Sₖₖ / Dₖ it makes for larger m could never redo it.
    p0 = np.array([[10.0**p_scale]])
    h = np.array([[h_value]])
    s = h_value**2 * p0[0, 0]
    r = np.array([[max(s * 10.0**r_ratio, 1e-300)]])
    if not 1e-300 <= s <= 1e100 or not r[0, 0] <= 1e100:
        return
    ekf = ExtendedKalmanFilter(np.zeros(1), p0)
    z = np.array([y_value * math.sqrt(s + r[0, 0])])
    result = ekf.update(z, lambda x: h @ x, h, r, gate=0.5)
    if result.status != FusionStatus.GATED:
        return
    rbuf = ekf._rbuf  # the buffers of that update: the kernel's S and 1 / D
    ratio = float(rbuf[_S, 0, 0] * rbuf[_VEC, _INV_DIAG, 0])
    assert abs(ratio - 1.0) <= 1e-6
    assert retry_gated(ekf._state, rbuf, h, z - h @ ekf.x) == GATED
    np.testing.assert_array_equal(ekf.P, p0)
