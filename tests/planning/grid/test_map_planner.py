"""MapPlanner and plan_path: world-coordinate planning on occupancy grids, synthetic, real maps."""

from __future__ import annotations

import itertools
import math
from functools import partial
from pathlib import Path

import numpy as np
import pytest
from grid_oracle import assert_valid_path
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from navkit import NoPathError
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import (
    AStarPlanner,
    CellPlanner,
    FieldDStar,
    MapPlanner,
    Path2D,
    astar,
    distance_field,
    plan_path,
)


def doorway_grid(door_cells: int, origin: Pose2D | None = None) -> OccupancyGrid:
    """4 m x 3 m room at 0.05 m split by a wall at x = 2 m with a centred door."""
    occupied = np.zeros((60, 80), dtype=bool)
    occupied[[0, -1], :] = True
    occupied[:, [0, -1]] = True
    occupied[:, 40] = True
    lo = 30 - door_cells // 2
    occupied[lo : lo + door_cells, 40] = False
    return OccupancyGrid.from_occupancy(
        occupied, resolution=0.05, origin=origin or Pose2D(0.0, 0.0, 0.0)
    )


def clearance(
    grid: OccupancyGrid, points: NDArray[np.float64], cells: NDArray[np.bool_] | None = None
) -> NDArray[np.float64]:
    """Distance from each point to the nearest centre of a ``cells`` cell (default: occupied), m."""
    mask = grid.occupied() if cells is None else cells
    centres = grid.cell_to_world(np.argwhere(mask))
    dist, _ = cKDTree(centres).query(points)
    return np.asarray(dist)


def test_path_matches_astar_on_the_inflated_costs_in_a_rotated_frame() -> None:
    origin = Pose2D(3.0, -2.0, 0.6)
    grid = doorway_grid(12, origin)
    start = grid.cell_to_world([10, 10]) + 0.01
    goal = grid.cell_to_world([50, 70]) - 0.01
    path = plan_path(grid, start, goal, robot_radius=0.15)
    assert isinstance(path, Path2D)
    assert path.frame == "world"
    with pytest.raises(ValueError, match="world"):
        _ = path.cells
    costs = grid.traversal_costs(robot_radius=0.15)
    reference = astar(costs, (10, 10), (50, 70))
    # The given ends exactly, linked to A*'s path between their cells' centres.
    np.testing.assert_array_equal(path.points[[0, -1]], [start, goal])
    np.testing.assert_allclose(path.points[1:-1], grid.cell_to_world(reference.points), atol=1e-12)
    cells = grid.world_to_cell(path.points)
    np.testing.assert_array_equal(cells[1:-1], reference.cells)
    np.testing.assert_array_equal(cells[[0, -1]], [(10, 10), (50, 70)])
    links = [float(np.hypot(*(path.points[i] - path.points[j]))) for i, j in ((0, 1), (-1, -2))]
    assert links == pytest.approx([0.01 * np.sqrt(2)] * 2, rel=1e-6)
    # The links run in cells of cost 1 (the start's and the goal's): cost and length grow by them.
    assert path.cost == pytest.approx(reference.cost * 0.05 + sum(links), rel=1e-12)
    assert path.length == pytest.approx(reference.length * 0.05 + sum(links), rel=1e-9)
    assert path.expanded == reference.expanded
    assert_valid_path(costs, cells[1:-1], (10, 10), (50, 70))
    # The path crosses the wall through the door.
    assert set(cells[:, 1].tolist()) >= {40}
    assert np.all(clearance(grid, path.points) > 0.15)
    with pytest.raises(ValueError):
        path.points[0, 0] = 0.0


def test_robot_radius_closes_a_narrow_door() -> None:
    grid = doorway_grid(8)  # 0.4 m door
    start, goal = (0.5, 1.5), (3.5, 1.5)
    through = plan_path(grid, start, goal, robot_radius=0.1)
    # Cell corners: linked to their cells' centres, half a diagonal each.
    assert through.length == pytest.approx(3.0 + 0.05 * np.sqrt(2), abs=0.06)
    with pytest.raises(NoPathError) as info:
        plan_path(grid, start, goal, robot_radius=0.25)
    assert info.value.expanded > 100


