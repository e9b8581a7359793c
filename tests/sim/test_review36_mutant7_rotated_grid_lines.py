"""Beams along the grid lines of a rotated map touch the cells on both sides (session 40).

A beam of ``World(grid=...)`` that runs along a grid line touches the blocked
cells on both sides of it (their closed squares, as boxes of the polygon world).
In a rotated map the sensor's position and the beam's direction reach the map's
frame through a rotation, so a sensor on a line lands a few 1e-16 above or below
it, and the walk treats a start within rounding of a line as on it (``_NEAR``).
The older tests of this (``test_review13_grid_rays_on_lines.py``) use unrotated
maps, where the sensor is exactly on the line: a mutant of the walk that forgot
the row above when the sensor rounded just below a row line
(``r_hi == r`` for ``r_hi != r``) survived them (mutation review, MUTANT7).

The map's own edges were not treated so: a sensor on the edge of a rotated map
that rounded to a hair outside read ``inf`` along the edge, past the blocked
cells beside it, and ``inf`` instead of 0 from the face of a blocked cell there
(3 % of these beams, all from sensors on an edge); fixed, a start within
rounding of the edge is on it.

Oracle: the slab test of every blocked cell's closed square, in the map's own
frame, where the sensor is exactly on the lattice and the beam exactly along an
axis (brute force over the cells).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.sim import World


def _cell_hit(p: tuple[float, float], d: tuple[float, float], x0: float, y0: float) -> float:
    """Where the ray p + t d first touches the closed unit square at (x0, y0) (slabs)."""
    lo, hi = 0.0, math.inf
    for q, v, a in ((p[0], d[0], x0), (p[1], d[1], y0)):
        if v == 0.0:
            if q < a or q > a + 1.0:
                return math.inf
            continue
        ta, tb = (a - q) / v, (a + 1.0 - q) / v
        lo, hi = max(lo, min(ta, tb)), min(hi, max(ta, tb))
    return lo if lo <= hi else math.inf


@pytest.mark.parametrize("seed", range(3))
def test_beams_along_the_lines_of_a_rotated_map_match_the_cell_squares(seed: int) -> None:
    rng = np.random.default_rng(3600 + seed)
    rows, cols = 12, 15
    occ = rng.random((rows, cols)) < 0.12
    cells = np.argwhere(occ)
    res = float(rng.choice([0.05, 0.1, 0.25, 0.3]))
    checked = 0
    for _ in range(12):
        yaw = float(rng.uniform(-math.pi, math.pi))
        origin = (float(rng.uniform(-3.0, 3.0)), float(rng.uniform(-3.0, 3.0)))
        world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=res, origin=(*origin, yaw)))
        c, s = math.cos(yaw), math.sin(yaw)
        for _ in range(10):
            # A sensor on a grid line of the map (cell units), its edges included.
            if rng.random() < 0.5:
                p = (float(rng.integers(0, cols + 1)), float(rng.integers(0, 2 * rows + 1)) / 2.0)
            else:
                p = (float(rng.integers(0, 2 * cols + 1)) / 2.0, float(rng.integers(0, rows + 1)))
            x = origin[0] + res * (c * p[0] - s * p[1])
            y = origin[1] + res * (s * p[0] + c * p[1])
            axes = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))
            angles = np.array([yaw + k * math.pi / 2 for k in range(4)])
            got = world.raycast((x, y, 0.0), angles, range_max=100.0)
            for k, d in enumerate(axes):
                if (d[0] == 0.0 and p[0] % 1.0) or (d[1] == 0.0 and p[1] % 1.0):
                    continue  # this beam runs across cells, not along a line
                want = min(
                    (_cell_hit(p, d, float(col), float(row)) for row, col in cells),
                    default=math.inf,
                )
                if math.isinf(want):
                    assert got[k] == math.inf, (yaw, p, d, got[k])
                else:
                    assert got[k] == pytest.approx(want * res, abs=1e-9), (yaw, p, d)
                checked += 1
    assert checked > 150


@pytest.mark.parametrize("seed", range(4))
def test_diagonal_beams_through_the_corners_of_a_rotated_map_match_the_cell_squares(
    seed: int,
) -> None:
    """Beams at 45 degrees to the map's axes from its lattice points, in and around the
    map: each passes through cell corners only, entering the map through one from
    outside. A mutant that shrank the rounding allowance of the point where a beam
    enters the map (``abs(sv) - abs(t0 * ev)`` for ``+``) survived the other tests."""
    rng = np.random.default_rng(3610 + seed)
    rows, cols = 12, 15
    occ = rng.random((rows, cols)) < 0.12
    cells = np.argwhere(occ)
    res = float(rng.choice([0.05, 0.1, 0.25, 0.3]))
    half = math.sqrt(0.5)
    axes = ((half, half), (-half, half), (-half, -half), (half, -half))
    for _ in range(12):
        yaw = float(rng.uniform(-math.pi, math.pi))
        origin = (float(rng.uniform(-3.0, 3.0)), float(rng.uniform(-3.0, 3.0)))
        world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=res, origin=(*origin, yaw)))
        c, s = math.cos(yaw), math.sin(yaw)
        angles = np.array([yaw + math.pi / 4 + k * math.pi / 2 for k in range(4)])
        for _ in range(10):
            p = (float(rng.integers(-4, cols + 5)), float(rng.integers(-4, rows + 5)))
            x = origin[0] + res * (c * p[0] - s * p[1])
            y = origin[1] + res * (s * p[0] + c * p[1])
            got = world.raycast((x, y, 0.0), angles, range_max=100.0)
            for k, d in enumerate(axes):
                want = min(
                    (_cell_hit(p, d, float(col), float(row)) for row, col in cells),
                    default=math.inf,
                )
                if math.isinf(want):
                    assert got[k] == math.inf, (yaw, p, d, got[k])
                else:
                    assert got[k] == pytest.approx(want * res, abs=1e-9), (yaw, p, d)
