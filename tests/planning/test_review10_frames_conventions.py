"""Frame conventions shared by the mapping and planning grids (review 10).

Checked against independent formulas on non-square grids (3 x 7 and 7 x 3,
where a swapped shape shows), resolutions that are not powers of two and
negative origins: ROS map_server's placement of image pixels, which cell a
point on a cell border falls in, and where planned paths run.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.planning import ConicAttraction, FieldDStar, MapPlanner, sample_field

SHAPES = [(3, 7), (7, 3)]


def _ros_pixel_centre(
    pixel: tuple[int, int], height: int, res: float, origin: tuple[float, float, float]
) -> tuple[float, float]:
    """World centre of image pixel (image row, col) by the map_server YAML rules.

    The image's top row has the largest y; ``origin`` is the pose of the
    lower-left corner of the bottom-left pixel, the yaw turning the map about it.
    """
    row, col = pixel
    lx = (col + 0.5) * res
    ly = (height - 1 - row + 0.5) * res
    ox, oy, yaw = origin
    c, s = math.cos(yaw), math.sin(yaw)
    return ox + c * lx - s * ly, oy + s * lx + c * ly


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("yaw", [0.0, 0.5, -3.0])
def test_read_map_places_a_corner_pixel_where_map_server_does(
    tmp_path: Path, shape: tuple[int, int], yaw: float
) -> None:
    height, width = shape
    origin = (-1.0, -2.0, yaw)
    for pixel in [(0, 0), (0, width - 1), (height - 1, 0), (height - 1, width - 1)]:
        image = np.full(shape, 254, dtype=np.uint8)
        image[pixel] = 0
        (tmp_path / "m.pgm").write_bytes(f"P5 {width} {height} 255\n".encode() + image.tobytes())
        (tmp_path / "m.yaml").write_text(
            f"image: m.pgm\nresolution: 0.03\norigin: [{origin[0]}, {origin[1]}, {yaw}]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
        )
        grid = read_map(tmp_path / "m.yaml")
        assert grid.shape == shape
        cells = np.argwhere(grid.occupied())
        assert cells.shape == (1, 2)
        want = _ros_pixel_centre(pixel, height, 0.03, origin)
        np.testing.assert_allclose(grid.cell_to_world(cells[0]), want, atol=1e-12)
        assert grid.world_to_cell(np.array(want)).tolist() == cells[0].tolist()
        # Written back, the pixel is where it was and the origin is kept.
        write_map(grid, tmp_path / "out.yaml")
        again = np.frombuffer((tmp_path / "out.pgm").read_bytes()[-height * width :], np.uint8)
        assert np.argwhere(again.reshape(shape) == 0).tolist() == [list(pixel)]
        assert read_map(tmp_path / "out.yaml").origin == grid.origin


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("res", [0.03, 0.05])
def test_border_points_fall_in_the_same_cell_in_every_grid(
    shape: tuple[int, int], res: float
) -> None:
    rows, cols = shape
    x0, y0 = -1.0, -2.0
    grid = OccupancyGrid(np.zeros(shape, dtype=np.float32), resolution=res, origin=(x0, y0, 0.0))
    planner = FieldDStar(np.ones(shape), resolution=res, origin=(x0, y0, 0.0))
    sampled = sample_field(
        ConicAttraction((0.0, 0.0)),
        xlim=(x0, x0 + cols * res),
        ylim=(y0, y0 + rows * res),
        resolution=res,
    )
    assert sampled.potential.shape == shape
    k = np.stack(
        np.meshgrid(np.arange(-1, rows + 2), np.arange(-1, cols + 2), indexing="ij"), -1
    ).reshape(-1, 2)
    # Cell corners, computed both as the user would (decimal multiples) and by the grid.
    corners = np.vstack(
        (np.column_stack((x0 + k[:, 1] * res, y0 + k[:, 0] * res)), grid.cell_to_world(k - 0.5))
    )
    cells = grid.world_to_cell(corners)
    one_by_one = np.array([grid.world_to_cell(p) for p in corners])
    nodes = np.floor(planner.world_to_node(corners, continuous=True)).astype(np.int64)
    np.testing.assert_array_equal(one_by_one, cells)
    np.testing.assert_array_equal(nodes, cells)
    np.testing.assert_array_equal(sampled.world_to_cell(corners), cells)
    np.testing.assert_array_equal(sampled.contains(corners), grid.contains(corners))
    # A border point belongs to the cell above / to the right of it (half-open cells).
    exact = grid.world_to_cell(grid.cell_to_world(k - 0.5), continuous=True)
    np.testing.assert_allclose(exact, k - 0.5, atol=1e-9)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("planner_name", ["astar", "field_dstar"])
def test_map_planner_paths_stay_in_free_cells_of_a_turned_offset_map(
    shape: tuple[int, int], planner_name: Literal["astar", "field_dstar"]
) -> None:
    rows, cols = shape
    occupied = np.zeros(shape, dtype=bool)
    if rows < cols:
        occupied[:2, cols // 2] = True  # a wall from the bottom: the path goes over it
        start, goal = (0, 0), (0, cols - 1)
    else:
        occupied[rows // 2, :2] = True
        start, goal = (0, 0), (rows - 1, 0)
    res, origin = 0.03, Pose2D(-1.0, -2.0, 0.4)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=res, origin=origin)
    path = MapPlanner(grid, planner=planner_name).plan(
        grid.cell_to_world(start), grid.cell_to_world(goal)
    )
    # Back to continuous (row, col) independently of the grid's methods.
    c, s = math.cos(origin.theta), math.sin(origin.theta)
    d = path.points - (origin.x, origin.y)
    col = (c * d[:, 0] + s * d[:, 1]) / res - 0.5
    row = (-s * d[:, 0] + c * d[:, 1]) / res - 0.5
    np.testing.assert_allclose((row[0], col[0]), start, atol=1e-9)
    np.testing.assert_allclose((row[-1], col[-1]), goal, atol=1e-9)
    t = np.linspace(0.0, 1.0, 101)
    for i in range(len(row) - 1):
        r = row[i] + t * (row[i + 1] - row[i])
        q = col[i] + t * (col[i + 1] - col[i])
        # Interior points of a cell's square only (a path may run along an edge).
        ri, qi = np.floor(r + 0.5).astype(int), np.floor(q + 0.5).astype(int)
        interior = (np.abs(r - ri) < 0.5 - 1e-9) & (np.abs(q - qi) < 0.5 - 1e-9)
        assert np.all((ri[interior] >= 0) & (ri[interior] < rows))
        assert np.all((qi[interior] >= 0) & (qi[interior] < cols))
        assert not occupied[ri[interior], qi[interior]].any()
