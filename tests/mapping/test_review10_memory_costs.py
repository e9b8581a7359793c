"""Peak memory of obstacle distances, inflation and costs (review 10).

A distance transform needs its float64 result (8 bytes a cell) and SciPy's
feature transform (two int32 indices, 8): about 17 bytes a cell. The earlier
code let SciPy compute the distances itself, with float64 temporaries of
twice the grid's size (33 bytes a cell for ``obstacle_distance`` and
``inflate``, 35 for ``costmap`` and ``traversal_costs``, whose Nav2 result is
1 byte a cell). Bounds: peak NumPy allocations (tracemalloc) in bytes a cell,
with margin; the values must stay SciPy's, bit for bit.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy import ndimage

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, costmap, traversal_costs
from navkit.mapping._obstacle_distance import obstacle_distance

SIDE = 1000
CELLS = SIDE * SIDE


def _peak_per_cell(call: Callable[[], Any]) -> float:
    """Peak bytes a cell allocated while ``call`` runs (its result included)."""
    return peak_bytes(call)[0] / CELLS


def _grid() -> OccupancyGrid:
    rng = np.random.default_rng(0)
    occupied = rng.random((SIDE, SIDE)) < 0.01
    unknown = np.zeros((SIDE, SIDE), dtype=bool)
    unknown[:, : SIDE // 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05, unknown=unknown & ~occupied)


def test_obstacle_distance_keeps_to_the_feature_transform_and_the_result() -> None:
    occupied = _grid().occupied()
    per_cell = _peak_per_cell(lambda: obstacle_distance(occupied))
    assert per_cell < 24.0


def test_obstacle_distance_is_scipys_bit_for_bit_across_tiles() -> None:
    # Shapes whose tiles split rows, columns or both, and strips.
    rng = np.random.default_rng(1)
    for shape in [(1, 200_000), (200_000, 1), (3, 70_000), (300, 700), (1, 1)]:
        occupied = rng.random(shape) < 1e-3
        occupied.flat[rng.integers(occupied.size)] = True
        got = obstacle_distance(occupied)
        want = ndimage.distance_transform_edt(~occupied)
        assert got.dtype == np.float64 and got.shape == shape
        assert np.array_equal(got.view(np.int64), want.view(np.int64))


def test_inflate_peak() -> None:
    grid = _grid()
    per_cell = _peak_per_cell(lambda: grid.inflate(0.3))
    assert per_cell < 24.0


def test_costmap_has_one_float64_grid_at_a_time() -> None:
    grid = _grid()
    per_cell = _peak_per_cell(lambda: costmap(grid, robot_radius=0.2, inflation_radius=2.0))
    assert per_cell < 26.0


def test_traversal_costs_peak() -> None:
    grid = _grid()
    per_cell = _peak_per_cell(
        lambda: traversal_costs(grid, robot_radius=0.2, inflation_radius=2.0, unknown_cost=5.0)
    )
    assert per_cell < 26.0
