"""A time gap in a batch's first row restores the filter's own state (review 35, MUTANT4).

``update_batch`` writes the filter's x and P into the output's extra last row
before the kernel runs, so that a ``TIME_GAP`` in row 0 (a prediction that
overflows, e.g. a corrupt stamp of 1e300 s) is undone from there. Deleting
the copy of x passed the suite: its test started from the default state, all
zeros, which the output array happened to hold. Here the filter starts from a
state and covariance with no zero entry; the oracle is the same log without
the corrupt row, run on a twin filter (the row is documented to change
nothing).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion

_X0 = np.array([1.5, -2.0, 0.7, 0.4, 0.05, 0.02])


def _p0() -> np.ndarray:
    a = np.random.default_rng(7).standard_normal((6, 6))
    return 0.1 * (a @ a.T) + 0.05 * np.eye(6)


def _log(times: list[float]) -> MeasurementLog:
    n = len(times)
    values = np.column_stack((np.full(n, 0.6), np.full(n, 0.5), np.full(n, 0.04), np.zeros(n)))
    observed = np.tile([True, True, True, False], (n, 1))
    return MeasurementLog(times, values, np.full((n, 4), 1e-2), observed)


@pytest.mark.parametrize("bad_time", [1e300, 1.7e308])
def test_a_corrupt_first_row_leaves_the_start_state(bad_time: float) -> None:
    times = [0.1, 0.2, 0.3]
    clean = PlanarFusion(_X0, _p0(), t0=0.0).update_batch(_log(times))
    fusion = PlanarFusion(_X0, _p0(), t0=0.0)
    result = fusion.update_batch(_log([bad_time, *times]))
    assert result.status[0] == FusionStatus.TIME_GAP
    np.testing.assert_array_equal(result.states[0], _X0)
    np.testing.assert_array_equal(result.covariances[0], _p0())
    np.testing.assert_array_equal(result.states[1:], clean.states)
    np.testing.assert_array_equal(result.covariances[1:], clean.covariances)
    np.testing.assert_array_equal(fusion.x, clean.states[-1])
