"""A PlanarFusion update whose residual overflows returns an empty residual, as documented.

Review 40 (mutation testing, MUTANT11; one of review 38's trimmed ``_fusion.py``
mutants that review 39 did not reach). ``UpdateResult.residual`` is documented
"empty when it was never computed or overflowed float64"; ``_rejection``'s
``residual = np.empty(0)`` deleted passed every test, the filter then returning
``residual == [-inf]`` for a speed of 1.7e308 read as -1.7e308. The EKF's
overflow was pinned (``test_estimation_contract.py``), PlanarFusion's was not.
Oracle: the residual z - h(x) of these readings, -3.4e308, is beyond the float
range (checked here in exact arithmetic).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from navkit.estimation import FusionStatus, PlanarFusion

BIG = 1.7e308
# State index and update method of each scalar reading of the state.
_READINGS = [(3, "update_speed"), (4, "update_yaw_rate"), (5, "update_acceleration")]


def _filter(index: int, history: float | None) -> PlanarFusion:
    x = [0.0] * 6
    x[index] = BIG
    if history is None:
        return PlanarFusion(x, np.eye(6), process_noise=np.zeros(6), t0=0.0)
    return PlanarFusion(x, np.eye(6), process_noise=np.zeros(6), t0=0.0, history=history)


def test_the_residual_overflows() -> None:
    assert abs(Fraction(-BIG) - Fraction(BIG)) > Fraction(np.finfo(np.float64).max)


@pytest.mark.parametrize(("index", "method"), _READINGS)
@pytest.mark.parametrize("history", [None, 5.0])
def test_an_overflowing_residual_is_empty_and_the_filter_unchanged(
    index: int, method: str, history: float | None
) -> None:
    f = _filter(index, history)
    x, p = f.x.copy(), f.P.copy()
    result = getattr(f, method)(0.0, -BIG, variance=1.0)
    assert result.status == FusionStatus.OVERFLOW
    assert not result.accepted
    assert result.nis == math.inf
    assert result.residual.shape == (0,)
    assert result.reason is not None and "overflow" in result.reason
    np.testing.assert_array_equal(f.x, x)
    np.testing.assert_array_equal(f.P, p)


def test_a_late_overflowing_residual_replayed_is_empty_too() -> None:
    # Through the history's replay (an out-of-order reading before a later one); a
    # time step of 1e-300 s, over which the huge speed moves the robot 1.7e8 m.
    f = _filter(3, 5.0)
    assert f.update_yaw(2e-300, 0.5, variance=1.0).accepted
    result = f.update_speed(1e-300, -BIG, variance=1.0)
    assert result.status == FusionStatus.OVERFLOW
    assert result.residual.shape == (0,)
    assert np.isfinite(f.x).all()
