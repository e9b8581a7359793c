"""A caller's inverted axis stays inverted through plot_grid, plot_scene and the rest.

``imshow`` (the map) and plot_scene's ``set_xlim``/``set_ylim`` with increasing
limits turned an axis the caller had inverted (``ax.invert_yaxis()``, an image
convention) the right way round again.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.mapping import OccupancyGrid
from navkit.planning import ConicAttraction, sample_field
from navkit.plot import plot_field, plot_grid, plot_path, plot_scene
from navkit.sim import Scene, World

pytest.importorskip("matplotlib")
from matplotlib.figure import Figure


def _grid() -> OccupancyGrid:
    occupied = np.zeros((4, 6), dtype=bool)
    occupied[3, :] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.5, origin=(1.0, 2.0, 0.0))


def _rotated_grid() -> OccupancyGrid:
    return OccupancyGrid.from_occupancy(np.zeros((4, 6), dtype=bool), resolution=0.5,
                                        origin=(1.0, 2.0, 0.3))  # fmt: skip


def _scene() -> Scene:
    return Scene("room", grid=_grid(), world=World([box(1.0, 2.0, 4.0, 4.0).exterior]),
                 paths=(("plan", np.array([[1.5, 2.5], [3.5, 3.5]])),))  # fmt: skip


_DRAWINGS: dict[str, Callable[[Any], Any]] = {
    "grid": lambda ax: plot_grid(_grid(), ax=ax),
    "rotated grid": lambda ax: plot_grid(_rotated_grid(), ax=ax),
    "scene": lambda ax: plot_scene(_scene(), ax=ax),
    "path": lambda ax: plot_path(np.array([[0.0, 0.0], [1.0, 2.0]]), ax=ax),
    "contour": lambda ax: plot_field(
        sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1, 1), ylim=(-1, 1), resolution=0.25),
        ax=ax, kind="contour"),
}  # fmt: skip


@pytest.mark.parametrize("inverted", ["x", "y", "xy", ""])
@pytest.mark.parametrize("drawing", list(_DRAWINGS))
def test_the_callers_axis_directions_are_kept(drawing: str, inverted: str) -> None:
    ax = Figure().add_subplot()
    if "x" in inverted:
        ax.invert_xaxis()
    if "y" in inverted:
        ax.invert_yaxis()
    _DRAWINGS[drawing](ax)
    assert ax.xaxis_inverted() == ("x" in inverted)
    assert ax.yaxis_inverted() == ("y" in inverted)


@pytest.mark.parametrize("drawing", ["grid", "scene"])
def test_an_inverted_view_shows_the_same_window(drawing: str) -> None:
    upright = Figure().add_subplot()
    _DRAWINGS[drawing](upright)
    flipped = Figure().add_subplot()
    flipped.invert_yaxis()
    _DRAWINGS[drawing](flipped)
    assert flipped.get_xlim() == pytest.approx(upright.get_xlim())
    assert flipped.get_ylim() == pytest.approx(upright.get_ylim()[::-1])


def test_later_drawing_keeps_an_inverted_axis_after_a_grid() -> None:
    ax = Figure().add_subplot()
    ax.invert_yaxis()
    plot_grid(_grid(), ax=ax)
    plot_path(np.array([[0.0, 0.0], [6.0, 7.0]]), ax=ax)  # autoscaling widens the view
    low, high = ax.get_ylim()
    assert ax.yaxis_inverted() and low >= 7.0 and high <= 0.0
