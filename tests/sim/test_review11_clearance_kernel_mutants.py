"""Footprint clearance of the sim's distance kernels (mutation testing).

Surviving mutants: a polygon footprint inside a circular room
(``Circle(..., solid=False)``) measured by its nearest point instead of its
farthest vertex (``r - far``); a wall or an occupied cell wholly inside a
polygon footprint not counted as contact; the ring search of the edge index
and of the map stopping one ring early; the footprint placed in a rotated
map's frame with the wrong sign. Distances are checked against shapely's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.affinity import rotate, translate
from shapely.geometry import LineString, Point, Polygon, box
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, World

_SQUARE = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]


@pytest.mark.parametrize(
    "pose", [(1.0, 0.0, 0.0), (0.0, -2.0, 0.3), (-1.5, 1.0, -1.2), (0.0, 0.0, 0.0)]
)
def test_polygon_in_a_circular_room_is_its_farthest_vertex_from_the_wall(
    pose: tuple[float, float, float],
) -> None:
    r = 5.0
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    # A convex footprint's farthest point from the room's centre is a vertex.
    far = max(math.hypot(x + c * vx - s * vy, y + s * vx + c * vy) for vx, vy in _SQUARE)
    world = World([Circle((0.0, 0.0), r, solid=False)])
    assert world.clearance(_SQUARE, pose) == pytest.approx(r - far, rel=1e-12)
    assert world.collides(_SQUARE, pose) is False


def test_disc_in_a_circular_room() -> None:
    world = World([Circle((1.0, 1.0), 4.0, solid=False)])
    d = math.hypot(2.0 - 1.0, 3.0 - 1.0)
    assert world.clearance(0.5, (2.0, 3.0, 0.0)) == pytest.approx(4.0 - (d + 0.5), rel=1e-12)


def test_a_wall_wholly_inside_a_polygon_footprint_touches_it() -> None:
    # "0 when the footprint touches or overlaps an obstacle's boundary".
    wall = LineString([(0.9, 0.0), (1.1, 0.05)])
    world = World([wall])
    assert Polygon(_SQUARE).contains(translate(wall, -1.0, 0.0))
    assert world.clearance(_SQUARE, (1.0, 0.0, 0.0)) == 0.0
    assert world.collides(_SQUARE, (1.0, 0.0, 0.0)) is True


def test_an_occupied_cell_wholly_inside_a_polygon_footprint_touches_it() -> None:
    occ = np.zeros((20, 20), dtype=bool)
    occ[10, 10] = True  # the square [1.0, 1.1] x [1.0, 1.1] m
    world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=0.1))
    assert world.clearance(_SQUARE, (1.05, 1.05, 0.3)) == 0.0
    assert world.collides(_SQUARE, (1.05, 1.05, 0.3)) is True
    assert world.clearance(_SQUARE, (1.05, 2.0, 0.0)) == pytest.approx(0.4, abs=1e-12)


def _shapely_clearance(obstacles: BaseGeometry, radius: float, x: float, y: float) -> float:
    return max(float(Point(x, y).distance(obstacles)) - radius, 0.0)


def test_disc_clearance_to_many_walls_equals_shapelys() -> None:
    # Enough short walls that the edge index has many cells and the search
    # visits several rings before it may stop.
    rng = np.random.default_rng(7)
    starts = rng.uniform(0.0, 20.0, (60, 2))
    ends = starts + rng.uniform(-0.6, 0.6, (60, 2))
    walls = [LineString([tuple(a), tuple(b)]) for a, b in zip(starts, ends, strict=True)]
    world = World(walls)
    union = unary_union(walls)
    for x, y in rng.uniform(-3.0, 23.0, (400, 2)):
        want = _shapely_clearance(union, 0.05, float(x), float(y))
        assert world.clearance(0.05, (float(x), float(y), 0.0)) == pytest.approx(
            want, rel=1e-9, abs=1e-12
        )


@pytest.mark.parametrize("theta", [0.0, 0.6, -2.2])
def test_disc_clearance_to_a_rotated_map_equals_shapelys(theta: float) -> None:
    rng = np.random.default_rng(11)
    rows, cols, res, ox, oy = 25, 30, 0.2, 1.0, -2.0
    occ = rng.random((rows, cols)) < 0.03
    grid = OccupancyGrid.from_occupancy(occ, resolution=res, origin=Pose2D(ox, oy, theta))
    world = World(grid=grid)
    # Cell (r, c) is the square [c, c+1] x [r, r+1] · res in the map's frame,
    # placed by the origin pose (rotation about the origin corner, then translation).
    cells = [box(c * res, r * res, (c + 1) * res, (r + 1) * res) for r, c in np.argwhere(occ)]
    blocked = translate(rotate(unary_union(cells), theta, origin=(0.0, 0.0), use_radians=True),
                        ox, oy)
    for u, v in rng.uniform(-1.0, 7.0, (300, 2)):
        # Query points over and around the map, in the map's frame, placed as the cells.
        x = ox + math.cos(theta) * u - math.sin(theta) * v
        y = oy + math.sin(theta) * u + math.cos(theta) * v
        if blocked.contains(Point(x, y)):
            continue
        want = _shapely_clearance(blocked.boundary, 0.03, x, y)
        assert world.clearance(0.03, (x, y, 0.0)) == pytest.approx(want, rel=1e-9, abs=1e-9)
