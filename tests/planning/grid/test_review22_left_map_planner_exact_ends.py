"""``MapPlanner.plan`` begins and ends at the points given, as ``plan_world`` (session 26).

Before, its world paths ran from the start cell's centre to the goal cell's
centre, up to half a cell diagonal (3.5 cm on a 5 cm map) from the robot and
the goal; ``FieldDStar.plan_world`` began and ended at the points given. Now
both do: each given point is linked by a straight segment inside its own
passable cell to that cell's centre, where the planned path begins or ends.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner, plan_path

Name = Literal["astar", "field_dstar"]
PLANNERS: tuple[Name, ...] = ("astar", "field_dstar")


def _wall_grid(origin: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> OccupancyGrid:
    """2 x 1 m at 0.1 m: a wall at x = 1 m from y = 0 to 0.6 m."""
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=origin)


def _cell_of(grid: OccupancyGrid, point: np.ndarray) -> tuple[int, int]:
    row, col = (int(v) for v in np.asarray(grid.world_to_cell(point)).reshape(2))
    return row, col


def _in_closed_square(grid: OccupancyGrid, points: np.ndarray, cell: tuple[int, int]) -> bool:
    """Whether every point lies in cell's closed square (continuous grid coordinates)."""
    q = np.asarray(grid.world_to_cell(points, continuous=True)).reshape(-1, 2)
    return bool(np.all(np.abs(q - np.array(cell)) <= 0.5 + 1e-9))


