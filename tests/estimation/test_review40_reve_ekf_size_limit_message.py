"""A singular computed S beyond the exact arithmetic's size limit says why (review 40, REVE).

``finish_singular_s`` refuses a measurement whose exact arithmetic would eliminate more
than ``_EXACT_ELIMINATION_MAX`` rows (a dense R of 26 components here). The exact S of a
positive definite P and R is positive definite; only the size limit refuses the update.
The message said "innovation covariance S is not positive definite" alone, as if P or R
were at fault, where ``finish_cancelled``'s refusal of the same size names the limit and
what to do. The filter is unchanged either way.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from precise_updates import linear, precise_problem


@pytest.mark.parametrize("seed, size", [(24, 26), (43, 28)])
def test_a_singular_s_past_the_limit_names_the_limit(seed: int, size: int) -> None:
    drawn = precise_problem(seed, (25, 30))
    assert drawn is not None
    x0, p, h, r, z = drawn
    assert h.shape[0] == size and kernels._exact_route(h.shape[1], r) is None
    ekf = ExtendedKalmanFilter(x0, p)
    with pytest.raises(FilterError) as raised:
        ekf.update(z, linear(h), h, r)
    message = str(raised.value)
    assert message.startswith("innovation covariance S is not positive definite")
    assert f"a measurement of {size} components" in message
    assert f"more than {kernels._EXACT_ELIMINATION_MAX} rows" in message
    assert "diagonal R" in message
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
    # ... and still usable: an ordinary update as a fresh filter's, bit for bit.
    fresh = ExtendedKalmanFilter(x0, p)
    loose = np.eye(size) * 1e6 * float(np.max(np.diag(p)))
    got = ekf.update(z, linear(h), h, loose)
    want = fresh.update(z, linear(h), h, loose)
    assert np.array_equal(ekf.x, fresh.x) and np.array_equal(ekf.P, fresh.P)
    assert got.nis == want.nis
