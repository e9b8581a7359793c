"""rasterize_polygons (and OccupancyGrid.from_polygons): shapely obstacles to occupancy."""

from __future__ import annotations

import math

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
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6 and <= 1e6 m"):
        rasterize_polygons([], bounds=(0, 0, 1, 1), resolution=0.0)
    with pytest.raises(TypeError, match="positional"):
        rasterize_polygons([], (0, 0, 1, 1), 0.1)  # type: ignore[call-arg]
    # The convenience method validates the same way (it is the same function).
    with pytest.raises(ValueError, match="bounds must have length 4"):
        OccupancyGrid.from_polygons([], bounds=(0, 0, 1), resolution=0.1)


# ------------------------------------------------------------ issue 12: bad input
def test_rasterize_checks_the_size_before_allocating() -> None:
    with pytest.raises(ValueError, match=r"bounds must lie within ±1e9 m"):
        rasterize_polygons([], bounds=(-1e308, -1e308, 1e308, 1e308), resolution=1e-3)
    with pytest.raises(ValueError, match=r"would need 1e\+18 cells \(3\.47 EiB of float32\)"):
        rasterize_polygons([], bounds=(0, 0, 1e6, 1e6), resolution=1e-3)
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6"):
        rasterize_polygons([], bounds=(0, 0, 1, 1), resolution=5e-324)


def test_rasterize_refuses_what_is_not_geometries() -> None:
    for value in ({}, {"a": box(0, 0, 1, 1)}, "box", 3, None):
        with pytest.raises(TypeError, match="geometries must be a shapely geometry or an iterable"):
            rasterize_polygons(value, bounds=(0, 0, 1, 1), resolution=0.1)
    with pytest.raises(ValueError, match=r"geometries\[0\] has non-finite coordinates"):
        rasterize_polygons([Point(math.nan, 0.5)], bounds=(0, 0, 1, 1), resolution=0.1)
    with pytest.raises(ValueError, match=r"geometries\[1\] has non-finite coordinates"):
        rasterize_polygons(
            [box(0, 0, 1, 1), box(0, 0, math.inf, 1)], bounds=(0, 0, 1, 1), resolution=0.1
        )


def test_rasterize_refuses_nan_coordinates_that_the_bounds_leave_out() -> None:
    # GEOS computes bounds without the NaN coordinates: these have finite bounds.
    with np.errstate(invalid="ignore"):  # shapely warns while building them
        bad = [
            shapely.LineString([(0.0, 0.0), (1.0, math.nan)]),
            Polygon([(0.0, 0.0), (1.0, 0.0), (math.nan, 1.0), (0.0, 1.0)]),
            shapely.MultiPoint([(0.5, 0.5), (math.nan, 1.0)]),  # all-NaN: empty in shapely 2.0
        ]
    for geom in bad:
        with np.errstate(invalid="ignore"):  # shapely 2.0 warns computing them
            assert np.isfinite(geom.bounds).all()
        with pytest.raises(ValueError, match=r"geometries\[1\] has non-finite coordinates"):
            rasterize_polygons([box(0, 0, 1, 1), geom], bounds=(0, 0, 1, 1), resolution=0.1)
    # A NaN z (a 2-D point read as 3-D) is not a coordinate of the raster.
    grid = rasterize_polygons(Point(0.55, 0.55, math.nan), bounds=(0, 0, 1, 1), resolution=0.1)
    assert grid.occupied().sum() == 1 and grid.occupied()[5, 5]


def test_huge_obstacles_are_quick_and_exact() -> None:
    # An obstacle far larger than the area: every cell, without an overflow.
    grid = rasterize_polygons(
        box(-1e300, -1e300, 1e300, 1e300), bounds=(0, 0, 50, 40), resolution=0.05
    )
    assert grid.shape == (800, 1000) and grid.occupied().all()
    # A disc covering most of a 1000 x 1000 grid: blocks inside and outside it are
    # decided whole; the rim cell by cell.
    disc = Point(25.0, 25.0).buffer(20.0, quad_segs=64)
    big = rasterize_polygons(disc, bounds=(0, 0, 50, 50), resolution=0.05)
    rows, cols = np.indices(big.shape)
    centre_d = np.hypot(0.05 * cols + 0.025 - 25.0, 0.05 * rows + 0.025 - 25.0)
    occ = big.occupied()
    assert occ[centre_d < 19.9].all() and not occ[centre_d > 20.1].any()