@st.composite
def scenes(draw: st.DrawFn) -> tuple[MapPlanner, np.ndarray, np.ndarray]:
    """A random map (rotated or not), a planner, and start and goal points in passable cells."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    rows, cols = draw(st.integers(4, 14)), draw(st.integers(4, 14))
    occupied = rng.random((rows, cols)) < draw(st.sampled_from([0.0, 0.1, 0.25]))
    resolution = draw(st.sampled_from([0.05, 0.1, 0.5]))
    origin = (draw(st.sampled_from([0.0, -3.3, 1234.5])), draw(st.sampled_from([0.0, 7.1])),
              draw(st.sampled_from([0.0, 0.6, -2.5])))  # fmt: skip
    grid = OccupancyGrid.from_occupancy(occupied, resolution=resolution, origin=origin)
    planner = MapPlanner(
        grid,
        robot_radius=draw(st.sampled_from([0.0, resolution])),
        inflation_radius=draw(st.sampled_from([None, 3 * resolution])),
        planner=draw(st.sampled_from(PLANNERS)),
    )
    free = np.argwhere(np.isfinite(planner.costs))
    if len(free) == 0:
        free = np.array([[0, 0]])

    def point() -> np.ndarray:
        row, col = free[draw(st.integers(0, len(free) - 1))]
        # Anywhere in the cell's half-open square: edges, corners and the centre included.
        offset = [draw(st.sampled_from([-0.5, -0.25, 0.0, 0.3, 0.499])) for _ in range(2)]
        return np.asarray(grid.cell_to_world([row + offset[0], col + offset[1]]), dtype=float)

    return planner, point(), point()


@settings(max_examples=80, deadline=None)
@given(scenes())
def test_paths_begin_and_end_at_the_points_given(
    scene: tuple[MapPlanner, np.ndarray, np.ndarray],
) -> None:
    planner, start, goal = scene
    grid = planner.grid
    s_cell, g_cell = _cell_of(grid, start), _cell_of(grid, goal)
    if not (planner.grid.contains(start) and planner.grid.contains(goal)):
        return  # a point on the far edge after the rotation's rounding: refused as before
    if not (np.isfinite(planner.costs[s_cell]) and np.isfinite(planner.costs[g_cell])):
        return
    given_start, given_goal = start.copy(), goal.copy()
    try:
        path = planner.plan(start, goal)
    except Exception as exc:  # only "no path" may stop it
        assert type(exc).__name__ == "NoPathError"
        return
    np.testing.assert_array_equal(start, given_start)  # inputs untouched
    np.testing.assert_array_equal(goal, given_goal)
    assert path.frame == "world"
    np.testing.assert_array_equal(path.points[0], start)
    np.testing.assert_array_equal(path.points[-1], goal)
    assert path.length == pytest.approx(
        float(np.hypot(*np.diff(path.points, axis=0).T).sum()), rel=1e-12, abs=1e-12
    )
    if s_cell == g_cell:
        # One cell: the straight segment, priced at the cell's cost.
        want = [start] if np.array_equal(start, goal) else [start, goal]
        np.testing.assert_array_equal(path.points, want)
        step = float(np.hypot(*(goal - start)))
        assert path.cost == pytest.approx(step * planner.costs[s_cell], rel=1e-12, abs=0.0)
        return
    # Between the links: the path planned between the two cells' centres.
    centres = np.asarray(grid.cell_to_world([s_cell, g_cell]), dtype=float)
    between = planner.plan(centres[0], centres[1])
    np.testing.assert_allclose(between.points[[0, -1]], centres, rtol=0.0, atol=1e-9)
    inner = path.points.copy()
    tiny = 1e-6 * grid.resolution
    links = 0.0
    for end, cell, given_point in ((0, s_cell, start), (-1, g_cell, goal)):
        step = float(np.hypot(*(given_point - centres[0 if end == 0 else 1])))
        if step > tiny:
            # A link: the given point, then its cell's centre, inside that cell.
            after = 1 if end == 0 else -2
            np.testing.assert_allclose(
                path.points[after], centres[0 if end == 0 else 1], rtol=0.0, atol=1e-9
            )
            assert _in_closed_square(grid, path.points[[end, after]], cell)
            links += step * float(planner.costs[cell])
            inner = inner[1:] if end == 0 else inner[:-1]
    assert inner.shape == between.points.shape
    np.testing.assert_allclose(inner, between.points, rtol=0.0, atol=1e-6 * grid.resolution)
    assert path.expanded == between.expanded
    assert path.cost == pytest.approx(between.cost + links, rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("name", PLANNERS)
def test_off_centre_points_are_linked_to_their_centres(name: Name) -> None:
    planner = MapPlanner(_wall_grid(), robot_radius=0.2, planner=name)
    path = planner.plan((0.52, 0.21), (1.58, 0.29))
    np.testing.assert_allclose(
        path.points[[0, 1, -2, -1]], [[0.52, 0.21], [0.55, 0.25], [1.55, 0.25], [1.58, 0.29]],
        rtol=0.0, atol=1e-12,
    )  # fmt: skip
    centre = planner.plan((0.55, 0.25), (1.55, 0.25))
    links = math.hypot(0.03, 0.04) + math.hypot(0.03, 0.04)  # cost-1 cells
    assert path.cost == pytest.approx(centre.cost + links, rel=1e-12)
    assert path.length == pytest.approx(centre.length + links, rel=1e-12)
    assert len(path.points) == len(centre.points) + 2


@pytest.mark.parametrize("name", PLANNERS)
def test_a_point_a_rounding_step_from_its_centre_replaces_it(name: Name) -> None:
    planner = MapPlanner(_wall_grid(), robot_radius=0.2, planner=name)
    centre = planner.plan((0.55, 0.25), (1.55, 0.25))
    start = (math.nextafter(0.55, 1.0), 0.25)
    goal = (1.55, math.nextafter(0.25, 0.0))
    path = planner.plan(start, goal)
    assert len(path.points) == len(centre.points)  # no link of 1e-16 m
    np.testing.assert_array_equal(path.points[[0, -1]], [start, goal])
    np.testing.assert_array_equal(path.points[1:-1], centre.points[1:-1])
    assert path.cost == pytest.approx(centre.cost, rel=1e-12)


@pytest.mark.parametrize("origin", [(0.0, 0.0, 0.0), (-3.0, 2.0, 0.7), (500130.0, 4500681.0, -2.1)])
def test_world_ends_match_field_dstar_plan_world(origin: tuple[float, float, float]) -> None:
    """One vocabulary: both world planners begin and end at the points given."""
    grid = _wall_grid(origin)
    start = np.asarray(grid.cell_to_world([2.3, 4.4]), dtype=float)  # off-centre
    goal = np.asarray(grid.cell_to_world([2.0, 15.5]), dtype=float)  # on a cell edge
    map_path = MapPlanner(grid, robot_radius=0.2, planner="field_dstar").plan(start, goal)
    costs = grid.traversal_costs(robot_radius=0.2)
    field = FieldDStar(costs, resolution=0.1, origin=origin, obstacles=grid.occupied())
    world_path = field.plan_world(start, goal)
    np.testing.assert_array_equal(map_path.points[[0, -1]], world_path.points[[0, -1]])
    np.testing.assert_array_equal(map_path.points[[0, -1]], [start, goal])


@pytest.mark.parametrize("name", PLANNERS)
def test_an_escaped_start_still_starts_at_the_start_and_ends_at_the_goal(name: Name) -> None:
    planner = MapPlanner(_wall_grid(), robot_radius=0.2, planner=name)
    path = planner.plan((0.85, 0.23), (1.53, 0.27), start_tolerance=0.2)
    np.testing.assert_allclose(path.points[:2], [[0.85, 0.23], [0.75, 0.25]], atol=1e-12)
    np.testing.assert_array_equal(path.points[-1], [1.53, 0.27])
    np.testing.assert_allclose(path.points[-2], [1.55, 0.25], atol=1e-12)
    # The goal's link adds to the escaped path to the goal cell's centre.
    to_centre = planner.plan((0.85, 0.23), (1.55, 0.25), start_tolerance=0.2)
    np.testing.assert_array_equal(path.points[:-1], to_centre.points)
    link = math.hypot(0.02, 0.02) * float(planner.costs[2, 15])
    assert path.cost == pytest.approx(to_centre.cost + link, rel=1e-12)
    assert path.length == pytest.approx(to_centre.length + math.hypot(0.02, 0.02), rel=1e-12)


def test_a_pose_start_and_plan_path_agree() -> None:
    grid = _wall_grid()
    pose = Pose2D(0.52, 0.21, 1.0)
    kept = MapPlanner(grid, robot_radius=0.2).plan(pose, (1.58, 0.29))
    one_shot = plan_path(grid, (0.52, 0.21), Pose2D(1.58, 0.29, -3.0), robot_radius=0.2)
    np.testing.assert_array_equal(kept.points, one_shot.points)
    assert (kept.cost, kept.length) == (one_shot.cost, one_shot.length)
    np.testing.assert_array_equal(kept.points[[0, -1]], [[0.52, 0.21], [1.58, 0.29]])


@pytest.mark.parametrize("name", PLANNERS)
def test_one_cell_paths(name: Name) -> None:
    planner = MapPlanner(_wall_grid(), unknown_cost=1.0, planner=name)
    costs = np.array(planner.costs)
    two = planner.plan((0.51, 0.22), (0.58, 0.29))
    np.testing.assert_array_equal(two.points, [[0.51, 0.22], [0.58, 0.29]])
    assert two.cost == pytest.approx(math.hypot(0.07, 0.07) * costs[2, 5], rel=1e-12)
    one = planner.plan((0.51, 0.22), (0.51, 0.22))
    assert one.points.tolist() == [[0.51, 0.22]] and one.cost == 0.0 and one.length == 0.0


def test_links_in_costly_cells_pay_their_cost() -> None:
    # A start in the inflation's decay band (cost above 1): its link costs more than its length.
    grid = _wall_grid()
    planner = MapPlanner(grid, robot_radius=0.1, inflation_radius=0.5)
    start, goal = (0.62, 0.71), (1.38, 0.73)
    s_cell = _cell_of(grid, np.array(start))
    assert planner.costs[s_cell] > 1.0
    path = planner.plan(start, goal)
    centres = np.asarray(grid.cell_to_world([s_cell, _cell_of(grid, np.array(goal))]))
    between = planner.plan(centres[0], centres[1])
    g_cell = _cell_of(grid, np.array(goal))
    links = (
        math.dist(start, centres[0]) * planner.costs[s_cell]
        + math.dist(goal, centres[1]) * planner.costs[g_cell]
    )
    assert path.cost == pytest.approx(between.cost + links, rel=1e-12)
    assert path.cost - between.cost > path.length - between.length  # costlier than long
