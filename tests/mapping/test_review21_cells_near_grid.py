"""``OccupancyGrid.cells_near``: the cells new obstacles at world points block (session 25).

A robot that sees new obstacles as world points (LiDAR hits) tells a planner
which cells they block. ``cells_near(points_xy, robot_radius=r)`` gives the
cells whose centres lie within ``r`` of a point's cell centre, the rule of
``inflate`` (so radius 0 gives each point's own cell, and the hits block what
inflating their cells in the map would). Checked against a brute-force oracle
over every cell, against ``inflate`` and ``traversal_costs`` themselves, with
points far outside the map, huge radii (reach of 1e12 cells, where the float
rule's edge is not the exact circle's), empty and bad input, and fed to
``FieldDStar.update_costs`` and a cost grid.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.jit import jit_disabled
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, astar

_EPS = 1e-9  # the inflation's slack, in cells (navkit.mapping._obstacle_distance.CELL_EPS)


def _oracle(grid: OccupancyGrid, points: np.ndarray, radius: float) -> np.ndarray:
    """Every map cell tested against every point's cell, row-major: the definition itself."""
    rows, cols = grid.shape
    reach = radius / grid.resolution + _EPS
    found = []
    if points.size:
        centres = grid.world_to_cell(np.asarray(points, dtype=float).reshape(-1, 2))
    else:
        centres = np.empty((0, 2), dtype=np.int64)
    for r in range(rows):
        for c in range(cols):
            for pr, pc in centres.tolist():
                dr = float(r - pr)
                dc = float(c - pc)
                if math.sqrt(dr * dr + dc * dc) <= reach:
                    found.append((r, c))
                    break
    return np.array(found, dtype=np.int64).reshape(-1, 2)


def _check_form(cells: np.ndarray, grid: OccupancyGrid) -> None:
    assert cells.dtype == np.int64
    assert cells.ndim == 2 and cells.shape[1] == 2
    if cells.shape[0]:
        rows, cols = grid.shape
        assert cells[:, 0].min() >= 0 and cells[:, 0].max() < rows
        assert cells[:, 1].min() >= 0 and cells[:, 1].max() < cols
        flat = cells[:, 0] * cols + cells[:, 1]
        assert np.all(np.diff(flat) > 0)  # row-major, no duplicates


@st.composite
def _grids(draw: st.DrawFn) -> OccupancyGrid:
    rows = draw(st.integers(1, 12))
    cols = draw(st.integers(1, 12))
    res = draw(st.sampled_from([0.05, 0.1, 0.25, 1.0]))
    yaw = draw(st.sampled_from([0.0, 0.0, 0.7, -2.5]))
    ox = draw(st.floats(-3.0, 3.0))
    oy = draw(st.floats(-3.0, 3.0))
    return OccupancyGrid.from_occupancy(
        np.zeros((rows, cols), dtype=bool), resolution=res, origin=Pose2D(ox, oy, yaw)
    )


def _points(grid: OccupancyGrid, data: st.DataObject, most: int = 6) -> np.ndarray:
    """Points in and around the map (up to a few cells outside), some sharing a cell."""
    rows, cols = grid.shape
    cont = st.tuples(
        st.floats(-4.0, rows + 3.0, allow_nan=False), st.floats(-4.0, cols + 3.0, allow_nan=False)
    )
    picked = data.draw(st.lists(cont, min_size=0, max_size=most))
    if not picked:
        return np.empty((0, 2))
    return grid.cell_to_world(np.array(picked) - 0.5)  # continuous coordinates: centres at ints


@settings(max_examples=150)
@given(st.data())
def test_cells_match_the_brute_force_oracle(data: st.DataObject) -> None:
    grid = data.draw(_grids())
    points = _points(grid, data)
    radius = data.draw(
        st.one_of(
            st.just(0.0),
            st.sampled_from([1.0, 1.5, 2.0, math.sqrt(2.0), math.sqrt(5.0), 3.0]).map(
                lambda m: m * grid.resolution  # exact distances between centres
            ),
            st.floats(0.0, 6.0 * grid.resolution),
        )
    )
    before = points.copy()
    cells = grid.cells_near(points, robot_radius=radius)
    _check_form(cells, grid)
    np.testing.assert_array_equal(cells, _oracle(grid, points, radius))
    np.testing.assert_array_equal(points, before)


@settings(max_examples=80)
@given(st.data())
def test_cells_are_what_inflating_the_points_cells_marks(data: st.DataObject) -> None:
    """Points inside the map: cells_near == inflate() of a map whose occupied cells are theirs."""
    grid = data.draw(_grids())
    rows, cols = grid.shape
    cont = st.tuples(st.floats(-0.49, rows - 0.51), st.floats(-0.49, cols - 0.51))
    picked = data.draw(st.lists(cont, min_size=1, max_size=5))
    points = grid.cell_to_world(np.array(picked))
    radius = data.draw(st.floats(0.0, 4.0 * grid.resolution))
    occupied = np.zeros((rows, cols), dtype=bool)
    centres = grid.world_to_cell(points)
    occupied[centres[:, 0], centres[:, 1]] = True
    marked = OccupancyGrid.from_occupancy(
        occupied, resolution=grid.resolution, origin=grid.origin
    ).inflate(radius)
    np.testing.assert_array_equal(grid.cells_near(points, robot_radius=radius), np.argwhere(marked))