def test_inflation_radius_keeps_the_path_away_from_walls() -> None:
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[18:22, 20:40] = True  # a block between start and goal
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    start, goal = (0.55, 2.05), (5.45, 2.05)
    tight = plan_path(grid, start, goal, robot_radius=0.2)
    wide = plan_path(grid, start, goal, robot_radius=0.2, inflation_radius=1.0)
    assert wide.length > tight.length
    assert clearance(grid, wide.points).min() > clearance(grid, tight.points).min()
    # Costs above 1 near obstacles make the cost exceed the length.
    assert wide.cost > wide.length
    assert tight.cost == pytest.approx(tight.length, rel=1e-12)


def test_options_reach_the_planner_through_partial() -> None:
    grid = doorway_grid(12)
    start, goal = (0.3, 0.3), (3.7, 2.7)
    optimal = plan_path(grid, start, goal, planner=partial(astar, heuristic_weight=0.0))
    astar_path = plan_path(grid, start, goal)
    assert optimal.cost == pytest.approx(astar_path.cost, rel=1e-12)
    assert optimal.expanded > astar_path.expanded
    cutting = plan_path(grid, start, goal, planner=partial(astar, corner_cutting=True))
    assert cutting.cost <= astar_path.cost


def test_cell_planner_callables_are_dispatched() -> None:
    calls: list[tuple[int, tuple[int, int], tuple[int, int]]] = []

    def straight(
        costs: NDArray[np.float64], start_cell: tuple[int, int], goal_cell: tuple[int, int]
    ) -> Path2D:
        calls.append((id(costs), start_cell, goal_cell))
        assert costs.dtype == np.float64 and not costs.flags.writeable
        cells = np.array([start_cell, goal_cell], dtype=np.float64)
        length = float(np.hypot(*(cells[1] - cells[0])))
        return Path2D(cells, "grid", cost=length, length=length, expanded=0)

    planner: CellPlanner = straight
    grid = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.5)
    path = plan_path(grid, (0.25, 0.25), (4.25, 2.25), planner=planner)
    np.testing.assert_allclose(path.points, [[0.25, 0.25], [4.25, 2.25]])
    assert path.frame == "world"
    assert path.length == pytest.approx(math.hypot(4.0, 2.0))
    assert path.cost == pytest.approx(path.length)
    assert calls[-1][1:] == ((0, 0), (4, 8))
    # A MapPlanner hands the same costs array to every query.
    map_planner = MapPlanner(grid, planner=straight)
    map_planner.plan((0.25, 0.25), (1.0, 1.0))
    map_planner.plan((1.0, 1.0), (0.25, 0.25))
    assert calls[-1][0] == calls[-2][0] == id(map_planner.costs)

    def wrong(costs: NDArray[np.float64], s: tuple[int, int], g: tuple[int, int]) -> object:
        return np.zeros((2, 2))

    with pytest.raises(TypeError, match="Path2D"):
        plan_path(grid, (0.25, 0.25), (4.25, 2.25), planner=wrong)  # type: ignore[arg-type]

    def in_world(costs: NDArray[np.float64], s: tuple[int, int], g: tuple[int, int]) -> Path2D:
        return Path2D([s, g], "world", cost=0.0, length=0.0, expanded=0)

    with pytest.raises(TypeError, match="grid"):
        plan_path(grid, (0.25, 0.25), (4.25, 2.25), planner=in_world)


def test_bad_arguments() -> None:
    grid = doorway_grid(12)
    with pytest.raises(ValueError, match=r"start \(-1.0, 1.0\) is outside"):
        plan_path(grid, (-1.0, 1.0), (3.0, 1.0))
    obstacle = r"goal \(2.02, 2.0\) \(cell \(40, 40\)\) is in an obstacle"
    with pytest.raises(ValueError, match=obstacle):
        plan_path(grid, (1.0, 1.0), (2.02, 2.0))
    near = r"goal .* is within robot_radius \(0.3 m\) of an obstacle"
    with pytest.raises(ValueError, match=near):
        plan_path(grid, (1.0, 1.0), (2.2, 2.0), robot_radius=0.3)
    with pytest.raises(ValueError, match="planner"):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), planner="rrt")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="planner"):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), planner=3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="robot_radius"):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), robot_radius=-0.1)
    with pytest.raises(ValueError, match="start"):
        plan_path(grid, (1.0, 1.0, 0.0, 1.0), (3.0, 1.0))
    with pytest.raises(ValueError, match="start"):
        plan_path(grid, (1.0, math.nan), (3.0, 1.0))
    with pytest.raises(TypeError, match="goal"):
        plan_path(grid, (1.0, 1.0), "here")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="OccupancyGrid"):
        plan_path(np.zeros((5, 5)), (1.0, 1.0), (3.0, 1.0))  # type: ignore[arg-type]


