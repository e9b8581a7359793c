"""rasterize_polygons (and OccupancyGrid.from_polygons): shapely obstacles to occupancy."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import Point, Polygon, box

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, rasterize_polygons


def brute_force_raster(
    geoms: list[shapely.Geometry], x0: float, y0: float, shape: tuple[int, int], res: float
) -> np.ndarray:
    out = np.zeros(shape, dtype=bool)
    for r in range(shape[0]):
        for c in range(shape[1]):
            cell = box(x0 + c * res, y0 + r * res, x0 + (c + 1) * res, y0 + (r + 1) * res)
            out[r, c] = any(g.intersects(cell) for g in geoms)
    return out


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_rasterize_matches_brute_force(seed: int) -> None:
    rng = np.random.default_rng(seed)
    geoms: list[shapely.Geometry] = []
    for _ in range(3):
        cx, cy = rng.uniform(-1, 4, 2)
        pts = rng.uniform(-0.8, 0.8, size=(5, 2)) + np.array([cx, cy])
        geoms.append(Polygon(pts).convex_hull)
    geoms.append(Point(rng.uniform(0, 3, 2)).buffer(0.2))
    grid = rasterize_polygons(geoms, bounds=(-0.5, -0.3, 3.5, 2.7), resolution=0.25)
    assert grid.shape == (12, 16)
    expected = brute_force_raster(geoms, -0.5, -0.3, grid.shape, 0.25)
    assert np.array_equal(grid.occupied(), expected)
    assert np.array_equal(grid.free(), ~expected)
    assert grid.origin == Pose2D(-0.5, -0.3, 0.0) and grid.resolution == 0.25


def test_rasterize_is_conservative() -> None:
    # A wall exactly on a cell boundary marks the cells on both sides.
    grid = rasterize_polygons(
        box(1.0, 0.0, 1.0, 1.0).buffer(1e-9), bounds=(0, 0, 2, 1), resolution=0.5
    )
    assert grid.occupied().tolist() == [[False, True, True, False]] * 2
    # A sliver thinner than a cell still blocks it.
    thin = OccupancyGrid.from_polygons(
        [box(0.6, 0.1, 0.61, 0.2)], bounds=(0, 0, 2, 1), resolution=0.5
    )
    assert thin.occupied().sum() == 1 and thin.occupied()[0, 1]


def test_rasterize_skips_empty_and_outside_geometries() -> None:
    grid = rasterize_polygons(
        [Polygon(), box(5, 5, 6, 6), box(-3, 0.2, -2, 0.3)],
        bounds=(0, 0, 2, 1),
        resolution=0.5,
    )
    assert not grid.occupied().any() and grid.free().all()


def test_rasterize_validation() -> None:
    with pytest.raises(TypeError, match=r"geometries\[1\] must be a shapely geometry"):
        rasterize_polygons([box(0, 0, 1, 1), "box"], bounds=(0, 0, 1, 1), resolution=0.1)
    with pytest.raises(ValueError, match="max > min"):
        rasterize_polygons([], bounds=(0, 0, 0, 1), resolution=0.1)
    with pytest.raises(ValueError, match="bounds must have length 4"):
        rasterize_polygons([], bounds=(0, 0, 1), resolution=0.1)
    with pytest.raises(ValueError, match="resolution must be > 0"):
        rasterize_polygons([], bounds=(0, 0, 1, 1), resolution=0.0)
    with pytest.raises(TypeError, match="positional"):
        rasterize_polygons([], (0, 0, 1, 1), 0.1)  # type: ignore[call-arg]
    # The convenience method validates the same way (it is the same function).
    with pytest.raises(ValueError, match="bounds must have length 4"):
        OccupancyGrid.from_polygons([], bounds=(0, 0, 1), resolution=0.1)
