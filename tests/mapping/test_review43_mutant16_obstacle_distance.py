"""Obstacle distances on grids past one tile, and on grids with no obstacle (review 43).

Mutants of ``navkit.mapping._obstacle_distance`` that the suite let pass: the
distances are computed from SciPy's feature transform in tiles of 2**16 cells,
and every grid of the suite fitted in one tile, so a tile one row short (rows
left as ``np.empty`` made them) or a second column tile whose column indices
restarted at 0 went unseen; and "no obstacle" as a large finite distance
(1e6 cells) instead of ``inf``, which a radius of more than 1e6 cells reaches.
Oracle: :func:`scipy.ndimage.distance_transform_edt` of the whole grid (its
distances, not its indices) and the documented rule of :meth:`inflate`.
Checked: each test fails on its mutants, passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import ndimage

from navkit.mapping import OccupancyGrid, costmap


def _inflate_oracle(occupied: np.ndarray, cells: float) -> np.ndarray:
    return np.asarray(ndimage.distance_transform_edt(~occupied) <= cells + 1e-9)


@pytest.mark.parametrize("shape", [(300, 300), (2, 70_000)])
def test_inflate_past_one_tile_matches_the_distance_transform(shape: tuple[int, int]) -> None:
    # (300, 300): 218 rows a tile, two row tiles. (2, 70000): two column tiles.
    rng = np.random.default_rng(43)
    occupied = rng.random(shape) < 0.002
    occupied[0, 0] = occupied[-1, -1] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5)
    for radius in (0.0, 0.5, 1.2):
        got = grid.inflate(radius)
        assert np.array_equal(got, _inflate_oracle(occupied, radius / 0.5)), radius


def test_a_grid_without_obstacles_inflates_nowhere_whatever_the_radius() -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((3, 4), dtype=bool), resolution=0.5)
    # 1e6 m at 0.5 m cells: a reach of 2e6 cells, farther than any finite stand-in.
    assert not grid.inflate(1e6).any()
    cost = costmap(grid, robot_radius=1e6, inflation_radius=1e6)
    assert (cost == 0).all()
