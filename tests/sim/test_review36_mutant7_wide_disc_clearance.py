"""A wide disc's clearance among many small primitives (mutation review, session 40).

The clearance search visits the edge index's cells in rings around the
footprint's bounding box and stops at the first ring whose cells all lie
farther than the best distance found. The older tests of it use a disc of 2 cm
among primitives a few centimetres apart: a mutant that put the disc's box at
its top edge only (``py + radius`` for ``py - radius``) survived them, since a
box wrong by 4 cm hides no cell. Here the disc (0.3-1.5 m) spans many of the
index's cells, so a wrong box stops the search before the cells below it.

Oracle: shapely's distance from the disc's centre to each wall, less the radius
(0 when it is within the radius: the disc touches or holds the wall).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, Point, Polygon
from shapely.ops import unary_union

from navkit.mapping import OccupancyGrid
from navkit.sim import World


@pytest.mark.parametrize("seed", range(3))
def test_wide_disc_clearance_among_many_short_walls_matches_shapely(seed: int) -> None:
    rng = np.random.default_rng(3660 + seed)
    walls = []
    for _ in range(250):
        a = rng.uniform(0.0, 12.0, 2)
        walls.append(LineString([a, a + rng.uniform(-0.15, 0.15, 2)]))
    world = World(walls)
    for x, y, th in rng.uniform([-1.0, -1.0, -math.pi], [13.0, 13.0, math.pi], (120, 3)):
        r = float(rng.uniform(0.3, 1.5))
        centre = Point(x, y)
        want = max(min(w.distance(centre) for w in walls) - r, 0.0)
        got = world.clearance(r, (x, y, th))
        assert got == pytest.approx(want, abs=1e-9), (x, y, r)
        assert world.collides(r, (x, y, th)) == (want == 0.0)


@pytest.mark.parametrize("seed", range(3))
def test_wide_disc_clearance_to_a_rotated_map_matches_shapely(seed: int) -> None:
    """The same in a map's cells, the search's box in the map's frame. A mutant that
    multiplied the box's lower edge by the resolution instead of dividing survived:
    with cells below 1 m it only grows the box (a slower search, the same answer);
    with cells above 1 m it moves the box's lower edge up past rows the footprint covers."""
    rng = np.random.default_rng(3670 + seed)
    occ = rng.random((50, 60)) < 0.02
    res = [0.05, 0.2, 2.5][seed]  # metres per cell: also above 1
    yaw = float(rng.uniform(-math.pi, math.pi))
    origin = (float(rng.uniform(-2.0, 2.0)), float(rng.uniform(-2.0, 2.0)))
    world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=res, origin=(*origin, yaw)))
    c, s = math.cos(yaw), math.sin(yaw)
    squares = []
    for row, col in np.argwhere(occ):
        corners = [(col, row), (col + 1, row), (col + 1, row + 1), (col, row + 1)]
        squares.append(
            Polygon([(origin[0] + res * (c * u - s * v), origin[1] + res * (s * u + c * v))
                     for u, v in corners])
        )  # fmt: skip
    cells = unary_union(squares)
    for u, v in rng.uniform([-5.0, -5.0], [65.0, 55.0], (80, 2)):
        x = origin[0] + res * (c * u - s * v)
        y = origin[1] + res * (s * u + c * v)
        r = float(rng.uniform(3.0, 15.0)) * res
        want = max(cells.boundary.distance(Point(x, y)) - r, 0.0)
        if cells.contains(Point(x, y)):
            want = 0.0
        got = world.clearance(r, (x, y, 0.0))
        assert got == pytest.approx(want, abs=1e-9), (u, v, r)