def test_map_planner_builds_the_costmap_once(monkeypatch: pytest.MonkeyPatch) -> None:
    grid = doorway_grid(12, Pose2D(0.5, -0.3, 0.2))
    planner = MapPlanner(grid, robot_radius=0.1, inflation_radius=0.3)
    costs = planner.costs
    np.testing.assert_array_equal(
        costs, grid.traversal_costs(robot_radius=0.1, inflation_radius=0.3)
    )
    assert not costs.flags.writeable
    queries = [
        (grid.cell_to_world([10, 10]), grid.cell_to_world([50, 70])),
        (grid.cell_to_world([5, 60]), grid.cell_to_world([40, 12])),
        (grid.cell_to_world([30, 30]), grid.cell_to_world([30, 50])),
    ]
    expected = [
        plan_path(grid, s, g, robot_radius=0.1, inflation_radius=0.3) for s, g in queries
    ]

    # From here on, building or validating costs again would fail.
    def forbidden(*args: object, **kwargs: object) -> None:
        raise AssertionError("the costmap was rebuilt or revalidated")

    monkeypatch.setattr(OccupancyGrid, "traversal_costs", forbidden)
    monkeypatch.setattr("navkit.planning.grid._astar.checked_cost_range", forbidden)
    monkeypatch.setattr("navkit.planning.grid._map_planner.checked_costs", forbidden)
    for _ in range(2):
        for (s, g), want in zip(queries, expected, strict=True):
            got = planner.plan(s, g)
            np.testing.assert_array_equal(got.points, want.points)
            assert (got.cost, got.length, got.expanded) == (want.cost, want.length, want.expanded)
            assert planner.costs is costs


def test_map_planner_matches_astar_on_its_costs() -> None:
    grid = doorway_grid(12)
    planner = MapPlanner(grid, robot_radius=0.15)
    reference = AStarPlanner(planner.costs)
    start = grid.cell_to_world([10, 10])
    goal = grid.cell_to_world([50, 70])
    path = planner.plan(start, goal)
    cells = reference.plan((10, 10), (50, 70))
    np.testing.assert_allclose(path.points, grid.cell_to_world(cells.points), atol=1e-12)
    assert path.cost == pytest.approx(cells.cost * grid.resolution, rel=1e-12)
    assert path.length == pytest.approx(cells.length * grid.resolution, rel=1e-9)


def test_start_and_goal_accept_poses_and_three_sequences() -> None:
    grid = doorway_grid(12, Pose2D(1.0, 2.0, -0.4))
    planner = MapPlanner(grid, robot_radius=0.1)
    start_xy = grid.cell_to_world([12, 8])
    goal_xy = grid.cell_to_world([45, 66])
    by_points = planner.plan(start_xy, goal_xy)
    for start, goal in [
        (Pose2D(start_xy[0], start_xy[1], 1.0), goal_xy),
        ((start_xy[0], start_xy[1], -2.0), Pose2D(goal_xy[0], goal_xy[1], 0.0)),
        (np.array([*start_xy, 0.5]), [goal_xy[0], goal_xy[1], 3.0]),
        (list(start_xy), tuple(goal_xy)),
    ]:
        path = planner.plan(start, goal)
        np.testing.assert_array_equal(path.points, by_points.points)
    one_shot = plan_path(grid, Pose2D(*start_xy, 0.3), goal_xy, robot_radius=0.1)
    np.testing.assert_array_equal(one_shot.points, by_points.points)


