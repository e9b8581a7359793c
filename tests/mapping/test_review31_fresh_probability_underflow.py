"""``OccupancyGrid.probability`` whatever numpy's underflow setting (review 31, FRESH).

Review 30 put ``np.exp`` under ``np.errstate(under="ignore")`` so that the
probabilities do not depend on a caller's ``np.seterr`` (its comment: "whatever
the caller's np.seterr"). The division after it was left outside: a log-odds
between about -709.78 and -708.4 makes ``exp(-l)`` a float64 beyond 4.5e307,
and ``1 / (1 + exp(-l))`` a subnormal number, which raised
``FloatingPointError: underflow encountered in divide`` under
``np.seterr(under="raise")`` (and warned under ``"warn"``).

Checked: against ``_grid.py`` before the change, the "raise" and "warn" cases
fail (FloatingPointError; RuntimeWarning turned error); "ignore" passes.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid

# float32 log-odds (the grid's storage) whose probability is subnormal or near it.
LOGODDS = np.array([[-709.5, -709.0], [-708.5, 0.0]], dtype=np.float32)


@pytest.mark.parametrize("mode", ["raise", "warn", "ignore"])
def test_probability_of_very_free_cells_whatever_the_underflow_setting(mode: str) -> None:
    grid = OccupancyGrid(LOGODDS, resolution=0.1)
    with np.errstate(under=mode):
        got = grid.probability()
    with np.errstate(under="ignore"):
        expected = 1.0 / (1.0 + np.exp(-LOGODDS.astype(np.float64)))
    np.testing.assert_array_equal(got, expected)
    assert got[0, 0] > 0.0 and got[0, 0] < np.finfo(np.float64).tiny  # subnormal
    assert got[1, 1] == 0.5
