"""plan_path: world-coordinate planning on occupancy grids, synthetic and real maps."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from grid_oracle import assert_valid_path
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from navkit import NoPathError
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.planning import WorldPath, astar, distance_field, plan_path
from navkit.planning.grid import _map_planner as plan_module


def doorway_grid(door_cells: int, origin: Pose2D | None = None) -> OccupancyGrid:
    """4 m x 3 m room at 0.05 m split by a wall at x = 2 m with a centred door."""
    occupied = np.zeros((60, 80), dtype=bool)
    occupied[[0, -1], :] = True
    occupied[:, [0, -1]] = True
    occupied[:, 40] = True
    lo = 30 - door_cells // 2
    occupied[lo : lo + door_cells, 40] = False
    return OccupancyGrid.from_occupancy(occupied, 0.05, origin or Pose2D(0.0, 0.0, 0.0))


def clearance(grid: OccupancyGrid, points: NDArray[np.float64]) -> NDArray[np.float64]:
    """Distance from each point to the nearest occupied cell centre, m."""
    centres = grid.cell_to_world(np.argwhere(grid.occupied()))
    dist, _ = cKDTree(centres).query(points)
    return np.asarray(dist)


def test_path_matches_astar_on_the_inflated_costs_in_a_rotated_frame() -> None:
    origin = Pose2D(3.0, -2.0, 0.6)
    grid = doorway_grid(12, origin)
    start = grid.cell_to_world([10, 10])[0] + 0.01
    goal = grid.cell_to_world([50, 70])[0] - 0.01
    path = plan_path(grid, start, goal, robot_radius=0.15)
    assert isinstance(path, WorldPath)
    costs = grid.traversal_costs(0.15)
    reference = astar(costs, (10, 10), (50, 70))
    cells = grid.world_to_cell(path.points)
    np.testing.assert_array_equal(cells, reference.cells)
    assert path.cost == pytest.approx(reference.cost * 0.05, rel=1e-12)
    assert path.length == pytest.approx(reference.length * 0.05, rel=1e-9)
    assert path.expanded == reference.expanded
    assert_valid_path(costs, cells, (10, 10), (50, 70))
    # The path crosses the wall through the door.
    assert set(cells[:, 1].tolist()) >= {40}
    assert np.all(clearance(grid, path.points) > 0.15)
    with pytest.raises(ValueError):
        path.points[0, 0] = 0.0


def test_robot_radius_closes_a_narrow_door() -> None:
    grid = doorway_grid(8)  # 0.4 m door
    start, goal = (0.5, 1.5), (3.5, 1.5)
    through = plan_path(grid, start, goal, robot_radius=0.1)
    assert through.length == pytest.approx(3.0, abs=0.06)
    with pytest.raises(NoPathError) as info:
        plan_path(grid, start, goal, robot_radius=0.25)
    assert info.value.explored > 100


def test_inflation_radius_keeps_the_path_away_from_walls() -> None:
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[18:22, 20:40] = True  # a block between start and goal
    grid = OccupancyGrid.from_occupancy(occupied, 0.1)
    start, goal = (0.55, 2.05), (5.45, 2.05)
    tight = plan_path(grid, start, goal, robot_radius=0.2)
    wide = plan_path(grid, start, goal, robot_radius=0.2, inflation_radius=1.0)
    assert wide.length > tight.length
    assert clearance(grid, wide.points).min() > clearance(grid, tight.points).min()
    # Costs above 1 near obstacles make the cost exceed the length.
    assert wide.cost > wide.length
    assert tight.cost == pytest.approx(tight.length, rel=1e-12)


def test_options_reach_the_planner() -> None:
    grid = doorway_grid(12)
    start, goal = (0.3, 0.3), (3.7, 2.7)
    optimal = plan_path(grid, start, goal, options={"heuristic_weight": 0.0})
    astar_path = plan_path(grid, start, goal)
    assert optimal.cost == pytest.approx(astar_path.cost, rel=1e-12)
    assert optimal.expanded > astar_path.expanded
    cutting = plan_path(grid, start, goal, options={"corner_cutting": True})
    assert cutting.cost <= astar_path.cost


def test_registered_planners_are_dispatched(monkeypatch: pytest.MonkeyPatch) -> None:
    def straight(
        costs: NDArray[np.float64], start: tuple[int, int], goal: tuple[int, int]
    ) -> tuple[NDArray[np.float64], float, int]:
        cells = np.array([start, goal], dtype=np.float64)
        return cells, float(np.hypot(*(cells[1] - cells[0]))), 0

    monkeypatch.setitem(plan_module.PLANNERS, "straight", straight)
    grid = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), 0.5)
    path = plan_path(grid, (0.25, 0.25), (4.25, 2.25), planner="straight")
    np.testing.assert_allclose(path.points, [[0.25, 0.25], [4.25, 2.25]])
    assert path.length == pytest.approx(math.hypot(4.0, 2.0))
    assert path.cost == pytest.approx(path.length)


def test_bad_arguments() -> None:
    grid = doorway_grid(12)
    with pytest.raises(ValueError, match=r"start_xy .* outside"):
        plan_path(grid, (-1.0, 1.0), (3.0, 1.0))
    with pytest.raises(ValueError, match=r"goal_xy .* obstacle"):
        plan_path(grid, (1.0, 1.0), (2.02, 2.0))
    with pytest.raises(ValueError, match=r"goal_xy .* obstacle"):
        plan_path(grid, (1.0, 1.0), (2.2, 2.0), robot_radius=0.3)
    with pytest.raises(ValueError, match="planner"):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), planner="rrt")
    with pytest.raises(ValueError, match="robot_radius"):
        plan_path(grid, (1.0, 1.0), (3.0, 1.0), robot_radius=-0.1)
    with pytest.raises(ValueError, match="start_xy"):
        plan_path(grid, (1.0, 1.0, 0.0), (3.0, 1.0))
    with pytest.raises(TypeError, match="OccupancyGrid"):
        plan_path(np.zeros((5, 5)), (1.0, 1.0), (3.0, 1.0))  # type: ignore[arg-type]


def test_office_map_route(shared_data: Path) -> None:
    # Willow Garage office, a real robot-built ROS map (0.1 m cells); the issue's
    # robot inflates by 0.3 m.
    folder = shared_data / "ros-map-server-maps" / "willow_garage_2010"
    yaml = folder / "willow-2010-02-18-0.10.yaml"
    grid = OccupancyGrid.load(yaml)
    costs = grid.traversal_costs(0.3)
    start_cell = (290, 221)
    field = distance_field(costs, start_cell)
    goal_cell = np.unravel_index(np.argmax(np.where(np.isfinite(field), field, -1.0)), field.shape)
    start = grid.cell_to_world(start_cell)[0]
    goal = grid.cell_to_world(goal_cell)[0]
    path = plan_path(grid, start, goal, robot_radius=0.3)
    # The farthest reachable cell is tens of metres of corridors away.
    assert path.length > 1.2 * np.hypot(*(goal - start))
    assert path.cost == pytest.approx(field[goal_cell] * grid.resolution, rel=1e-9)
    assert np.all(clearance(grid, path.points) > 0.3)
    back = plan_path(grid, goal, start, robot_radius=0.3)
    assert back.cost == pytest.approx(path.cost, rel=1e-9)