def test_map_planner_with_field_dstar_keeps_one_prepared_planner() -> None:
    grid = doorway_grid(12)
    planner = MapPlanner(grid, robot_radius=0.1, planner="field_dstar")
    queries = [((0.3, 0.3), (3.7, 2.7)), ((3.5, 0.4), (0.6, 2.5)), ((0.3, 0.3), (1.5, 2.6))]
    reference = FieldDStar(planner.costs)
    for _ in range(2):
        for start, goal in queries:
            path = planner.plan(start, goal)
            assert path.frame == "world"
            cells = reference.plan_cells(
                tuple(grid.world_to_cell(start).tolist()), tuple(grid.world_to_cell(goal).tolist())
            )
            np.testing.assert_array_equal(path.points[[0, -1]], [start, goal])
            np.testing.assert_allclose(
                path.points[1:-1], grid.cell_to_world(cells.points), atol=1e-12
            )
            links = np.hypot(*(path.points[[0, -1]] - path.points[[1, -2]]).T).sum()
            assert path.cost == pytest.approx(cells.cost * grid.resolution + links, rel=1e-12)
            assert path.expanded == cells.expanded
            one_shot = plan_path(grid, start, goal, robot_radius=0.1, planner="field_dstar")
            np.testing.assert_array_equal(one_shot.points, path.points)


def test_unknown_space_is_named_in_the_error() -> None:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[:, 10] = True
    unknown = np.zeros((20, 20), dtype=bool)
    unknown[15:, 15:] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    planner = MapPlanner(grid)
    with pytest.raises(ValueError, match=r"goal .* is in unknown space \(unknown_cost is inf\)"):
        planner.plan((0.25, 0.25), (1.75, 1.75))
    with pytest.raises(ValueError, match=r"start .* is in an obstacle"):
        planner.plan((1.05, 0.25), (1.75, 0.25))
    crossing = MapPlanner(grid, unknown_cost=5.0)
    path = crossing.plan((1.95, 1.25), (1.75, 1.75))
    assert path.cost > path.length


def test_unknown_space_keeps_robot_radius_clear_by_default() -> None:
    # Issue 12: robot_radius kept paths clear of occupied cells only.
    unknown = np.zeros((30, 30), dtype=bool)
    unknown[:, 15] = True  # an unknown wall with a gap
    unknown[12:18, 15] = False
    grid = OccupancyGrid.from_occupancy(np.zeros((30, 30), dtype=bool), resolution=0.1,
                                        unknown=unknown)
    start, goal = (0.45, 1.25), (2.95, 1.25)  # level with the gap's edge row
    for planner in ("astar", "field_dstar"):
        path = plan_path(grid, start, goal, robot_radius=0.25, planner=planner)
        assert clearance(grid, dense(path.points), unknown).min() >= 0.25 - 0.05
        # Without the inflation the path runs straight along the gap's edge.
        old = plan_path(grid, start, goal, robot_radius=0.25, planner=planner,
                        inflate_unknown=False)
        assert clearance(grid, dense(old.points), unknown).min() <= 0.1 + 1e-9
    # A 0.35 m robot does not fit through the gap any more; unknown_cost=inf and
    # inflate_unknown=False keeps the former behaviour.
    with pytest.raises(NoPathError):
        plan_path(grid, start, goal, robot_radius=0.35)
    plan_path(grid, start, goal, robot_radius=0.35, inflate_unknown=False)
    # Crossable unknown space (a finite cost) is not inflated, and cannot be.
    assert not MapPlanner(grid, robot_radius=0.25, unknown_cost=5.0).inflate_unknown
    with pytest.raises(ValueError, match="unknown_cost must be inf"):
        MapPlanner(grid, robot_radius=0.25, unknown_cost=5.0, inflate_unknown=True)
    explicit = MapPlanner(grid, robot_radius=0.25, inflate_unknown=True)
    assert explicit.inflate_unknown
    assert np.isinf(explicit.costs[5, 13]) and np.isfinite(explicit.costs[5, 12])
    with pytest.raises(ValueError, match=r"start .* within robot_radius \(0.25 m\) of unknown"):
        MapPlanner(grid, robot_radius=0.25).plan((1.35, 0.45), goal)