@pytest.mark.parametrize("radius", [0.0, 0.1, 0.2, 0.25, 0.3, 0.45])
def test_hits_block_the_cells_traversal_costs_blocks_around_the_same_obstacles(
    radius: float,
) -> None:
    """Blocking hits with cells_near == putting them in the map and inflating by robot_radius."""
    rng = np.random.default_rng(7)
    grid = OccupancyGrid.from_occupancy(
        np.zeros((30, 40), dtype=bool), resolution=0.1, origin=Pose2D(-1.0, 2.0, 0.3)
    )
    hits = grid.cell_to_world(rng.uniform(-0.5, [29.5, 39.5], size=(25, 2)))
    occupied = np.zeros(grid.shape, dtype=bool)
    centres = grid.world_to_cell(hits)
    occupied[centres[:, 0], centres[:, 1]] = True
    with_hits = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=grid.origin)
    blocked = np.isinf(with_hits.traversal_costs(robot_radius=radius))
    np.testing.assert_array_equal(grid.cells_near(hits, robot_radius=radius), np.argwhere(blocked))


def test_radius_zero_gives_each_points_own_cell_once() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
    points = np.array([[0.55, 0.35], [0.51, 0.39], [1.95, 0.05], [0.0, 0.0], [2.5, 0.5]])
    cells = grid.cells_near(points, robot_radius=0.0)
    assert cells.tolist() == [[0, 0], [0, 19], [3, 5]]  # (2.5, 0.5) is outside: no cell
    # A point on a cell edge is in the cell above it (world_to_cell's floor).
    assert grid.cells_near([0.3, 0.2], robot_radius=0.0).tolist() == [[2, 3]]


def test_one_point_of_shape_2_gives_the_same_cells_as_a_list_of_one() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    one = grid.cells_near((0.45, 0.52), robot_radius=0.15)
    np.testing.assert_array_equal(one, grid.cells_near([[0.45, 0.52]], robot_radius=0.15))
    assert one.shape == (9, 2)


@pytest.mark.parametrize("empty", [[], np.empty((0, 2)), np.empty((0,)), ()])
def test_no_points_no_cells(empty: object) -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    cells = grid.cells_near(empty, robot_radius=0.3)  # type: ignore[arg-type]
    assert cells.shape == (0, 2) and cells.dtype == np.int64


def test_points_far_outside() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=0.5, resolution=0.1, origin=(10.0, -3.0, 0.0))
    far = np.array([[1e300, 0.0], [-1e300, 1e300], [1e9, -1e9], [-5.0, -3.2]])
    assert grid.cells_near(far, robot_radius=1.0).shape == (0, 2)
    # Reaching in from outside: 0.3 m left of the map, radius 0.35 m (3.5 cells).
    cells = grid.cells_near([9.75, -2.75], robot_radius=0.35)
    np.testing.assert_array_equal(cells, _oracle(grid, np.array([[9.75, -2.75]]), 0.35))
    assert cells[:, 1].max() == 0  # only the first column is reached
    # The largest radius from 1e5 m away covers the map; from 1e300 m nothing.
    everything = grid.cells_near([[1e5, 1e5]], robot_radius=1e6)
    np.testing.assert_array_equal(everything, np.argwhere(np.ones(grid.shape, dtype=bool)))
    assert grid.cells_near([[1e300, 1e300]], robot_radius=1e6).shape == (0, 2)


@pytest.mark.parametrize(
    ("dx", "dy"),
    [(-1.0, 0.5), (-0.7071, -0.7071), (0.6, 0.8), (0.0, -1.0), (-0.9999999, 0.0001)],
)
def test_reach_of_1e12_cells_follows_the_float_rule_at_its_edge(dx: float, dy: float) -> None:
    """resolution 1e-6 m and radius 1e6 m: the disc's edge where d**2 is far above 2**53.

    The point sits just about ``robot_radius`` away, so the edge crosses the
    map and its cells are decided by the rounding of ``sqrt(dr**2 + dc**2)``.
    """
    grid = OccupancyGrid.empty(width=8e-6, height=6e-6, resolution=1e-6)
    centre = np.array([4e-6, 3e-6])
    for offset in (-3e-6, -1e-6, 0.0, 1e-6, 2.5e-6):
        point = centre + (1e6 + offset) * np.array([dx, dy]) / math.hypot(dx, dy)
        cells = grid.cells_near(point, robot_radius=1e6)
        np.testing.assert_array_equal(cells, _oracle(grid, point.reshape(1, 2), 1e6))


