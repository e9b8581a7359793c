"""Review 54 (MUTANT34): P0s the filters' checks refuse, and what the refusal says.

Review 53 lets ``covariance`` take a matrix NumPy's Cholesky refuses (or finds a
subnormal pivot in) when the filters' own LDLᵀ check takes it. Two mutants of
that passed the tests: the replayed check taking any positive pivot (a
subnormal one, whose reciprocal overflows, included), and a matrix NumPy's
Cholesky refuses being reported with "a pivot of nan".
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter


@pytest.mark.parametrize("tiny", [1e-310, 1e-320, 2e-308])
@pytest.mark.parametrize("where", [0, 1, 2])
def test_a_subnormal_pivot_is_refused(tiny: float, where: int) -> None:
    p0 = np.eye(3)
    p0[where, where] = tiny
    assert 0.0 < tiny < np.finfo(np.float64).tiny  # subnormal
    with pytest.raises(ValueError, match=r"^P0 must be positive definite with LDLᵀ pivots") as info:
        ExtendedKalmanFilter(np.zeros(3), p0)
    assert "nan" not in str(info.value)


def test_a_subnormal_pivot_left_by_elimination_is_refused() -> None:
    # Pivots 1 and 1e-310 (2 - 2 * (1 - 5e-311)): NumPy finds the subnormal pivot.
    a = 1.0 - 5e-311
    p0 = np.array([[1.0, a], [a, 1.0]])
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        ExtendedKalmanFilter(np.zeros(2), p0)


@pytest.mark.parametrize(
    "p0",
    [
        [[1.0, 2.0], [2.0, 1.0]],  # indefinite
        [[1.0, 0.0], [0.0, 0.0]],  # singular
        [[1.0, 0.0], [0.0, -1e-300]],  # a negative variance
        [[-1.0, 0.0], [0.0, 1.0]],
    ],
)
def test_a_matrix_no_check_factorises_is_named_without_a_pivot(p0: list[list[float]]) -> None:
    with pytest.raises(ValueError) as info:
        ExtendedKalmanFilter(np.zeros(2), np.array(p0))
    message = str(info.value)
    assert message.startswith("P0 must be")
    assert "nan" not in message
