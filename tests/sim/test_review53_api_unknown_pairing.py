"""MapPlanner's unknown_cost and World's unknown_blocks are chosen together (the docs' pairing).

Review 52's PIPELINE user planned across unknown space at a finite cost and ran
the route in a World whose unknown cells block. The two never meet in code (a
plan reaches the simulator as points), so the docstrings and guides state the
pairing; this checks the pairing they state on a map with an unknown band.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.sim import World

RADIUS = 0.1


def _band_map() -> OccupancyGrid:
    """A 2 m × 4 m room, a wall across it, its gap unknown (never seen)."""
    occupied = np.zeros((20, 40), dtype=bool)
    occupied[:, 20] = True
    unknown = np.zeros_like(occupied)
    unknown[8:12, 20] = True
    occupied[8:12, 20] = False
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)


def _footprint_hits(world: World, points: np.ndarray) -> bool:
    # Every 1 cm along the route: the vertices alone may straddle the band.
    steps = [
        np.linspace(a, b, max(2, int(np.hypot(*(b - a)) / 0.01) + 1))
        for a, b in itertools.pairwise(points)
    ]
    dense = np.concatenate(steps)
    return any(world.collides(RADIUS, (x, y, 0.0)) for x, y in dense)


def test_a_finite_unknown_cost_plans_through_cells_a_blocking_world_blocks() -> None:
    grid = _band_map()
    start, goal = (0.5, 1.0), (3.5, 1.0)
    route = MapPlanner(grid, robot_radius=RADIUS, unknown_cost=5.0).plan(start, goal)
    assert grid.unknown()[tuple(route.to_grid(grid).cells.T)].any()
    assert _footprint_hits(World(grid=grid), route.points)  # unknown_blocks=True: mismatched
    assert not _footprint_hits(World(grid=grid, unknown_blocks=False), route.points)  # paired


def test_the_default_pair_agrees() -> None:
    grid = _band_map()
    # unknown_cost=inf: the band is a wall to the planner, as to the World by default.
    with pytest.raises(NoPathError):
        MapPlanner(grid, robot_radius=RADIUS).plan((0.5, 1.0), (3.5, 1.0))
    assert World(grid=grid).collides(RADIUS, (2.05, 1.0, 0.0))
