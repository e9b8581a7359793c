"""OccupancyGrid.world_to_cell: the continuous coordinates against the cells."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.grid_coords import round_half_up
from navkit.mapping import OccupancyGrid

coordinate = st.floats(-1e9, 1e9, allow_nan=False)


@settings(max_examples=50, deadline=None)
@given(
    st.floats(1e-6, 1e6),
    coordinate,
    coordinate,
    st.floats(-math.pi, math.pi),
    st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=4),
)
def test_cells_are_the_continuous_coordinates_rounded_half_up_away_from_edges(
    resolution: float, x: float, y: float, yaw: float, points: list[tuple[float, float]]
) -> None:
    grid = OccupancyGrid(np.zeros((2, 2)), resolution=resolution, origin=(x, y, yaw))
    pts = np.array(points)
    cells = grid.world_to_cell(pts)
    continuous = grid.world_to_cell(pts, continuous=True)
    differ = round_half_up(continuous) != cells
    # Where they differ, the continuous value lies on the cell's edge (c ± 0.5)
    # to within its own rounding (a few ulps), as the docstring says.
    edge = np.minimum(np.abs(continuous - (cells - 0.5)), np.abs(continuous - (cells + 0.5)))
    assert (edge[differ] <= 2.0 * np.spacing(np.abs(continuous[differ]))).all()


test_cells_are_the_continuous_coordinates_rounded_half_up_away_from_edges_thoroughly = slow_twin(
    test_cells_are_the_continuous_coordinates_rounded_half_up_away_from_edges, max_examples=300
)


def test_a_point_a_hair_below_an_edge() -> None:
    # The documented exception: -1e-17 m is in cell -1, its continuous -0.5.
    grid = OccupancyGrid(np.zeros((2, 2)), resolution=1.0)
    assert grid.world_to_cell([-1e-17, 0.5]).tolist() == [0, -1]
    assert grid.world_to_cell([-1e-17, 0.5], continuous=True).tolist() == [0.0, -0.5]
