"""What OccupancyGrid.empty covers, as its docstring says (review 54, FOUND7).

Its summary said the grid covers ``width × height`` metres, rounded up to whole
cells; a count within 1e-9 of a cell (and the rounding of the division) is not
rounded up, and a float32 resolution counts cells of the decimal it stands for
(bcb53cd): 10 m at float32 0.01 are 1000 cells of 0.0099999998 m, 9.99999977
m. The docstring now says by how much the grid may fall short; this pins it.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.float32 import intended_resolution
from navkit.mapping import OccupancyGrid

_F32_ROUNDING = 2.0**-24


def _short_by(extent: float, cells: int, resolution: float) -> float:
    """How far ``cells`` cells of ``resolution`` fall short of ``extent``, m (<= 0: covered)."""
    return extent - cells * resolution


def _allowed(extent: float, cells: int, resolution: float) -> float:
    """The shortfall the docstring allows, m (one more ulp of the product computed here)."""
    slack = (1e-9 + 2.0**-50 * cells) * max(resolution, intended_resolution(resolution))
    if intended_resolution(resolution) != resolution:
        slack += _F32_ROUNDING * extent
    return slack + math.ulp(extent) * 2


@settings(max_examples=300, deadline=None)
@given(
    st.floats(1e-3, 1e3),
    st.floats(1e-3, 1e3),
    st.sampled_from([0.01, 0.025, 0.03, 0.05, 0.1, 0.3, 0.7, 1.0, 0.0123, 2.5]),
    st.booleans(),
)
def test_the_grid_covers_its_extent_as_documented(
    width: float, height: float, decimal: float, single: bool
) -> None:
    resolution = float(np.float32(decimal)) if single else decimal
    if width / resolution * height / resolution > 2**24:
        return
    grid = OccupancyGrid.empty(width=width, height=height, resolution=resolution)
    rows, cols = grid.shape
    for extent, cells in ((width, cols), (height, rows)):
        assert _short_by(extent, cells, resolution) <= _allowed(extent, cells, resolution)
        # Rounded up, not more: one cell fewer would not cover it.
        assert cells == 1 or _short_by(extent, cells - 1, resolution) > 0.0


def test_the_documented_float32_example() -> None:
    grid = OccupancyGrid.empty(width=10.0, height=0.5, resolution=float(np.float32(0.01)))
    assert grid.shape == (50, 1000)
    short = 10.0 - 1000 * grid.resolution
    assert 0.0 < short <= _F32_ROUNDING * 10.0  # 2.2e-7 m: within float32's rounding
