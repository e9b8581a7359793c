"""Review 54 (MUTANT34): beyond 200 states P0 is checked in float64 by the kernels' LDLᵀ.

Review 53 takes a P0 NumPy's Cholesky refuses when the filters' own LDLᵀ check
takes it, replayed in Python up to 200 rows and run by a kernel beyond. The
tests' matrices were also taken by the scaled Cholesky test, so handing the
kernel a float32 rounding of P0 passed them. This block's LDLᵀ in float64 has a
second pivot of 2.2e-16; LAPACK's Cholesky and the scaled Cholesky test
refuse it, and rounded to float32 it is indefinite.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

BLOCK = np.array(
    [[0.7964102461435598, 0.8457774946845268], [0.8457774946845268, 0.8982048811886941]]
)


@pytest.mark.parametrize("n", [2, 200, 201, 230])
def test_a_p0_only_the_filters_own_check_takes_is_taken(n: int) -> None:
    p0 = np.eye(n)
    p0[-2:, -2:] = BLOCK
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.cholesky(p0)
    single = BLOCK.astype(np.float32).astype(np.float64)
    assert np.linalg.eigvalsh(single)[0] < 0.0  # the premise: indefinite in float32
    ekf = ExtendedKalmanFilter(np.zeros(n), p0)
    assert np.array_equal(ekf.P, p0)