def test_huge_radius_on_a_large_map_is_bounded_by_the_map() -> None:
    """A radius covering the map gives each cell once (not points × disc cells)."""
    grid = OccupancyGrid.empty(width=60.0, height=40.0, resolution=0.1)  # 400 × 600
    rng = np.random.default_rng(3)
    points = rng.uniform([0.0, 0.0], [60.0, 40.0], size=(200, 2))
    cells = grid.cells_near(points, robot_radius=1e6)
    assert cells.shape == (400 * 600, 2)
    _check_form(cells, grid)


@pytest.mark.parametrize(
    "bad",
    [
        [[0.1, math.nan]],
        [[math.inf, 0.2]],
        [0.1, -math.inf],
        [[0.1, 0.2, 0.3]],
        [[1.0, 2.0], [3.0]],
        [["a", "b"]],
        [[True, False]],
        [[1 + 2j, 0.0]],
    ],
)
def test_bad_points_name_points_xy(bad: object) -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    with pytest.raises((TypeError, ValueError), match="points_xy"):
        grid.cells_near(bad, robot_radius=0.2)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("bad", "error"),
    [
        (-0.1, ValueError),
        (math.nan, ValueError),
        (math.inf, ValueError),
        (1e6 * (1 + 1e-15), ValueError),
        (True, TypeError),
        ("0.2", TypeError),
        (None, TypeError),
    ],
)
def test_bad_radius_names_robot_radius(bad: object, error: type[Exception]) -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    with pytest.raises(error, match="robot_radius"):
        grid.cells_near([0.5, 0.5], robot_radius=bad)  # type: ignore[arg-type]


def test_radius_is_keyword_only() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    with pytest.raises(TypeError):
        grid.cells_near([0.5, 0.5], 0.2)  # type: ignore[call-arg]


def test_inputs_and_grid_are_not_modified() -> None:
    grid = OccupancyGrid.from_probabilities(
        np.random.default_rng(1).uniform(size=(8, 9)), resolution=0.1
    )
    logodds = grid.logodds.copy()
    points = np.array([[0.31, 0.42], [0.05, 0.75], [5.0, 5.0]])
    points.flags.writeable = False  # a read-only array is taken as it is
    kept = points.copy()
    grid.cells_near(points, robot_radius=0.2)
    np.testing.assert_array_equal(points, kept)
    np.testing.assert_array_equal(grid.logodds, logodds)
    strided = np.zeros((3, 4))[:, ::2]
    strided[:] = kept
    np.testing.assert_array_equal(
        grid.cells_near(strided, robot_radius=0.2), grid.cells_near(kept, robot_radius=0.2)
    )


def test_cells_feed_field_dstar_update_costs_and_a_cost_grid() -> None:
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:, 0] = occupied[:, -1] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(1.0, -1.0, 0.0))
    costs = grid.traversal_costs(robot_radius=0.1)
    fd = FieldDStar(costs, resolution=grid.resolution, origin=grid.origin)
    start, goal = (1.25, -0.05), (3.75, -0.05)
    first = fd.plan_world(start, goal)
    hits = np.array([[2.5, -0.05], [2.52, 0.1], [2.48, -0.2], [2.5, 0.6]])  # a wall across
    cells = grid.cells_near(hits, robot_radius=0.1)
    fd.update_costs(cells, np.inf)
    assert np.isinf(fd.costs[cells[:, 0], cells[:, 1]]).all()
    changed = fd.costs != costs
    assert changed.sum() == np.isfinite(costs[cells[:, 0], cells[:, 1]]).sum()
    detour = fd.replan_world()
    assert detour.length > first.length
    # The same cells block A* on a copy of the costs.
    blocked = costs.copy()
    blocked[cells[:, 0], cells[:, 1]] = np.inf
    np.testing.assert_array_equal(blocked, fd.costs)
    s, g = grid.world_to_cell(np.array([start, goal]))
    assert astar(blocked, tuple(s), tuple(g)).cost > astar(costs, tuple(s), tuple(g)).cost


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_the_kernel_compiles_once() -> None:
    """Counting and filling run the same compiled signature, read-only points included."""

    script = (
        "import numpy as np\n"
        "from navkit.mapping import OccupancyGrid\n"
        "g = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)\n"
        "p = np.array([[0.5, 0.5], [0.2, 0.9]]); p.flags.writeable = False\n"
        "g.cells_near(p, robot_radius=0.2); g.cells_near([0.5, 0.5], robot_radius=0.0)\n"
        "g.cells_near([[5.0, 5.0]], robot_radius=1e6)\n"
        "from navkit.mapping._cells_near_kernels import cells_near_kernel as k\n"
        "print(len(k.signatures))\n"
    )
    env = dict(os.environ)  # keeps NUMBA_CACHE_DIR for the child
    done = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
    )
    assert done.stdout.split()[-1] == "1"
