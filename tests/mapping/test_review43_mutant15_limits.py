"""The mapping limits' edges that no test pinned (MUTANT15, mutants 20-82 of review 42's list).

Survivors closed here: ``cells_text``'s own default (4 bytes of float32, the
size its docstring quotes); ``cost_or_inf`` reading a 0-d float array as its
number (``np.array(np.inf)`` is inf, as ``np.float64(np.inf)`` is) and refusing
a 1-element 1-D array; and its lower bound 1 itself, which is a cost (a free
cell's). And a grid too large along one axis alone, which the tests met only
as a product of two axes: its count (1e18 and more cells) is quoted as a
number, not as "more than 1e308 cells", and a count whose bytes overflow a
float is "more bytes than exist", not "inf YiB". The slack of ``_cell_count``
is the documented 1e-9 cells (for short grids, where the few ulps of the
division are far smaller): a width 1.5e-9 cells past ``n`` cells takes ``n + 1``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, traversal_costs
from navkit.mapping._limits import cells_text, cost_or_inf, grid_shape


def test_cells_text_defaults_to_float32_cells() -> None:
    # Its docstring's example: 4 bytes a cell, 1e18 * 4 B = 3.47 EiB.
    assert cells_text(1e18) == "1e+18 cells (3.47 EiB of float32)"
    assert cells_text(1e18) == cells_text(1e18, 4, "float32")
    assert cells_text(3.0) == "3 cells (12 B of float32)"


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.float16])
def test_a_zero_d_float_array_is_its_number(dtype: type[np.floating]) -> None:
    assert cost_or_inf(np.array(np.inf, dtype=dtype), "unknown_cost") == math.inf
    assert cost_or_inf(np.array(3.0, dtype=dtype), "unknown_cost") == 3.0
    assert cost_or_inf(np.ma.masked_array(np.inf, mask=False), "unknown_cost") == math.inf
    with pytest.raises(ValueError, match=r"^unknown_cost has masked entries"):
        cost_or_inf(np.ma.masked_array(np.array(np.inf, dtype=dtype), mask=True), "unknown_cost")


@pytest.mark.parametrize("value", [np.array([np.inf]), np.array([3.0]), np.array([[3.0]])])
def test_a_one_element_array_is_no_cost(value: np.ndarray) -> None:
    with pytest.raises(TypeError, match=r"^unknown_cost must be a real number, got ndarray"):
        cost_or_inf(value, "unknown_cost")


def test_traversal_costs_read_a_zero_d_inf_as_inf() -> None:
    occupied = np.array([[True, False, False, False, False]])
    unknown = np.array([[False, False, False, False, True]])
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    expected = traversal_costs(grid, robot_radius=0.1, inflation_radius=0.2)
    got = traversal_costs(
        grid,
        robot_radius=0.1,
        inflation_radius=0.2,
        unknown_cost=np.array(np.inf),  # type: ignore[arg-type]
    )
    np.testing.assert_array_equal(got, expected)
    assert got[0, 4] == math.inf


@pytest.mark.parametrize("cost", [1.0, np.nextafter(1.0, 2.0), 1.5, 1.999, 1e9])
def test_costs_from_1_to_1e9_are_costs(cost: float) -> None:
    assert cost_or_inf(cost, "unknown_cost") == cost
    grid = OccupancyGrid.from_occupancy(
        np.array([[False, False]]), resolution=0.1, unknown=np.array([[False, True]])
    )
    np.testing.assert_array_equal(traversal_costs(grid, unknown_cost=cost), [[1.0, cost]])


@pytest.mark.parametrize("cost", [np.nextafter(1.0, 0.0), 0.0, -1.0, np.nextafter(1e9, 2e9)])
def test_costs_outside_1_to_1e9_are_refused(cost: float) -> None:
    with pytest.raises(ValueError, match=r"^unknown_cost must be >= 1 and <= 1e9, or inf, got"):
        cost_or_inf(cost, "unknown_cost")


@pytest.mark.parametrize(
    ("width", "height", "resolution", "match"),
    [
        (1e12, 1e-6, 1e-6, r"would need 1e\+18 cells \(3\.47 EiB of float32\); the maximum"),
        (1e-6, 1e13, 1e-6, r"would need 1e\+19 cells \(34\.7 EiB of float32\); the maximum"),
        (1.0, 1e24, 1e-6, r"would need 1e\+36 cells \(3\.31e\+12 YiB of float32\); the max"),
        (1e308, 1.0, 1.0, r"would need 1e\+308 cells \(more bytes than exist of float32\);"),
        # width / resolution overflows: inf cells, not math.ceil's NaN error.
        (1e308, 1.0, 1e-6, r"would need more than 1e308 cells \(more bytes than exist\); the"),
        (1.0, 1e308, 1e-6, r"would need more than 1e308 cells \(more bytes than exist\); the"),
    ],
)
def test_one_axis_alone_too_long_is_quoted_by_its_count(
    width: float, height: float, resolution: float, match: str
) -> None:
    with pytest.raises(ValueError, match=match):
        OccupancyGrid.empty(width=width, height=height, resolution=resolution)


@pytest.mark.parametrize("resolution", [1.0, 0.5, 0.25, 2.0])
@pytest.mark.parametrize("n", [1, 7, 1000])
def test_a_ratio_within_1e_9_cells_of_n_is_n_cells(n: int, resolution: float) -> None:
    # Binary resolutions: (n + d) * resolution / resolution is n + d to a few ulps of n.
    for d, cells in ((0.5e-9, n), (0.99e-9, n), (1.5e-9, n + 1), (3e-9, n + 1)):
        got = grid_shape(
            width=(n + d) * resolution, height=resolution, resolution=resolution, what="g"
        )
        assert got == (1, cells), (d, got)
