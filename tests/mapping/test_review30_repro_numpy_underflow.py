"""Costmaps and rasterized maps do not depend on numpy's error state (review 30, reproducibility).

Both underflow by design on ordinary inputs: the inflation band decays as
``exp(-cost_scaling_factor * (d - robot_radius))``, whose far cells underflow
to 0 (cost 0, as in Nav2), and the exact cell edges of ``rasterize_polygons``
are found by bisection over the floats, which near a coordinate 0 visits
subnormal ones. numpy ignores underflow by default, so the same calls raised
``FloatingPointError`` only after a caller's ``np.seterr(under="raise")`` (or
``all="raise"``, a common NaN hunt) and warned under ``"warn"``: whether they
returned depended on global state.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import box

from navkit.mapping import OccupancyGrid, costmap, rasterize_polygons, traversal_costs
from navkit.mapping.io import grid_to_msg_fields, write_map
from navkit.planning import MapPlanner


def _grid() -> OccupancyGrid:
    occupied = np.zeros((60, 60), dtype=bool)
    occupied[30, 30] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05)


def _far_grid() -> OccupancyGrid:
    occupied = np.zeros((100, 100), dtype=bool)
    occupied[0, 0] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=1.0)


# exp(-1000 * 1.4): far below the smallest subnormal.
_CASES = {
    "costmap": lambda g: costmap(
        g, robot_radius=0.1, inflation_radius=1.5, cost_scaling_factor=1000.0
    ),
    "method": lambda g: g.costmap(
        robot_radius=0.1, inflation_radius=1.5, cost_scaling_factor=1000.0
    ),
    "traversal_costs": lambda g: traversal_costs(
        g, robot_radius=0.1, inflation_radius=1.5, cost_scaling_factor=1000.0
    ),
    # 1 m cells, the obstacle in a corner: cells up to 140 m from it, exp(-10 * 139.9).
    "MapPlanner": lambda _: (
        MapPlanner(_far_grid(), robot_radius=0.1, inflation_radius=150.0)
        .plan((50.5, 50.5), (99.5, 99.5))
        .points
    ),
}


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize("mode", ["raise", "warn"])
def test_the_same_costs_whatever_numpys_underflow_setting(name: str, mode: str) -> None:
    call = _CASES[name]
    grid = _grid()
    expected = call(grid)  # numpy's default state: underflow ignored
    with np.errstate(under=mode):
        got = call(grid)  # raised FloatingPointError / warned before the fix
    assert np.array_equal(got, expected)


def test_far_cells_cost_nothing_under_raise() -> None:
    with np.errstate(all="raise"):
        costs = costmap(_grid(), robot_radius=0.1, inflation_radius=1.5, cost_scaling_factor=1000.0)
    assert costs[30, 30] == 254  # lethal
    assert costs[30, 33] == 0  # 0.15 m away: exp(-1000 * 0.05) * 252 truncates to 0
    assert costs[0, 0] == 0  # the corner: an underflow to exactly 0


# A unit box from the origin at 0.4 m: edge 0's bracket holds subnormals.
_RASTER = {
    "rasterize_polygons": lambda: (
        rasterize_polygons(
            [box(0.0, 0.0, 1.0, 1.0)], bounds=(0.0, 0.0, 2.0, 2.0), resolution=0.4
        ).logodds
    ),
    "from_polygons": lambda: (
        OccupancyGrid.from_polygons(
            [box(0.0, 0.0, 1.0, 1.0)], bounds=(0.0, 0.0, 2.0, 2.0), resolution=0.4
        ).logodds
    ),
}


@pytest.mark.parametrize("name", sorted(_RASTER))
@pytest.mark.parametrize("mode", ["raise", "warn"])
def test_the_same_raster_whatever_numpys_underflow_setting(name: str, mode: str) -> None:
    call = _RASTER[name]
    expected = call()
    with np.errstate(under=mode):
        got = call()  # raised FloatingPointError / warned before the fix
    assert np.array_equal(got, expected)
    assert (got > 0).sum() == 9  # cells 0..2 on each axis: [0, 1.2] covers [0, 1]


# OccupancyGrid.probability's exp(-l) underflows for l > ~708 (p = 1), and the
# scale image and message tables probe it far beyond: every real map.
_LOGODDS = np.array([[-800.0, -2.0, 0.0, 2.0, 800.0]])


def _write_scale(grid: OccupancyGrid, folder: Path) -> bytes:
    path = write_map(grid, folder / "m.yaml", mode="scale")
    return path.with_suffix(".png").read_bytes()


_PROBABILITY = {
    "probability": lambda grid, _: grid.probability(),
    "grid_to_msg_fields": lambda grid, _: grid_to_msg_fields(grid).data,
    "write_map_scale": _write_scale,
}


@pytest.mark.parametrize("name", sorted(_PROBABILITY))
def test_probabilities_whatever_numpys_underflow_setting(name: str, tmp_path: Path) -> None:
    call = _PROBABILITY[name]
    # Thresholds of this test alone: the image and message tables are cached per
    # thresholds, so the first call (under "raise" here) is the one that builds them.
    thresh = 0.6 + 0.01 * sorted(_PROBABILITY).index(name)
    grid = OccupancyGrid(_LOGODDS, resolution=0.1, occupied_thresh=thresh, free_thresh=0.17)
    with np.errstate(under="raise"):
        got = call(grid, tmp_path)
    expected = call(grid, tmp_path)
    assert np.array_equal(np.asarray(got), np.asarray(expected))
