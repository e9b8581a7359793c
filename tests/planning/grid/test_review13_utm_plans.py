"""Planning on maps in UTM coordinates: the paths of the same map at the origin, moved.

The map's origin is a UTM position (x ~ 5e5 m, y ~ 4.5e6 m, floats 5.8e-11 and
9.3e-10 m apart) and the start and goal are UTM points; the scene at the origin is
the same one moved by subtracting the offset (exact: Sterbenz). The planners work in
cells, so they search the same cells: the same expansions and cost, bit for bit.
Only the world points of the path are UTM coordinates, each rounded once or twice
at that size (``cell_to_world`` rotates, then adds the origin): within 1e-8 m, ten
float steps (measured: 4.7e-10 m); the length, a sum of their differences, too
(measured: 9e-10 m over 20 m of 1 mm cells).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner

UTM = np.array([500123.45, 4500678.9])


def _occupied() -> np.ndarray:
    occupied = np.zeros((300, 300), dtype=bool)
    occupied[100:200, 150] = True
    occupied[150, 20:120] = True
    return occupied


def _ends(resolution: float, yaw: float) -> tuple[np.ndarray, np.ndarray]:
    """Start and goal as UTM points, (2, 2), and the same at the origin (exact)."""
    cells = np.array([[86.1, 51.3], [250.2, 280.7]]) * resolution  # map frame, m
    far = Pose2D(*UTM, yaw).transform_points(cells)
    return far, far - UTM


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
@pytest.mark.parametrize(("resolution", "yaw"), [(0.05, 0.0), (0.05, 0.7), (0.001, -2.1)])
def test_map_planner_at_utm_coordinates_plans_the_path_at_the_origin(
    planner: str, resolution: float, yaw: float
) -> None:
    far_ends, near_ends = _ends(resolution, yaw)
    paths = []
    for origin, ends in ((UTM, far_ends), (np.zeros(2), near_ends)):
        grid = OccupancyGrid.from_occupancy(
            _occupied(), resolution=resolution, origin=(*origin, yaw)
        )
        paths.append(MapPlanner(grid, robot_radius=4 * resolution, planner=planner).plan(*ends))
    far, near = paths
    assert far.expanded == near.expanded
    # The links from the given ends to their cells' centres are measured in world
    # metres: at UTM coordinates, to within a rounding step of 4.5e6 m.
    assert far.cost == pytest.approx(near.cost, abs=1e-8)
    assert far.points.shape == near.points.shape
    np.testing.assert_allclose(far.points - UTM, near.points, rtol=0.0, atol=1e-8)
    assert far.length == pytest.approx(near.length, abs=1e-8)


@pytest.mark.parametrize("yaw", [0.0, 0.7])
def test_map_planner_escape_at_utm_coordinates_is_the_escape_at_the_origin(yaw: float) -> None:
    resolution = 0.05
    rng = np.random.default_rng(17)
    grids = [
        OccupancyGrid.from_occupancy(_occupied(), resolution=resolution, origin=(*o, yaw))
        for o in (UTM, np.zeros(2))
    ]
    planners = [MapPlanner(g, robot_radius=3 * resolution) for g in grids]
    goal_far = Pose2D(*UTM, yaw).transform_points([[280.3 * resolution, 280.6 * resolution]])[0]
    escaped = 0
    for _ in range(20):
        # Within robot_radius of the wall at column 150 (not in it).
        local = [rng.choice([rng.uniform(147.0, 149.9), rng.uniform(151.1, 153.0)]),
                 rng.uniform(110.0, 190.0)]  # fmt: skip
        start_far = Pose2D(*UTM, yaw).transform_points([[v * resolution for v in local]])[0]
        far = planners[0].plan(start_far, goal_far, start_tolerance=0.3)
        near = planners[1].plan(start_far - UTM, goal_far - UTM, start_tolerance=0.3)
        assert far.points[0].tolist() == start_far.tolist()  # the start itself, not rounded
        assert far.cost == pytest.approx(near.cost, abs=1e-8)
        np.testing.assert_allclose(far.points - UTM, near.points, rtol=0.0, atol=1e-8)
        escaped += not np.array_equal(near.points[1], grids[1].cell_to_world(
            grids[1].world_to_cell(start_far - UTM)))  # fmt: skip
    assert escaped > 10


@pytest.mark.parametrize("yaw", [0.0, -2.1])
def test_field_dstar_world_methods_at_utm_coordinates(yaw: float) -> None:
    resolution = 0.001
    costs = np.where(_occupied(), np.inf, 1.0)
    far_ends, near_ends = _ends(resolution, yaw)
    far_planner = FieldDStar(costs, resolution=resolution, origin=(*UTM, yaw))
    near_planner = FieldDStar(costs, resolution=resolution, origin=(0.0, 0.0, yaw))
    np.testing.assert_array_equal(
        far_planner.world_to_node(far_ends), near_planner.world_to_node(near_ends)
    )
    far = far_planner.plan_world(*far_ends)
    near = near_planner.plan_world(*near_ends)
    # The path runs from the points given, exactly, not from their round trip
    # through grid coordinates.
    assert far.points[0].tolist() == far_ends[0].tolist()
    assert far.points[-1].tolist() == far_ends[1].tolist()
    assert far.cost == near.cost  # computed in the grid
    # The length of the points returned (review 54, FOUND7), as MapPlanner's: at UTM
    # coordinates, to within their rounding steps.
    assert far.length == pytest.approx(near.length, abs=1e-8)
    np.testing.assert_allclose(far.points - UTM, near.points, rtol=0.0, atol=1e-8)
