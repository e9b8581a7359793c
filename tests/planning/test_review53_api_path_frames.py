"""Path2D.to_world / to_grid: a grid path on a map's cells converted as MapPlanner converts it.

Review 52's PIPELINE user converted a grid-frame path by hand
(``Path2D(grid.cell_to_world(p.points), "world", cost=p.cost * grid.resolution, ...)``);
the path now converts itself, through the one conversion MapPlanner's world
plans use, so a grid path between two cell centres converts to the world plan
MapPlanner returns between those centres, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, Path2D, astar


def _random_map(seed: int) -> OccupancyGrid:
    rng = np.random.default_rng(seed)
    occupied = rng.random((30, 40)) < 0.12
    occupied[:3, :3] = False
    occupied[-3:, -3:] = False
    origin = (rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0), rng.uniform(-math.pi, math.pi))
    return OccupancyGrid.from_occupancy(
        occupied, resolution=0.05 + 0.1 * rng.random(), origin=origin
    )


def _same(a: Path2D, b: Path2D) -> None:
    assert a.frame == b.frame
    assert a.points.tobytes() == b.points.tobytes()
    assert (a.cost, a.length, a.expanded) == (b.cost, b.length, b.expanded)


def _centres(grid: OccupancyGrid, *cells: tuple[int, int]) -> list[np.ndarray]:
    return list(grid.cell_to_world(np.array(cells, dtype=np.int64)))


@pytest.mark.parametrize("seed", range(6))
def test_astar_path_converts_to_map_planners_world_plan_bit_for_bit(seed: int) -> None:
    grid = _random_map(seed)
    start, goal = (1, 1), (28, 38)
    planned = MapPlanner(grid, robot_radius=0.0).plan(*_centres(grid, start, goal))
    cells = astar(grid.traversal_costs(robot_radius=0.0), start, goal)
    _same(cells.to_world(grid), planned)


@pytest.mark.parametrize("seed", range(6))
def test_field_dstar_path_converts_to_map_planners_world_plan_bit_for_bit(seed: int) -> None:
    grid = _random_map(seed)
    start, goal = (1, 1), (28, 38)
    planned = MapPlanner(grid, planner="field_dstar").plan(*_centres(grid, start, goal))
    cells = FieldDStar(grid.traversal_costs()).plan_cells(start, goal)
    converted = cells.to_world(grid)
    _same(converted, planned)
    # Not the hand conversion's length (cells × resolution): the world polyline's own.
    assert converted.length == pytest.approx(cells.length * grid.resolution, rel=1e-12)


def test_real_map_conversion_matches_map_planner(shared_data) -> None:  # type: ignore[no-untyped-def]
    grid = OccupancyGrid.load(
        shared_data / "ros-map-server-maps/willow_garage_2010/willow-2010-02-18-0.10.yaml"
    )
    start, goal = (281, 236), (237, 180)
    planned = MapPlanner(grid, robot_radius=0.3).plan(*_centres(grid, start, goal))
    cells = AStarPlanner(grid.traversal_costs(robot_radius=0.3)).plan(start, goal)
    _same(cells.to_world(grid), planned)


def test_to_grid_inverts_to_world() -> None:
    grid = _random_map(7)
    cells = FieldDStar(grid.traversal_costs()).plan_cells((1, 1), (28, 38))
    back = cells.to_world(grid).to_grid(grid)
    assert back.frame == "grid"
    np.testing.assert_allclose(back.points, cells.points, rtol=0, atol=1e-9)
    assert back.cost == pytest.approx(cells.cost, rel=1e-12)
    assert back.length == pytest.approx(cells.length, rel=1e-9)
    assert back.expanded == cells.expanded
    # Cells only of an A* path (through cell centres): Field D*'s points on cell
    # edges may round into either neighbour after a round trip.
    through_centres = astar(grid.traversal_costs(), (1, 1), (28, 38))
    assert through_centres.to_world(grid).to_grid(grid).cells.tolist() == (
        through_centres.cells.tolist()
    )


def test_world_plan_to_grid_gives_its_cells() -> None:
    grid = _random_map(3)
    planned = MapPlanner(grid).plan((grid.cell_to_world((1, 1))), grid.cell_to_world((28, 38)))
    cells = planned.to_grid(grid).cells
    assert cells[0].tolist() == [1, 1] and cells[-1].tolist() == [28, 38]
    assert not grid.occupied()[cells[:, 0], cells[:, 1]].any()


def test_local_grid_paths_convert_in_the_robot_frame() -> None:
    local = LocalGrid.from_points([[0.2, 0.1]], half_width=1.0, resolution=0.1)
    costs = np.where(local.occupied, np.inf, 1.0)
    path = astar(costs, (10, 10), (10, 14))
    world = path.to_world(local)
    np.testing.assert_array_equal(world.points, local.cell_to_world(path.points))
    assert world.cost == path.cost * local.resolution
    np.testing.assert_allclose(world.to_grid(local).points, path.points, atol=1e-12)


def test_converted_path_follows_the_trackers() -> None:
    grid = _random_map(1)
    cells = astar(grid.traversal_costs(), (1, 1), (28, 38))
    with pytest.raises(ValueError, match=r"path\.to_world\(grid\)"):
        RegulatedPurePursuit().set_path(cells)
    tracker = RegulatedPurePursuit()
    tracker.set_path(cells.to_world(grid))
    assert tracker.path_xy is not None and tracker.path_xy.shape[1] == 2


def test_refusals_name_the_problem() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
    grid_path = Path2D([[0, 0], [1, 1]], "grid", cost=1.5, length=1.4, expanded=2)
    world_path = Path2D([[0.25, 0.25]], "world", cost=0.0, length=0.0, expanded=0)
    with pytest.raises(ValueError, match="to_world converts a 'grid' path; this path is already"):
        world_path.to_world(grid)
    with pytest.raises(ValueError, match="to_grid converts a 'world' path; this path is already"):
        grid_path.to_grid(grid)
    for bad in (None, grid.occupied(), FieldDStar(np.ones((2, 2)))):
        with pytest.raises(TypeError, match="grid must be an OccupancyGrid or a LocalGrid"):
            grid_path.to_world(bad)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match="grid must be an OccupancyGrid or a LocalGrid"):
            world_path.to_grid(bad)  # type: ignore[arg-type]
    far = Path2D([[0, 0], [2.0**63, 0]], "grid", cost=1.0, length=1.0, expanded=0)
    with pytest.raises(ValueError, match="points must lie within"):
        far.to_world(grid)
    off = Path2D([[0, 0], [2e9, 0]], "world", cost=1.0, length=1.0, expanded=0)
    with pytest.raises(ValueError, match="points must lie within"):
        off.to_grid(grid)
    dear = Path2D([[0, 0], [1, 0]], "world", cost=1e308, length=1.0, expanded=0)
    with pytest.raises(ValueError, match="cost 1e\\+308 overflows"):
        dear.to_grid(grid)
    with pytest.raises(ValueError, match=r"path\.to_grid\(grid\)\.cells"):
        _ = world_path.cells


def test_world_paths_are_new_read_only_records() -> None:
    grid = _random_map(2)
    cells = astar(grid.traversal_costs(), (1, 1), (28, 38))
    before = cells.points.copy()
    world = cells.to_world(grid)
    assert world is not cells and not world.points.flags.writeable
    np.testing.assert_array_equal(cells.points, before)
    assert not np.shares_memory(world.points, cells.points)
