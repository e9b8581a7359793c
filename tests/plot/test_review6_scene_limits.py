"""plot_scene's limits fit a scene smaller than its 0.25 m margin (a map of micrometre cells)."""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.plot import plot_scene
from navkit.sim import Scene


@pytest.mark.parametrize("resolution", [1e-6, 1e-4, 0.01])
def test_a_tiny_map_fills_the_picture(resolution: float) -> None:
    occupied = np.zeros((10, 10), dtype=bool)
    occupied[4:6, 4:6] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=resolution)
    side = 10 * resolution
    ax = plot_scene(Scene("tiny", grid=grid, points=(("p", np.array([[side / 2, side / 2]])),)))
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    # The map spans [0, side]: it must be seen whole and take a third of the view or more.
    assert x0 < 0.0 < side < x1 and y0 < 0.0 < side < y1
    assert x1 - x0 <= 3.0 * side * (1 + 1e-9)
    assert y1 - y0 <= 3.0 * side * (1 + 1e-9)


def test_a_single_point_keeps_its_quarter_metre() -> None:
    ax = plot_scene(Scene("dot", points=(("p", np.array([[2.0, -1.0]])),)))
    assert ax.get_xlim() == pytest.approx((1.75, 2.25))
    assert ax.get_ylim() == pytest.approx((-1.25, -0.75))


@pytest.mark.parametrize(("span", "margin"), [(0.25, 0.25), (2.0, 0.25), (10.0, 0.5)])
def test_larger_scenes_keep_their_margin(span: float, margin: float) -> None:
    path = np.array([[0.0, 0.0], [span, span]])
    ax = plot_scene(Scene("line", paths=(("p", path),)))
    assert ax.get_xlim() == pytest.approx((-margin, span + margin))