def test_start_and_goal_errors_explain_the_costs_after_the_map_changed() -> None:
    # The costs are a snapshot of the map, but the reason for a blocked cell
    # was read from the map as it is now: a cell that became occupied was
    # reported as "in an obstacle" although the planner blocks it as unknown,
    # and an obstacle that was cleared as being "within robot_radius of
    # unknown space" on a map without any unknown cell.
    scan = LaserScan([1.4], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=3.0)
    logodds = np.full((1, 4), -5.0)
    logodds[0, 3] = 0.0  # unknown
    grid = OccupancyGrid(logodds, resolution=0.5)
    planner = MapPlanner(grid)
    for _ in range(5):
        grid.integrate_scan(scan, (0.25, 0.25, 0.0))
    assert grid.occupied()[0, 3]  # the map changed, the planner's costs did not
    with pytest.raises(ValueError, match=r"goal .* is in unknown space \(unknown_cost is inf\)"):
        planner.plan((0.25, 0.25), (1.75, 0.25))

    occupied = np.zeros((1, 4), dtype=bool)
    occupied[0, 3] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5)
    planner = MapPlanner(grid)
    far = LaserScan([3.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.0)
    for _ in range(25):  # 6.9 down to free at -0.4 a scan (no jump to the clamp)
        grid.integrate_scan(far, (0.25, 0.25, 0.0))
    assert grid.free().all()
    with pytest.raises(ValueError, match=r"goal .* \(cell \(0, 3\)\) is in an obstacle$"):
        planner.plan((0.25, 0.25), (1.75, 0.25))
    assert planner.grid is grid
    assert np.isinf(planner.costs[0, 3])


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"robot_radius": 1e308}, ValueError, "robot_radius"),
        ({"robot_radius": 1e6 * (1 + 1e-15)}, ValueError, "robot_radius"),
        ({"robot_radius": math.inf}, ValueError, "robot_radius"),
        ({"robot_radius": True}, TypeError, "robot_radius"),
        ({"robot_radius": "0.1"}, TypeError, "robot_radius"),
        ({"inflation_radius": 1e308}, ValueError, "inflation_radius"),
        ({"unknown_cost": True}, TypeError, "unknown_cost"),
        ({"unknown_cost": "5"}, TypeError, "unknown_cost"),
        ({"unknown_cost": 0.5}, ValueError, "unknown_cost"),
        ({"unknown_cost": 1e300}, ValueError, "unknown_cost"),
        ({"inflate_unknown": "yes"}, TypeError, "inflate_unknown"),
        ({"inflate_unknown": 1}, TypeError, "inflate_unknown"),
    ],
)
def test_map_planner_option_ranges(kwargs: dict[str, object], error: type, match: str) -> None:
    grid = doorway_grid(12)
    with pytest.raises(error, match=match):
        MapPlanner(grid, **kwargs)  # type: ignore[arg-type]
    with pytest.raises(error, match=match):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), **kwargs)  # type: ignore[arg-type]


def test_map_planner_properties() -> None:
    grid = doorway_grid(12)
    planner = MapPlanner(grid, robot_radius=0.1)
    assert planner.grid is grid
    assert planner.robot_radius == 0.1
    assert planner.planner == "astar"
    assert planner.costs.shape == grid.shape
    assert repr(planner) == "MapPlanner(<60x80 map>, robot_radius=0.1, planner='astar')"
    with pytest.raises(TypeError):
        MapPlanner(grid, 0.1)  # type: ignore[misc]
    with pytest.raises(AttributeError):
        planner.costs = planner.costs  # type: ignore[misc]


def willow_garage(shared_data: Path) -> OccupancyGrid:
    """The Willow Garage office, a real robot-built ROS map (0.1 m cells)."""
    folder = shared_data / "ros-map-server-maps" / "willow_garage_2010"
    return OccupancyGrid.load(folder / "willow-2010-02-18-0.10.yaml")


