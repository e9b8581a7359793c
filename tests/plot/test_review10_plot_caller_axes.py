"""plot_scene on the caller's axes keeps in view what they showed before.

It set the view to the scene alone: a line the caller had drawn, the limits
they had set, or a first scene on the same axes were cropped out of sight.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.plot import plot_scene
from navkit.sim import Scene

pytest.importorskip("matplotlib")


def _axes() -> Any:
    from matplotlib.figure import Figure

    return Figure().add_subplot()


def _scene(x0: float = 0.0) -> Scene:
    occupied = np.zeros((6, 8), dtype=bool)
    occupied[2:4, 3:5] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5, origin=(x0, -1.0, 0.0))
    return Scene("room", grid=grid, paths=(("plan", np.array([[x0 + 0.5, 0.0],
                                                                [x0 + 3.5, 1.5]])),))  # fmt: skip


def _sees(ax: Any, x: float, y: float) -> bool:
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return bool(min(x0, x1) <= x <= max(x0, x1) and min(y0, y1) <= y <= max(y0, y1))


def _scene_corners(scene: Scene) -> list[tuple[float, float]]:
    assert scene.grid is not None
    grid = scene.grid
    local = [[0.0, 0.0], [grid.width, grid.height]]
    return [(float(x), float(y)) for x, y in grid.origin.transform_points(local)]


def test_the_callers_own_line_stays_in_view() -> None:
    ax = _axes()
    ax.plot([20.0, 21.0], [15.0, 16.0], label="mine")
    scene = _scene()
    plot_scene(scene, ax=ax)
    assert _sees(ax, 20.0, 15.0) and _sees(ax, 21.0, 16.0)
    assert all(_sees(ax, x, y) for x, y in _scene_corners(scene))
    assert ax.lines[0].get_label() == "mine"


def test_limits_the_caller_set_stay_in_view() -> None:
    ax = _axes()
    ax.set_xlim(-10.0, 10.0)
    ax.set_ylim(-8.0, 8.0)
    plot_scene(_scene(), ax=ax)
    assert _sees(ax, -10.0, -8.0) and _sees(ax, 10.0, 8.0)


def test_a_second_scene_on_the_same_axes_keeps_the_first_in_view() -> None:
    ax = _axes()
    first, second = _scene(0.0), _scene(30.0)
    plot_scene(first, ax=ax)
    plot_scene(second, ax=ax)
    assert all(_sees(ax, x, y) for x, y in _scene_corners(first) + _scene_corners(second))


def test_fresh_axes_of_the_caller_show_what_new_axes_show() -> None:
    scene = _scene()
    mine = plot_scene(scene, ax=_axes())
    new = plot_scene(scene)
    assert mine.get_xlim() == pytest.approx(new.get_xlim())
    assert mine.get_ylim() == pytest.approx(new.get_ylim())
