"""Review 54 (MUTANT34): the two bounds of a float32 SampledField axis, each at its edge.

``SampledField`` takes float32 cell centres within 4 ulps of their dtype (of the
largest coordinate plus the axis's length) of evenly spaced ones, where an ulp
is at most 1 % of a cell. Review 53's tests met neither bound: centres rounded
once to float32 are within one ulp, and its coarse axis (0.01 m at 1e4 m, an
ulp 12 % of a cell) is past any share up to 10 %. So a tolerance of 1 ulp, or
a share of 10 %, passed them. Here: centres 3 ulps off are taken, and an axis
at 2,000 m (an ulp 2.4 % of a 0.01 m cell) is refused saying to pass float64.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import SampledField


def _record(x: np.ndarray, resolution: float) -> SampledField:
    n = x.shape[0]
    return SampledField(x, [0.5], np.zeros((1, n)), np.zeros((1, n, 2)), resolution=resolution)


def test_centres_three_float32_ulps_off_are_taken() -> None:
    # Near 500 m an ulp of float32 is 2**-15 m (3.05e-5 m, 0.3 % of a 0.01 m cell).
    n = 100
    even = (400.0 + (np.arange(n) + 0.5) * 0.01).astype(np.float32)
    ulp = np.spacing(even)
    assert np.all(ulp == np.float32(2.0**-15))
    x = even.copy()
    x[1::2] += 3 * ulp[1::2]  # every other centre 3 ulps up (the first kept)
    sampled = _record(x, 0.01)
    assert np.array_equal(sampled.x, x.astype(np.float64))
    # Each centre still lies in its own cell.
    cells = sampled.world_to_cell(np.column_stack((x, np.full(n, 0.5))))
    assert np.array_equal(cells[:, 1], np.arange(n))
    # Ten ulps off (3e-4 m, 3 % of a cell) is no even spacing.
    x[50] += 10 * ulp[50]
    with pytest.raises(ValueError, match="evenly spaced"):
        _record(x, 0.01)


def test_float32_holding_a_cell_only_to_2_percent_is_refused_saying_so() -> None:
    x = (2000.0 + (np.arange(10) + 0.5) * 0.01).astype(np.float32)
    # The premise: an ulp of float32 there is between 1 % and 10 % of the cell.
    assert 0.01 * 0.01 < np.finfo(np.float32).eps * 2000.0 < 0.1 * 0.01
    with pytest.raises(ValueError) as info:
        _record(x, 0.01)
    assert "pass float64 coordinates" in str(info.value)
    assert _record(x.astype(np.float64).round(3), 0.01).shape == (1, 10)
