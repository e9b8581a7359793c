"""Mutation-testing gaps of the memory-lean OccupancyGrid constructor (review 10).

The constructor keeps float16/32/64 ndarrays as they are (no float64 copy) and
sends everything else through the general conversion. Two promises of the
general path survived a widened fast path: masked entries are refused, and the
stored float32 log-odds are those of the float64 conversion (bit-identical to
the code before the memory work), also for extended-precision input.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.mapping import OccupancyGrid


@pytest.mark.parametrize("dtype", [np.float16, np.float32, np.float64])
def test_masked_logodds_are_refused_whatever_the_float_dtype(dtype: type) -> None:
    data: NDArray[Any] = np.array([[1.0, np.nan], [0.0, -1.0]], dtype=dtype)
    masked = np.ma.masked_array(data, mask=[[False, True], [False, False]])
    with pytest.raises(ValueError, match="masked"):
        OccupancyGrid(masked, resolution=0.1)


def test_unmasked_subclass_values_are_kept() -> None:
    masked = np.ma.masked_array(np.array([[1.5, -2.0]], dtype=np.float32), mask=False)
    grid = OccupancyGrid(masked, resolution=0.1)
    assert type(grid.logodds) is np.ndarray
    np.testing.assert_array_equal(grid.logodds, np.array([[1.5, -2.0]], dtype=np.float32))


@pytest.mark.skipif(
    np.finfo(np.longdouble).nmant <= np.finfo(np.float64).nmant,
    reason="long double is float64 here",
)
def test_extended_precision_logodds_round_through_float64() -> None:
    # 1 + 2**-24 is the midpoint of two float32 neighbours; a long double just above
    # it rounds to it in float64 (then to 1.0, ties to even), but up if rounded
    # straight to float32.
    tiny = np.longdouble(2) ** -60
    value = np.longdouble(1) + np.longdouble(2) ** -24 + tiny
    logodds = np.array([[value, -value]], dtype=np.longdouble)
    expected = np.asarray(logodds.astype(np.float64), dtype=np.float32)
    assert expected[0, 0] != np.float32(value)  # the two roundings differ
    grid = OccupancyGrid(logodds, resolution=0.1)
    np.testing.assert_array_equal(grid.logodds, expected)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("bad", [-np.inf, np.inf, np.nan])
def test_non_finite_logodds_are_refused_as_not_finite(dtype: type, bad: float) -> None:
    logodds: NDArray[Any] = np.array([[0.5, bad], [0.0, -0.5]], dtype=dtype)
    with pytest.raises(ValueError, match="logodds must contain only finite values"):
        OccupancyGrid(logodds, resolution=0.1)
