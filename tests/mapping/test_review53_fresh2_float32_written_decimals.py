"""A float64 resolution exactly a decimal one writes counts its own cells (review 53, FRESH2).

bcb53cd counts cells of a float32 resolution (a ROS message's) in the decimal
it stands for, ``intended_resolution``: any float that is a float32 value was
taken for the shortest decimal float32 rounds to it. A float64 resolution
written as an exact binary fraction is a float32 value too: 0.00244140625
(5 / 2**11) was taken for 0.0024414062, and ``OccupancyGrid.empty`` of 0.00244140625
m by 0.00244140625 m at it had 2 x 2 cells (1 x 1 before bcb53cd), 1000 of them
across 1001. Such a resolution, exactly a decimal of at most 10 significant
digits, is itself now; the float32 of every decimal of up to 5 (slow: 6)
significant digits from 1e-4 to 1e4 m still stands for that decimal. ``LocalGrid.from_points``
rounded half cells of 1.01171875 m (taken for 1.0117188) down.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.float32 import intended_resolution
from navkit.mapping import LocalGrid, OccupancyGrid

#: Exact binary fractions, float32 values all, of at most 10 significant digits.
WRITTEN = (0.00244140625, 2.0**-12, 2.0**-14, 3 * 2.0**-10, 1.00390625, 0.0048828125)


@pytest.mark.parametrize("resolution", WRITTEN)
def test_a_written_binary_fraction_counts_its_own_cells(resolution: float) -> None:
    assert float(np.float32(resolution)) == resolution  # the premise: a float32 value
    assert intended_resolution(resolution) == resolution
    for n in (1, 7, 100, 1000):
        grid = OccupancyGrid.empty(width=n * resolution, height=resolution, resolution=resolution)
        assert grid.shape == (1, n)


def test_a_local_grid_at_a_written_binary_fraction_rounds_half_cells_up() -> None:
    # 1.01171875 was taken for 1.0117188, above it: (k + 0.5) cells fell below the
    # halfway point and rounded down (sizes 1, 3, 5, 11 where 21ad508 gave 3, 5, 7, 13).
    resolution = 1.01171875
    sizes = [
        LocalGrid.from_points(
            np.zeros((0, 2)), half_width=(k + 0.5) * resolution, resolution=resolution
        ).size
        for k in (0, 1, 2, 5)
    ]
    assert sizes == [3, 5, 7, 13]


def _decimals(digits: int) -> np.ndarray:
    """Every decimal of ``digits`` significant digits from 1e-4 up to 1e4."""
    mantissas = np.arange(10 ** (digits - 1), 10**digits)
    return np.unique(
        np.concatenate(
            [
                np.array([f"{m}e{e}" for m in mantissas], dtype=np.float64)
                for e in range(-4 - digits + 1, 4 - digits + 1)
            ]
        )
    )


def _misread(digits: int) -> list[float]:
    out = []
    for decimal in _decimals(digits):
        single = float(np.float32(decimal))
        if single != decimal and intended_resolution(single) != decimal:
            out.append(float(decimal))
    return out


@pytest.mark.parametrize("digits", [1, 2, 3, 4])
def test_the_float32_of_a_short_decimal_still_stands_for_it(digits: int) -> None:
    assert _misread(digits) == []


@pytest.mark.slow
@pytest.mark.parametrize("digits", [5, 6])
def test_the_float32_of_a_longer_decimal_still_stands_for_it(digits: int) -> None:
    assert _misread(digits) == []
