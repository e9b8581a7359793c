"""OccupancyGrid: constructors, coordinates, views, messages, rasterising and inflation."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import Point, Polygon, box

from navkit._shared.costs import validate_costs
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid


def test_empty_grid_shape_and_extent() -> None:
    grid = OccupancyGrid.empty(3.0, 2.0, 0.1, Pose2D(-1.0, -2.0, 0.0))
    assert grid.shape == (20, 30)
    assert grid.width == pytest.approx(3.0) and grid.height == pytest.approx(2.0)
    assert grid.unknown().all() and not grid.occupied().any() and not grid.free().any()
    # Rounded up to whole cells.
    assert OccupancyGrid.empty(1.01, 0.2, 0.5).shape == (1, 3)


def test_row_zero_is_lowest_y() -> None:
    grid = OccupancyGrid.empty(2.0, 3.0, 0.5, Pose2D(10.0, 20.0, 0.0))
    cells = grid.world_to_cell([[10.1, 20.1], [10.1, 22.9], [11.9, 20.1]])
    assert cells.tolist() == [[0, 0], [5, 0], [0, 3]]


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-20, 20),
    st.floats(-20, 20),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.05, 0.1, 0.3]),
    st.integers(0, 2**32 - 1),
)
def test_world_cell_round_trip(ox: float, oy: float, yaw: float, res: float, seed: int) -> None:
    grid = OccupancyGrid(np.zeros((30, 40)), res, Pose2D(ox, oy, yaw))
    rng = np.random.default_rng(seed)
    cells = np.column_stack((rng.integers(-5, 35, 50), rng.integers(-5, 45, 50)))
    centres = grid.cell_to_world(cells)
    assert np.array_equal(grid.world_to_cell(centres), cells)
    # Any point lies within half a cell diagonal of its cell's centre.
    local = rng.uniform([-1, -1], [13, 10], size=(200, 2))
    pts = grid.origin.transform_points(local)
    back = grid.cell_to_world(grid.world_to_cell(pts))
    assert np.all(np.hypot(*(back - pts).T) <= res * math.sqrt(0.5) + 1e-9)
    # The kernel agrees with a plain numpy statement of the same rule.
    expected = np.floor(local[:, ::-1] / res).astype(np.int64)
    close = np.abs(local / res - np.round(local / res)) < 1e-9
    ok = ~close.any(axis=1)
    assert np.array_equal(grid.world_to_cell(pts)[ok], expected[ok])
    inside = (expected[:, 0] >= 0) & (expected[:, 0] < 30) & (expected[:, 1] >= 0)
    inside &= expected[:, 1] < 40
    assert np.array_equal(grid.contains(pts)[ok], inside[ok])


def test_coordinate_input_validation() -> None:
    grid = OccupancyGrid.empty(1.0, 1.0, 0.1)
    with pytest.raises(ValueError, match="points must have shape"):
        grid.world_to_cell(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="finite"):
        grid.world_to_cell([[math.nan, 0.0]])
    with pytest.raises(ValueError, match="integer"):
        grid.cell_to_world([[0.5, 1.0]])
    assert grid.world_to_cell(np.empty((0, 2))).shape == (0, 2)


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda: OccupancyGrid.empty(1.0, 1.0, -0.1), ValueError, "resolution must be > 0"),
        (lambda: OccupancyGrid.empty(0.0, 1.0, 0.1), ValueError, "width must be > 0"),
        (lambda: OccupancyGrid.empty(1.0, 1.0, 0.1, [0, math.nan, 0]), ValueError, "origin"),
        (lambda: OccupancyGrid(np.zeros(5), 0.1), ValueError, "logodds must be 2-D"),
        (lambda: OccupancyGrid(np.zeros((0, 3)), 0.1), ValueError, "must not be empty"),
        (
            lambda: OccupancyGrid(np.zeros((2, 2)), 0.1, free_thresh=0.7),
            ValueError,
            "free_thresh .* must be smaller",
        ),
        (lambda: OccupancyGrid.from_occupancy(np.zeros((2, 2)), 0.1), TypeError, "boolean"),
        (
            lambda: OccupancyGrid.from_probabilities([[0.2, 1.5]], 0.1),
            ValueError,
            r"probabilities must lie in \[0, 1\]",
        ),
    ],
)
def test_bad_constructor_arguments(call: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        call()  # type: ignore[operator]


def test_views_and_thresholds() -> None:
    p = np.array([[0.0, 0.1, 0.19, 0.2, 0.5, 0.64, 0.66, 0.9, 1.0]])
    grid = OccupancyGrid.from_probabilities(p, 0.1)
    assert grid.occupied().tolist() == [[False] * 6 + [True] * 3]
    assert grid.free().tolist() == [[True] * 3 + [False] * 6]
    assert grid.unknown().tolist() == [[False] * 3 + [True] * 3 + [False] * 3]
    assert grid.occupied(threshold=0.95).sum() == 1
    assert grid.free(threshold=0.5).sum() == 4
    assert np.allclose(grid.probability(), np.clip(p, 1e-3, 1 - 1e-3), atol=1e-6)
    with pytest.raises(ValueError, match="threshold must lie in"):
        grid.occupied(threshold=1.5)


def test_arrays_are_copied_and_read_only() -> None:
    occ = np.zeros((3, 3), dtype=bool)
    grid = OccupancyGrid.from_occupancy(occ, 0.1)
    occ[1, 1] = True
    assert not grid.occupied().any()
    with pytest.raises(ValueError):
        grid.logodds[0, 0] = 1.0
    other = grid.copy()
    before = grid.logodds.copy()
    other.integrate_scan(LaserScan([0.15], 0.0, 0.1, 0.01, 1.0), Pose2D(0.05, 0.05, 0.0))
    assert np.array_equal(grid.logodds, before)
    assert not np.array_equal(other.logodds, before)


def test_from_occupancy_unknown() -> None:
    occ = np.array([[True, False, False]])
    unknown = np.array([[False, False, True]])
    grid = OccupancyGrid.from_occupancy(occ, 1.0, unknown=unknown)
    assert grid.occupied().tolist() == [[True, False, False]]
    assert grid.free().tolist() == [[False, True, False]]
    assert grid.unknown().tolist() == [[False, False, True]]
    with pytest.raises(ValueError, match="must not overlap"):
        OccupancyGrid.from_occupancy(occ, 1.0, unknown=occ)


# --------------------------------------------------------------------- messages
def fake_msg(data: list[int], width: int, height: int, yaw: float) -> SimpleNamespace:
    return SimpleNamespace(
        info=SimpleNamespace(
            width=width,
            height=height,
            resolution=0.05,
            origin=SimpleNamespace(
                position=SimpleNamespace(x=1.5, y=-2.0, z=0.0),
                orientation=SimpleNamespace(
                    x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2)
                ),
            ),
        ),
        data=data,
    )


def test_msg_round_trip() -> None:
    data = [-1, 0, 100, 50, 20, 80]
    grid = OccupancyGrid.from_msg(fake_msg(data, 3, 2, 0.7))
    assert grid.shape == (2, 3)
    assert grid.origin.theta == pytest.approx(0.7)
    assert (grid.origin.x, grid.origin.y) == (1.5, -2.0)
    # data row 0 is the row at the origin (lowest y in the grid frame).
    assert grid.occupied().tolist() == [[False, False, True], [False, False, True]]
    fields = grid.to_msg_fields()
    assert fields["data"].dtype == np.int8
    assert fields["data"].tolist() == [-1, 0, 100, -1, 20, 80]  # 50 % is log-odds 0
    assert fields["origin_orientation"][2:] == pytest.approx((math.sin(0.35), math.cos(0.35)))
    trinary = grid.to_msg_fields(trinary=True)["data"].tolist()
    assert trinary == [-1, 0, 100, -1, -1, 100]
    again = OccupancyGrid.from_msg(fake_msg(list(fields["data"]), 3, 2, 0.7))
    assert np.array_equal(again.occupied(), grid.occupied())
    assert np.array_equal(again.free(), grid.free())


def test_bad_msgs() -> None:
    with pytest.raises(ValueError, match="expected width\\*height = 6"):
        OccupancyGrid.from_msg(fake_msg([0] * 5, 3, 2, 0.0))
    with pytest.raises(ValueError, match=r"-1 \(unknown\) or 0\.\.100"):
        OccupancyGrid.from_msg(fake_msg([0, 0, 0, 0, 0, 101], 3, 2, 0.0))
    with pytest.raises(TypeError, match="nav_msgs/OccupancyGrid"):
        OccupancyGrid.from_msg(SimpleNamespace(data=[0]))


# ------------------------------------------------------------------- polygons
def brute_force_raster(geoms: list[shapely.Geometry], x0: float, y0: float, shape: tuple[int, int],
                       res: float) -> np.ndarray:
    out = np.zeros(shape, dtype=bool)
    for r in range(shape[0]):
        for c in range(shape[1]):
            cell = box(x0 + c * res, y0 + r * res, x0 + (c + 1) * res, y0 + (r + 1) * res)
            out[r, c] = any(g.intersects(cell) for g in geoms)
    return out


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_from_polygons_matches_brute_force(seed: int) -> None:
    rng = np.random.default_rng(seed)
    geoms: list[shapely.Geometry] = []
    for _ in range(3):
        cx, cy = rng.uniform(-1, 4, 2)
        pts = rng.uniform(-0.8, 0.8, size=(5, 2)) + np.array([cx, cy])
        geoms.append(Polygon(pts).convex_hull)
    geoms.append(Point(rng.uniform(0, 3, 2)).buffer(0.2))
    grid = OccupancyGrid.from_polygons(geoms, (-0.5, -0.3, 3.5, 2.7), 0.25)
    assert grid.shape == (12, 16)
    expected = brute_force_raster(geoms, -0.5, -0.3, grid.shape, 0.25)
    assert np.array_equal(grid.occupied(), expected)
    assert np.array_equal(grid.free(), ~expected)


def test_from_polygons_is_conservative() -> None:
    # A wall exactly on a cell boundary marks the cells on both sides.
    grid = OccupancyGrid.from_polygons(box(1.0, 0.0, 1.0, 1.0).buffer(1e-9), (0, 0, 2, 1), 0.5)
    assert grid.occupied().tolist() == [[False, True, True, False]] * 2
    # A sliver thinner than a cell still blocks it.
    thin = OccupancyGrid.from_polygons([box(0.6, 0.1, 0.61, 0.2)], (0, 0, 2, 1), 0.5)
    assert thin.occupied().sum() == 1 and thin.occupied()[0, 1]


def test_from_polygons_validation() -> None:
    with pytest.raises(TypeError, match=r"geometries\[1\] must be a shapely geometry"):
        OccupancyGrid.from_polygons([box(0, 0, 1, 1), "box"], (0, 0, 1, 1), 0.1)
    with pytest.raises(ValueError, match="max > min"):
        OccupancyGrid.from_polygons([], (0, 0, 0, 1), 0.1)
    with pytest.raises(ValueError, match="bounds must have length 4"):
        OccupancyGrid.from_polygons([], (0, 0, 1), 0.1)


# ------------------------------------------------------------------ inflation
@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 0.6))
def test_inflate_matches_brute_force(seed: int, radius: float) -> None:
    rng = np.random.default_rng(seed)
    occ = rng.random((15, 18)) < 0.05
    grid = OccupancyGrid.from_occupancy(occ, 0.1)
    mask = grid.inflate(radius)
    obstacles = np.argwhere(occ)
    cells = np.argwhere(np.ones_like(occ))
    if len(obstacles):
        d = np.hypot(*(cells[:, None, :] - obstacles[None, :, :]).transpose(2, 0, 1)).min(axis=1)
        expected = (d * 0.1 <= radius + 1e-9).reshape(occ.shape)
    else:
        expected = np.zeros_like(occ)
    assert np.array_equal(mask, expected)


def test_inflate_exact_multiple_of_resolution() -> None:
    occ = np.zeros((9, 9), dtype=bool)
    occ[4, 4] = True
    mask = OccupancyGrid.from_occupancy(occ, 0.1).inflate(0.3)
    assert mask[4, 1] and mask[4, 7] and not mask[4, 0]
    assert mask.sum() == 29  # lattice points with dx² + dy² <= 9
    with pytest.raises(ValueError, match="radius_m must be >= 0"):
        OccupancyGrid.from_occupancy(occ, 0.1).inflate(-0.1)


def test_costmap_follows_nav2_inflation_layer() -> None:
    occ = np.zeros((1, 12), dtype=bool)
    occ[0, 0] = True
    unknown = np.zeros_like(occ)
    unknown[0, 1] = unknown[0, 4] = True
    grid = OccupancyGrid.from_occupancy(occ, 0.05, unknown=unknown)
    cost = grid.costmap(inscribed_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0)
    expected = [254, 253, 253]  # obstacle, unknown inside inscribed radius, inscribed
    # Beyond the inscribed radius: int(252 * exp(-5 (d - 0.1))) up to ceil(0.3/0.05) cells.
    expected += [int(252 * math.exp(-5.0 * (k * 0.05 - 0.1))) for k in range(3, 7)]
    expected += [0] * 5
    expected[4] = 255  # unknown keeps 255 when its inflated cost is < 253
    assert cost[0].tolist() == expected
    assert expected[3] == 196 and expected[6] == 92
    with_unknown = grid.costmap(0.1, 0.3, 5.0, inflate_unknown=True)
    assert with_unknown[0, 4] == int(252 * math.exp(-5.0 * 0.1))
    with pytest.raises(ValueError, match=r"inflation_radius \(0\.1\) must be >= inscribed_radius"):
        grid.costmap(0.3, 0.1)


def test_traversal_costs_for_planners() -> None:
    occ = np.zeros((1, 12), dtype=bool)
    occ[0, 0] = True
    unknown = np.zeros_like(occ)
    unknown[0, 11] = True
    grid = OccupancyGrid.from_occupancy(occ, 0.05, unknown=unknown)
    costs = grid.traversal_costs(0.1, 0.3, 5.0)
    nav2 = grid.costmap(0.1, 0.3, 5.0)
    assert np.all(np.isinf(costs[0, :3]))
    assert costs[0, 3] == pytest.approx(1 + 4 * 196 / 252)
    assert costs[0, 8] == 1.0 and np.isinf(costs[0, 11])
    assert np.all(np.diff(costs[0, 3:8]) <= 0)
    band = nav2 < 253
    assert np.allclose(costs[band], 1 + 4 * nav2[band].astype(float) / 252)
    crossing = grid.traversal_costs(0.1, 0.3, 5.0, unknown_cost=3.0)
    assert crossing[0, 11] == 3.0
    validate_costs(costs)
    validate_costs(crossing)
    point_robot = grid.traversal_costs()
    assert np.isinf(point_robot[0, 0]) and point_robot[0, 1] == 1.0
    with pytest.raises(ValueError, match="unknown_cost must be >= 1"):
        grid.traversal_costs(unknown_cost=0.5)
