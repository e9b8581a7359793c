"""Maps in UTM coordinates: the same cells, matches and maps as the scene at the origin.

Outdoor robots keep maps at a projected origin (x ~ 5e5 m, y ~ 4.5e6 m, where floats
are 5.8e-11 and 9.3e-10 m apart). The scenes here are built at UTM coordinates and
moved to the origin by subtracting the offset, which is exact (Sterbenz: the points
lie within a factor 2 of it), so both hold the same geometry. Every conversion
subtracts the grid's origin first (``x - origin``, exact again) and scales after, so
grid coordinates, and with them cells and ray casting, are bit for bit those at the
origin. A result that is itself a UTM coordinate (a matched pose) rounds once or a
few times at its size: within 1e-8 m (ten float steps at 4.5e6 m; measured 1.3e-10 m
for the matcher, 6e-10 m for the mapper).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import box

from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.sim import World

UTM = (500123.45, 4500678.9)
BEAMS = 360
ROOM = [box(0.0, 0.0, 10.0, 10.0).exterior, box(4.9, 3.0, 5.1, 7.0), box(1.5, 1.4, 4.5, 1.6)]


def _scan(pose: tuple[float, float, float]) -> LaserScan:
    """A 360-beam scan in a 10 m x 10 m room with two inner walls (pose at the origin)."""
    world = World(ROOM)
    angles = np.linspace(-math.pi, math.pi, BEAMS, endpoint=False)
    ranges = world.raycast(pose, angles, range_max=12.0)
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / BEAMS,
                     range_min=0.05, range_max=12.0)  # fmt: skip


def _far(local: tuple[float, ...]) -> tuple[float, ...]:
    """``local`` moved to UTM: (x, y, theta) or (x, y)."""
    return (local[0] + UTM[0], local[1] + UTM[1], *local[2:])


def _near(far: tuple[float, ...]) -> tuple[float, ...]:
    """A UTM point or pose moved to the origin: exact."""
    return (far[0] - UTM[0], far[1] - UTM[1], *far[2:])


@pytest.mark.parametrize("exact", [False, True])
@pytest.mark.parametrize("yaw", [0.0, 0.4, -0.3])
def test_integrate_scan_at_utm_coordinates_writes_the_cells_of_the_origin(
    exact: bool, yaw: float
) -> None:
    sensor = _near(_far((3.013, 5.021, 0.3)))  # the local pose as a UTM pose rounds
    scan = _scan(sensor)  # type: ignore[arg-type]
    corner = _far((-4.0, -3.0))  # the map's lower-left corner
    grids = []
    for origin, pose in ((_near(corner), sensor), (corner, _far(sensor))):
        grid = OccupancyGrid.empty(width=16.0, height=16.0, resolution=0.05,
                                   origin=(*origin, yaw))  # fmt: skip
        assert integrate_scan(grid, scan, pose, exact=exact) > 1000
        grids.append(grid)
    np.testing.assert_array_equal(grids[1].logodds, grids[0].logodds)


@pytest.mark.parametrize("resolution", [1e-6, 1e-3, 0.05])
@pytest.mark.parametrize("yaw", [0.0, 1.1])
def test_world_to_cell_at_utm_coordinates_is_that_at_the_origin(
    resolution: float, yaw: float
) -> None:
    rng = np.random.default_rng(13)
    far = OccupancyGrid.empty(width=800 * resolution, height=600 * resolution,
                              resolution=resolution, origin=(*UTM, yaw))  # fmt: skip
    near = OccupancyGrid.empty(width=800 * resolution, height=600 * resolution,
                               resolution=resolution, origin=(0.0, 0.0, yaw))  # fmt: skip
    cells = np.column_stack((rng.integers(0, 600, 500), rng.integers(0, 800, 500)))
    points = far.cell_to_world(cells + rng.uniform(-0.5, 0.5, cells.shape))
    shifted = points - np.array(UTM)
    np.testing.assert_array_equal(far.world_to_cell(points), near.world_to_cell(shifted))
    np.testing.assert_array_equal(
        far.world_to_cell(points, continuous=True), near.world_to_cell(shifted, continuous=True)
    )
    # Cell centres at UTM coordinates round to the float's step (9.3e-10 m): even
    # micrometre cells come back to themselves.
    np.testing.assert_array_equal(far.world_to_cell(far.cell_to_world(cells)), cells)


def _scanned_map(
    origin: tuple[float, float], scan: LaserScan, pose: tuple[float, ...]
) -> OccupancyGrid:
    """A 12 m square map around the room at ``origin``, one scan from ``pose`` written in."""
    grid = OccupancyGrid.empty(width=12.0, height=12.0, resolution=0.05,
                               origin=(origin[0] - 1.0, origin[1] - 1.0, 0.0))  # fmt: skip
    integrate_scan(grid, scan, pose, hit=2.2, miss=-0.4)
    return grid


@pytest.mark.parametrize("search", [False, True])
def test_scan_matcher_at_utm_coordinates_matches_as_at_the_origin(search: bool) -> None:
    truth = _near(_far((3.013, 5.021, 0.3)))
    scan = _scan(truth)  # type: ignore[arg-type]
    guess = (truth[0] + 0.08, truth[1] - 0.06, truth[2] + 0.03)  # 0.1 m off
    options = (
        {"search_distance": 0.1, "search_angle": 0.1, "translation_weight": 1.0,
         "rotation_weight": 1.0} if search else {}
    )  # fmt: skip
    near_map = _scanned_map((0.0, 0.0), scan, truth)
    far_map = _scanned_map(UTM, scan, _far(truth))
    near = ScanMatcher(**options).match(near_map, scan, guess)  # type: ignore[arg-type]
    far = ScanMatcher(**options).match(far_map, scan, _far(guess))  # type: ignore[arg-type]
    assert near.converged and far.converged
    assert math.dist((near.pose.x, near.pose.y), truth[:2]) < 0.05  # within a cell
    moved = _near((far.pose.x, far.pose.y, far.pose.theta))
    assert moved == pytest.approx((near.pose.x, near.pose.y, near.pose.theta), abs=1e-8)
    assert far.iterations == near.iterations
    assert far.score == pytest.approx(near.score, abs=1e-8)
    np.testing.assert_allclose(far.covariance, near.covariance, rtol=1e-6)


def test_scan_mapper_at_utm_coordinates_maps_as_at_the_origin() -> None:
    start = _near(_far((3.013, 5.021, 0.3)))
    mappers = (ScanMapper(pose=start), ScanMapper(pose=_far(start)))
    for k in range(6):
        pose = _near(_far((start[0] + 0.3 * k, start[1] + 0.1 * k, start[2] + 0.05 * k)))
        scan = _scan(pose)  # type: ignore[arg-type]
        odometry = (pose[0] + 0.01, pose[1] - 0.01, pose[2])
        near = mappers[0].update(scan, odometry)
        far = mappers[1].update(scan, _far(odometry))
        moved = _near((far.pose.x, far.pose.y, far.pose.theta))
        assert moved == pytest.approx((near.pose.x, near.pose.y, near.pose.theta), abs=1e-8)
        assert far.iterations == near.iterations
    near_map, far_map = mappers[0].map, mappers[1].map
    # The map's corner is a UTM coordinate too: within a float step or two of it.
    assert _near((far_map.origin.x, far_map.origin.y)) == pytest.approx(
        (near_map.origin.x, near_map.origin.y), abs=2e-9
    )
    np.testing.assert_array_equal(far_map.logodds, near_map.logodds)
