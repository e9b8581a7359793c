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
from shapely.geometry import LineString, Point

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