def test_rasterize_leaves_the_geometries_as_they_were() -> None:
    shape = box(0.2, 0.2, 0.6, 0.6)
    assert not shapely.is_prepared(shape)
    rasterize_polygons([shape], bounds=(0, 0, 1, 1), resolution=0.1)
    assert not shapely.is_prepared(shape)
    shapely.prepare(shape)
    rasterize_polygons([shape], bounds=(0, 0, 1, 1), resolution=0.1)
    assert shapely.is_prepared(shape)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_block_subdivision_matches_brute_force(seed: int) -> None:
    # Tiny leaf blocks: the block tests (missed, covered, split) decide most cells.
    import navkit.mapping._rasterize as raster

    rng = np.random.default_rng(seed)
    geoms: list[shapely.Geometry] = [
        Point(rng.uniform(0, 3, 2)).buffer(rng.uniform(0.1, 1.0)),
        Polygon(rng.uniform(-0.5, 3.5, size=(6, 2))).convex_hull,
        shapely.LineString(rng.uniform(-0.5, 3.5, size=(3, 2))),
        box(0.5, 0.5, 1.5, 1.0),  # edges on cell boundaries
    ]
    leaf = raster._LEAF_CELLS
    raster._LEAF_CELLS = 2
    try:
        grid = rasterize_polygons(geoms, bounds=(-0.5, -0.25, 3.5, 2.75), resolution=0.125)
    finally:
        raster._LEAF_CELLS = leaf
    expected = brute_force_raster(geoms, -0.5, -0.25, grid.shape, 0.125)
    assert np.array_equal(grid.occupied(), expected)


def test_edges_on_cell_boundaries_occupy_both_sides_however_they_round() -> None:
    # 0.3 / 0.1 rounds to 3 exactly, but 0.1 * 3 to 0.30000000000000004: the
    # square of cell 3 started just beyond the obstacle's edge at 0.3, so cell 3
    # stayed free though world_to_cell puts the edge's points in it (an edge at
    # 0.2, which rounds the other way, occupied cells 1 and 2).
    grid = rasterize_polygons(box(0.0, 0.0, 0.3, 0.3), bounds=(0, 0, 1, 1), resolution=0.1)
    expected = np.zeros((10, 10), dtype=bool)
    expected[:4, :4] = True
    assert np.array_equal(grid.occupied(), expected)
    assert grid.occupied()[tuple(grid.world_to_cell([0.3, 0.3]))]


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.sampled_from([0.1, 0.05, 0.07, 0.3, 1e-6, 3.3]),
    st.floats(-1e9, 1e9 - 66.0),  # the grid's 20 cells (at most 66 m) end within 1e9 m
)
def test_every_obstacle_point_lies_in_an_occupied_cell(
    seed: int, res: float, xmin: float
) -> None:
    # Points on and within a few ulps of cell boundaries: the cell world_to_cell
    # gives each (inside the grid) must be occupied.
    rng = np.random.default_rng(seed)
    ymin = float(rng.uniform(-10, 10))
    k = rng.integers(0, 20, (40, 2))
    pts = np.column_stack((xmin + k[:, 1] * res, ymin + k[:, 0] * res))
    pts += rng.integers(-3, 4, pts.shape) * np.spacing(pts)
    grid = rasterize_polygons(
        shapely.MultiPoint(pts), bounds=(xmin, ymin, xmin + 20 * res, ymin + 20 * res),
        resolution=res,
    )  # fmt: skip
    cells = grid.world_to_cell(pts)
    inside = grid.contains(pts)
    assert inside.any()
    assert grid.occupied()[cells[inside, 0], cells[inside, 1]].all()
