"""Minimal valid inputs of the grid constructors: long one-row strips get their cell count.

``width = n * resolution`` must give ``n`` columns however long the strip (a
``1 x n`` grid is valid up to ``n = 2**28``); the old absolute 1e-9-cell slack
was smaller than the float rounding of ``(n * resolution) / resolution`` beyond
a few million cells, which added a column.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.mapping._limits import MAX_CELLS, grid_shape

RESOLUTIONS = [0.05, 0.1, 0.03, 0.07, 0.025, 0.3, 1e-3, 1e-6, 0.0123, 3.3, 123.456]


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(min_value=1, max_value=MAX_CELLS),
    resolution=st.sampled_from(RESOLUTIONS),
)
def test_n_cells_of_resolution_give_n_cells(n: int, resolution: float) -> None:
    width = n * resolution
    assert grid_shape(width=width, height=resolution, resolution=resolution, what="g") == (1, n)
    assert grid_shape(width=resolution, height=width, resolution=resolution, what="g") == (n, 1)


@pytest.mark.parametrize(
    ("n", "resolution"),
    # Found by search: (n * resolution) / resolution rounds above n by more than 1e-9.
    [(228337702, 0.05), (28318674, 0.05), (17476268, 0.03)],
)
def test_known_long_strips(n: int, resolution: float) -> None:
    assert (n * resolution) / resolution - n > 1e-9  # the case the old slack missed
    assert grid_shape(width=n * resolution, height=resolution, resolution=resolution,
                      what="g") == (1, n)


@pytest.mark.parametrize("resolution", RESOLUTIONS)
def test_a_hair_more_than_n_cells_still_rounds_up(resolution: float) -> None:
    for n in (1, 7, 1000, 17476268, 2**28 - 1):
        got = grid_shape(width=(n + 1e-5) * resolution, height=resolution,
                         resolution=resolution, what="g")
        assert got == (1, n + 1)


def test_empty_long_strip_has_n_columns() -> None:
    # 70 MB of float32: the public constructor on a strip the old rounding widened.
    n, res = 17476268, 0.03
    grid = OccupancyGrid.empty(width=n * res, height=res, resolution=res)
    assert grid.shape == (1, n)
    # Its last column ends at the requested width (to float rounding).
    assert grid.width == pytest.approx(n * res, rel=1e-12)

