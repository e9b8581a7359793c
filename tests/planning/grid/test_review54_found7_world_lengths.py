"""One rule for a world path's length: that of its own points (review 54, FOUND7).

``MapPlanner.plan`` and ``Path2D.to_world`` gave a world path the length of its
world points' polyline; ``FieldDStar.plan_world`` (and ``replan_world``) the
length of its node polyline times the resolution, which differs in the last
bits (131 of 200 random plans), so a world path's length depended on which
planner made it. Every world path navkit returns now holds the length of its
own points; the cost stays the planner's (an integral the points cannot give).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner, Path2D


def _points_length(path: Path2D) -> float:
    legs = np.diff(path.points, axis=0)
    return float(np.hypot(legs[:, 0], legs[:, 1]).sum())


def _world(seed: int) -> tuple[np.ndarray, float, tuple[float, float, float]]:
    rng = np.random.default_rng(seed)
    rows, cols = (int(v) for v in rng.integers(5, 40, 2))
    costs = np.ones((rows, cols))
    costs[rng.random((rows, cols)) < 0.15] = np.inf
    costs[rng.random((rows, cols)) < 0.2] = 3.0
    origin = (
        float(rng.choice([0.0, -2000.0, 4.5e5])) + float(rng.normal()),
        float(rng.choice([0.0, 5.4e6])) + float(rng.normal()),
        float(rng.uniform(-np.pi, np.pi)) if rng.random() < 0.5 else 0.0,
    )
    return costs, float(rng.choice([0.05, 0.1, 0.3])), origin


def _free_point(rng: np.random.Generator, planner: FieldDStar, costs: np.ndarray) -> np.ndarray:
    free = np.argwhere(np.isfinite(costs))
    cell = free[rng.integers(len(free))].astype(np.float64) + rng.uniform(-0.45, 0.45, 2)
    return np.asarray(planner.node_to_world(cell + 0.5), dtype=np.float64)


def test_field_dstar_world_paths_hold_their_points_length() -> None:
    plans = replans = 0
    for seed in range(40):
        costs, resolution, origin = _world(seed)
        planner = FieldDStar(costs, resolution=resolution, origin=origin)
        rng = np.random.default_rng(seed + 1000)
        for _ in range(5):
            start, goal = _free_point(rng, planner, costs), _free_point(rng, planner, costs)
            try:
                path = planner.plan_world(start, goal)
            except (NoPathError, ValueError):
                continue
            assert path.length == _points_length(path), (seed, start, goal)
            assert path.points[0].tolist() == start.tolist()
            plans += 1
            try:
                again = planner.replan_world(_free_point(rng, planner, costs))
            except (NoPathError, ValueError):
                continue
            assert again.length == _points_length(again), seed
            replans += 1
    assert plans >= 100 and replans >= 50


def test_an_escaped_start_counts_its_segment_in_the_points_length() -> None:
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(4.5e5, 5.4e6, 0.3))
    start = grid.cell_to_world((2.0, 8.5))
    goal = grid.cell_to_world((2.0, 15.5))
    field = FieldDStar(
        grid.traversal_costs(robot_radius=0.2),
        resolution=0.1,
        origin=(4.5e5, 5.4e6, 0.3),
        obstacles=grid.occupied(),
    )
    path = field.plan_world(start, goal, start_tolerance=0.2)
    assert path.length == _points_length(path)
    mapped = MapPlanner(grid, robot_radius=0.2, planner="field_dstar")
    route = mapped.plan(start, goal, start_tolerance=0.2)
    assert route.length == _points_length(route)  # the rule MapPlanner already kept


def test_in_free_space_cost_and_length_agree_to_rounding() -> None:
    planner = FieldDStar(np.ones((10, 10)), resolution=0.5, origin=(1.0, 2.0, 0.0))
    path = planner.plan_world((1.25, 2.25), (5.75, 4.25))
    assert path.length == pytest.approx(path.cost, rel=1e-15)
    assert path.length == _points_length(path) == pytest.approx(float(np.hypot(4.5, 2.0)))
