"""An ExtendedKalmanFilter of more than 200 states takes its own P as P0 (review 53, FRESH3).

54bec22 made a filter's own covariance a valid ``P0``: where NumPy's Cholesky
refuses a near-singular matrix the kernels' LDLᵀ takes (its second pivot 2.2e-16,
LAPACK's 0.0), ``covariance()`` replays that LDLᵀ in Python. Only up to 200 rows,
though (beyond, only the scaled Cholesky test, which refuses such a matrix too):
a filter of 201 states refused its own P, 12 of 88 after one update with R 1e-20
of P, where the docstring says its P is always a valid P0. Beyond 200 rows the
kernels' own check runs now.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter

# LDLᵀ pivots 1.23 and 2.2e-16 (the kernels take it); LAPACK's Cholesky: 0.0.
NEAR_SINGULAR = np.array(
    [[1.2295186115074588, 1.1701889166820183], [1.1701889166820183, 1.113722141258639]]
)


def _with_block(n: int, block: np.ndarray) -> np.ndarray:
    out = np.eye(n)
    out[:2, :2] = block
    return out


@pytest.mark.parametrize("n", [2, 200, 201, 260])
def test_a_near_singular_block_the_kernels_take_is_a_valid_p0(n: int) -> None:
    p0 = _with_block(n, NEAR_SINGULAR)
    before = p0.copy()
    ekf = ExtendedKalmanFilter(np.zeros(n), p0)
    assert ekf.P[:2, :2].tobytes() == NEAR_SINGULAR.tobytes()
    np.testing.assert_array_equal(p0, before)


@pytest.mark.parametrize("n", [201, 260])
def test_what_no_check_takes_is_still_refused_beyond_200_rows(n: int) -> None:
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        ExtendedKalmanFilter(np.zeros(n), _with_block(n, np.ones((2, 2))))
    indefinite = _with_block(n, np.array([[1.0, 2.0], [2.0, 1.0]]))
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        ExtendedKalmanFilter(np.zeros(n), indefinite)


@pytest.mark.slow
def test_a_filter_of_201_states_is_rebuilt_from_the_p_it_committed() -> None:
    # About 2 s an update (R 1e-20 of P takes the exact updates); at 54bec22 the
    # filters of the 4th and 11th draws refused their own P.
    rng = np.random.default_rng(0)
    n = 201
    committed = 0
    for _ in range(11):
        a = rng.standard_normal((2, 2))
        ekf = ExtendedKalmanFilter(np.zeros(n), _with_block(n, a @ a.T + 0.1 * np.eye(2)))
        h = np.zeros((1, n))
        h[0, :2] = rng.standard_normal(2)
        try:
            ekf.update(rng.standard_normal(1), lambda x, h=h: h @ x, lambda x, h=h: h, [[1e-20]])
        except FilterError:
            continue  # the update itself refused: nothing committed
        committed += 1
        again = ExtendedKalmanFilter(ekf.x, ekf.P)
        assert again.P.tobytes() == ekf.P.tobytes()
    assert committed >= 5
