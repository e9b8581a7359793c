"""A resolution no short decimal stands behind counts its own cells (review 53, FRESH2).

bcb53cd counts cells of a float32 resolution (a ROS message's) in the decimal
it stands for, ``intended_resolution``: any float that is a float32 value was
taken for the shortest decimal float32 rounds to it. A float64 resolution
written as an exact binary fraction is a float32 value too: 0.00244140625
(5 / 2**11) was taken for 0.0024414062, and ``OccupancyGrid.empty`` of
0.00244140625 m by 0.00244140625 m at it had 2 x 2 cells (1 x 1 before
bcb53cd), 1000 of them across 1001; ``LocalGrid.from_points`` rounded half
cells of 1.01171875 m (taken for 1.0117188) down; 1 m at float32 1/81 (taken
for 0.012345679) had 82 cells, 81 before. A float32 whose shortest decimal has
more than 6 significant digits (C's FLT_DIG: more than float32 keeps of any
decimal) is itself now; the float32 of every decimal of up to 4 (slow: 6)
significant digits from 1e-4 to 1e4 m still stands for that decimal.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.float32 import intended_resolution
from navkit.mapping import LocalGrid, OccupancyGrid

#: Exact binary fractions, float32 values all, and a float32 of no short decimal (1/81).
WRITTEN = (
    0.00244140625,
    2.0**-12,
    2.0**-14,
    3 * 2.0**-10,
    1.00390625,
    0.0048828125,
    float(np.float32(1 / 81)),
)


@pytest.mark.parametrize("resolution", WRITTEN)
def test_a_written_binary_fraction_counts_its_own_cells(resolution: float) -> None:
    assert float(np.float32(resolution)) == resolution  # the premise: a float32 value
    assert intended_resolution(resolution) == resolution
    for n in (1, 7, 81, 100, 1000):
        grid = OccupancyGrid.empty(width=n * resolution, height=resolution, resolution=resolution)
        assert grid.shape == (1, n)


def test_one_metre_at_float32_one_81st_is_81_cells() -> None:
    resolution = float(np.float32(1 / 81))
    assert OccupancyGrid.empty(width=1.0, height=1.0, resolution=resolution).shape == (81, 81)


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
