"""plot_grid: ROS map orientation on world axes, checked on the rendered pixels."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from plot_pixels import grey_at, render

from navkit.mapping import OccupancyGrid
from navkit.plot import plot_grid

matplotlib = pytest.importorskip("matplotlib")


def _grid(origin: tuple[float, float, float] = (2.0, 1.0, 0.0)) -> OccupancyGrid:
    """6 × 4 m at 0.1 m: an obstacle near the top (high y), unknown cells at the bottom."""
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[30:38, 5:15] = True  # world x in [2.5, 3.5), y in [4.0, 4.8)
    unknown = np.zeros_like(occupied)
    unknown[0:5, 40:55] = True  # world x in [6.0, 7.5), y in [1.0, 1.5)
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=origin, unknown=unknown)


def test_an_obstacle_at_high_y_is_drawn_dark_at_the_top(tmp_path: Path) -> None:
    grid = _grid()
    ax = plot_grid(grid)
    image, pixel = render(ax, tmp_path)
    obstacle, free, unknown = pixel([[3.0, 4.4], [5.0, 2.5], [6.75, 1.25]])
    assert grey_at(image, obstacle) < 0.1
    assert grey_at(image, free) > 0.95
    assert 0.5 < grey_at(image, unknown) < 0.9
    # Row 0 of the image is its top: the high-y obstacle sits above the map's middle.
    assert obstacle[0] < pixel([[3.0, 3.0]])[0, 0] < pixel([[3.0, 1.2]])[0, 0]
    # The dark pixels inside the map are exactly the obstacle's world rectangle
    # x in [2.5, 3.5), y in [4.0, 4.8) (one pixel of slack for antialiasing).
    top, left = pixel([2.0, 5.0])[0]
    bottom, right = pixel([8.0, 1.0])[0]
    dark = np.argwhere(image[top + 2 : bottom - 2, left + 2 : right - 2].mean(axis=2) < 0.2)
    dark += (top + 2, left + 2)
    (r_high, c_low), (r_low, c_high) = pixel([[2.5, 4.8], [3.5, 4.0]])
    assert len(dark) > 100
    assert r_high - 1 <= dark[:, 0].min() and dark[:, 0].max() <= r_low + 1
    assert c_low - 1 <= dark[:, 1].min() and dark[:, 1].max() <= c_high + 1


def test_the_image_covers_the_map_extent_in_metres() -> None:
    ax = plot_grid(_grid())
    assert [float(v) for v in ax.images[0].get_extent()] == pytest.approx([2.0, 8.0, 1.0, 5.0])
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"
    assert ax.get_aspect() == 1.0


def test_a_rotated_origin_rotates_the_map(tmp_path: Path) -> None:
    theta = 0.5
    grid = _grid(origin=(2.0, 1.0, theta))
    ax = plot_grid(grid)
    image, pixel = render(ax, tmp_path)
    centre = grid.cell_to_world([33.5, 9.5])  # middle of the obstacle block
    assert grey_at(image, pixel(centre)) < 0.1
    # Where the block would be without the rotation is free space now.
    assert grey_at(image, pixel([3.0, 4.4])) > 0.95
    x0, x1 = ax.get_xlim()
    corners = grid.origin.transform_points([[0, 0], [6, 0], [0, 4], [6, 4]])
    assert x0 <= corners[:, 0].min() + 1e-9 and x1 >= corners[:, 0].max() - 1e-9
    assert math.isclose(float(corners[2, 0]), 2.0 - 4 * math.sin(theta))


def test_a_huge_grid_is_shrunk_without_losing_one_cell_walls() -> None:
    occupied = np.zeros((30, 5000), dtype=bool)
    occupied[:, 2501] = True  # one cell thick
    ax = plot_grid(OccupancyGrid.from_occupancy(occupied, resolution=0.05))
    shades = np.asarray(ax.images[0].get_array())
    assert shades.shape[1] < 2100
    assert (shades.min(axis=0) == 0.0).sum() >= 1
    assert float(ax.images[0].get_extent()[1]) >= 250.0  # the whole map is covered


@pytest.mark.parametrize("theta", [0.0, 0.4])
def test_a_shrunk_grid_is_drawn_over_its_own_extent_only(tmp_path: Path, theta: float) -> None:
    # 2049 × 3 unknown cells of 1 m are shrunk in blocks of 2 × 2, padded to
    # 2050 × 4: the padding (a row above the map, a column right of it) is not map.
    grid = OccupancyGrid(np.zeros((2049, 3)), resolution=1.0, origin=(10.0, 20.0, theta))
    ax = plot_grid(grid)
    corners = grid.origin.transform_points([[0, 0], [3, 0], [0, 2049], [3, 2049]])
    np.testing.assert_allclose(ax.dataLim.get_points(),
                               [corners.min(axis=0), corners.max(axis=0)], atol=1e-9)  # fmt: skip
    # Zoom in on the top right corner of the map (map frame x = 3 m, y = 2049 m).
    centre = grid.origin.transform_points([[3.0, 2048.0]])[0]
    ax.set_aspect("auto")
    ax.set_xlim(centre[0] - 3.0, centre[0] + 3.0)
    ax.set_ylim(centre[1] - 3.0, centre[1] + 3.0)
    image, pixel = render(ax, tmp_path)
    inside, right, above = pixel(grid.origin.transform_points([[2.5, 2047.5], [3.5, 2047.5],
                                                               [1.5, 2049.5]]))  # fmt: skip
    assert 0.6 < grey_at(image, inside) < 0.9  # unknown grey
    assert grey_at(image, right) > 0.99  # the axes' white background, not map
    assert grey_at(image, above) > 0.99


def test_draws_on_given_axes_with_opacity() -> None:
    from matplotlib.figure import Figure

    ax = Figure().add_subplot()
    assert plot_grid(_grid(), ax=ax, alpha=0.5) is ax
    assert ax.images[0].get_alpha() == 0.5


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"grid": np.zeros((3, 3))}, TypeError, "grid"),
        ({"alpha": 1.5}, ValueError, "alpha"),
        ({"alpha": math.nan}, ValueError, "alpha"),
        ({"ax": "axes"}, TypeError, "ax"),
    ],
)
def test_bad_arguments_are_refused(kwargs: dict, error: type, match: str) -> None:
    grid = kwargs.pop("grid", _grid())
    with pytest.raises(error, match=match):
        plot_grid(grid, **kwargs)
