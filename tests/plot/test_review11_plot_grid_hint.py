"""plot_grid's TypeError says how to make an OccupancyGrid of what was passed.

It said only "grid must be an OccupancyGrid, got ndarray": a user with an
occupancy array, a LocalGrid or a ScanMapper was not told how to convert it.
Each conversion the message gives must draw the same cells.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.plot import plot_grid

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("value", [np.zeros((3, 4), dtype=bool), [[0.0, 1.0]]])
def test_an_array_is_told_how_to_become_a_grid(value: object) -> None:
    with pytest.raises(TypeError, match=r"grid must be .*OccupancyGrid.*from_occupancy.*"
                                        r"from_probabilities"):  # fmt: skip
        plot_grid(value)  # type: ignore[arg-type]


def test_a_local_grid_is_told_a_conversion_that_keeps_its_cells() -> None:
    g = LocalGrid.from_points([[0.5, -0.2], [-0.3, 0.7]], half_width=1.0, resolution=0.1)
    with pytest.raises(TypeError, match="LocalGrid: convert it") as caught:
        plot_grid(g)  # type: ignore[arg-type]
    assert "from_occupancy(g.occupied" in str(caught.value)
    # The conversion the message gives, followed to the letter, keeps every cell.
    r, h = g.resolution, g.half_width
    grid = OccupancyGrid.from_occupancy(g.occupied, resolution=r,
                                        origin=(-h - r / 2, -h - r / 2, 0.0))  # fmt: skip
    points = np.array([[0.5, -0.2], [-0.3, 0.7], [0.9, 0.9], [-1.0, -1.0]])
    np.testing.assert_array_equal(grid.world_to_cell(points), g.world_to_cell(points))
    assert plot_grid(grid).images


def test_a_mapper_with_a_grid_map_is_told_to_pass_it() -> None:
    class Holder:
        map = OccupancyGrid.from_occupancy(np.zeros((2, 2), dtype=bool), resolution=1.0)

    with pytest.raises(TypeError, match=r"got Holder: pass its map"):
        plot_grid(Holder())  # type: ignore[arg-type]