def test_office_map_route(shared_data: Path) -> None:
    # The robot inflates by 0.3 m. Its walls are mostly unknown cells,
    # which keep the robot 0.3 m away too (inflate_unknown): (281, 236) is the
    # cell of the main corridor network nearest the former start (290, 221),
    # which now lies in a small room sealed off by that clearance.
    grid = willow_garage(shared_data)
    costs = grid.traversal_costs(robot_radius=0.3)
    start_cell = (281, 236)
    field = distance_field(costs, start_cell)
    goal_cell = np.unravel_index(np.argmax(np.where(np.isfinite(field), field, -1.0)), field.shape)
    start = grid.cell_to_world(start_cell)
    goal = grid.cell_to_world(goal_cell)
    path = plan_path(grid, start, goal, robot_radius=0.3)
    # The farthest reachable cell is tens of metres of corridors away.
    assert path.length > 1.2 * np.hypot(*(goal - start))
    assert path.cost == pytest.approx(field[goal_cell] * grid.resolution, rel=1e-9)
    assert np.all(clearance(grid, path.points) > 0.3)
    back = plan_path(grid, goal, start, robot_radius=0.3)
    assert back.cost == pytest.approx(path.cost, rel=1e-9)
    assert np.all(clearance(grid, path.points, grid.unknown()) > 0.3)


def dense(points: NDArray[np.float64], step: float = 0.005) -> NDArray[np.float64]:
    """The polyline ``points`` sampled every ``step`` metres (its vertices included)."""
    out = [points[:1]]
    for a, b in itertools.pairwise(points):
        n = max(1, math.ceil(float(np.hypot(*(b - a))) / step))
        out.append(a + (b - a) * np.linspace(0.0, 1.0, n + 1)[1:, None])
    return np.vstack(out)


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_paths_keep_robot_radius_from_unknown_space_on_the_office_map(
    shared_data: Path, planner: str
) -> None:
    # Issue 12: on the Willow Garage map, whose walls are mostly unknown cells, a
    # 0.2 m robot's A* path passed 0.10 m and Field D*'s 0.05 m from unknown
    # space. With the default inflate_unknown (True, as unknown_cost is inf) both
    # keep robot_radius from unknown cell centres up to half a cell.
    grid = willow_garage(shared_data)
    radius = 0.2
    start_cell = (290, 221)
    field = distance_field(grid.traversal_costs(robot_radius=radius), start_cell)
    goal_cell = np.unravel_index(np.argmax(np.where(np.isfinite(field), field, -1.0)), field.shape)
    start = grid.cell_to_world(start_cell)
    goal = grid.cell_to_world(goal_cell)
    path = plan_path(grid, start, goal, robot_radius=radius, planner=planner)
    assert path.length > 40.0
    points = dense(path.points)
    assert clearance(grid, points, grid.unknown()).min() >= radius - grid.resolution / 2
    assert clearance(grid, points).min() >= radius - grid.resolution / 2
    # The old behaviour, still available: unknown space counts as an obstacle
    # cell only, and the path grazes it.
    old = plan_path(grid, start, goal, robot_radius=radius, planner=planner,
                    inflate_unknown=False)
    assert clearance(grid, dense(old.points), grid.unknown()).min() < 0.11
    assert MapPlanner(grid, robot_radius=radius).inflate_unknown
    assert not MapPlanner(grid, robot_radius=radius, unknown_cost=5.0).inflate_unknown


def test_start_and_goal_errors_name_unknown_space(shared_data: Path) -> None:
    grid = willow_garage(shared_data)
    planner = MapPlanner(grid, robot_radius=0.3)
    inside = grid.cell_to_world((281, 236))
    # (290, 221) is free and 0.3 m from every obstacle, but near unknown space.
    near_unknown = grid.cell_to_world((290, 221))
    assert not grid.unknown()[290, 221] and not grid.occupied()[290, 221]
    with pytest.raises(ValueError, match=r"start .* within robot_radius \(0.3 m\) of unknown"):
        planner.plan(near_unknown, inside)
    with pytest.raises(ValueError, match=r"goal .* within robot_radius \(0.3 m\) of unknown"):
        planner.plan(inside, near_unknown)
    unknown_cell = tuple(np.argwhere(grid.unknown())[0])
    with pytest.raises(ValueError, match="is in unknown space"):
        planner.plan(grid.cell_to_world(unknown_cell), inside)
    occupied_cell = tuple(np.argwhere(grid.occupied())[0])
    with pytest.raises(ValueError, match="is in an obstacle"):
        planner.plan(grid.cell_to_world(occupied_cell), inside)
