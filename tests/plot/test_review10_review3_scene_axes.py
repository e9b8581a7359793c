"""plot_scene on the caller's axes widens the view only along axes that showed something.

The widening to what the caller's axes showed took both axes' limits as soon
as either held something: after an ``axhline`` (data along y only) or a
``set_xlim`` alone, the other axis's default [0, 1] was kept in view, and a
scene far from the origin was squeezed into a sliver beside it.
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


def _scene() -> Scene:
    occupied = np.zeros((6, 8), dtype=bool)
    occupied[2:4, 3:5] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5, origin=(100.0, 200.0, 0.0))
    return Scene("room", grid=grid, paths=(("plan", np.array([[100.5, 200.5],
                                                              [103.5, 202.5]])),))  # fmt: skip


def _fresh_view() -> tuple[tuple[float, float], tuple[float, float]]:
    ax = plot_scene(_scene(), ax=_axes())
    return ax.get_xlim(), ax.get_ylim()


@pytest.mark.parametrize("axis", ["x", "y"])
def test_a_reference_line_along_one_axis_keeps_the_other_axis_on_the_scene(axis: str) -> None:
    ax = _axes()
    if axis == "y":
        ax.axhline(205.0)  # data along y only: any x
        before = ax.get_ylim()
    else:
        ax.axvline(105.0)
        before = ax.get_xlim()
    plot_scene(_scene(), ax=ax)
    fresh_x, fresh_y = _fresh_view()
    fresh, other = (fresh_y, fresh_x) if axis == "y" else (fresh_x, fresh_y)
    views = (ax.get_xlim(), ax.get_ylim())
    along, across = (views[1], views[0]) if axis == "y" else views
    # Across the line: the scene's own view; along it: the scene's and the line's.
    assert across == pytest.approx(other)
    assert along == pytest.approx((min(fresh[0], before[0]), max(fresh[1], before[1])))


@pytest.mark.parametrize("axis", ["x", "y"])
def test_limits_set_along_one_axis_only_widen_that_axis(axis: str) -> None:
    ax = _axes()
    if axis == "x":
        ax.set_xlim(90.0, 95.0)
    else:
        ax.set_ylim(190.0, 195.0)
    plot_scene(_scene(), ax=ax)
    fresh_x, fresh_y = _fresh_view()
    if axis == "x":
        assert ax.get_xlim() == pytest.approx((90.0, fresh_x[1]))
        assert ax.get_ylim() == pytest.approx(fresh_y)
    else:
        assert ax.get_ylim() == pytest.approx((190.0, fresh_y[1]))
        assert ax.get_xlim() == pytest.approx(fresh_x)


def test_an_image_and_fixed_limits_still_widen_both_axes() -> None:
    ax = _axes()
    ax.imshow(np.zeros((3, 4)))  # origin "upper": the y limits come reversed
    plot_scene(_scene(), ax=ax)
    fresh_x, fresh_y = _fresh_view()
    assert ax.get_xlim() == pytest.approx((-0.5, fresh_x[1]))
    # Widened, and still pointing down as the image left it.
    assert tuple(sorted(ax.get_ylim())) == pytest.approx((-0.5, fresh_y[1]))
    assert ax.yaxis_inverted()
    ax = _axes()
    ax.autoscale(False)  # the caller fixed the default [0, 1] x [0, 1] view
    plot_scene(_scene(), ax=ax)
    assert ax.get_xlim() == pytest.approx((0.0, fresh_x[1]))
    assert ax.get_ylim() == pytest.approx((0.0, fresh_y[1]))
