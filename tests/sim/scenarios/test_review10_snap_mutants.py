"""Two rules of the indoor scenarios' end-point snap that no test pinned down.

* ``_segments_touch`` grows every cell by 1e-9 "so that a segment through a corner
  is caught whatever the rounding": a step that passes exactly through an obstacle
  cell's corner (in exact arithmetic, from a point with round decimal coordinates)
  must count as touching it, although float rounding may put it 1e-16 beside.
* ``_passable`` lets a step cross the obstacle the point is in, "the 8-connected
  blob of obstacle cells around its cell": a wall cell joined to the point's cell
  only at a corner belongs to it.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from scipy import ndimage
from shapely.geometry import LineString, box
from test_review10_snap_walls import reference_snap

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.sim.scenarios._indoor_nav_mapping import _passable, _segments_touch

HALF = Fraction(1, 2)


def steps_through_corners() -> list[tuple[tuple[float, float], tuple[int, int]]]:
    """Steps from decimal points to cell centres passing exactly through a corner of cell (0, 0).

    A corner P of the square [-1/2, 1/2]^2, a centre E, and the point
    q = P + j/10 (P - E) on the line beyond P: the step q -> E goes through P.
    """
    steps = []
    for pr, pc in itertools.product((-HALF, HALF), repeat=2):
        for er, ec in itertools.product(range(-3, 4), repeat=2):
            if (er, ec) == (0, 0):
                continue
            for j in range(1, 25):
                qr, qc = pr + Fraction(j, 10) * (pr - er), pc + Fraction(j, 10) * (pc - ec)
                if abs(qr) <= HALF and abs(qc) <= HALF:  # q on the cell: the other rule
                    continue
                # The decimal the caller means, as the nearest float (never exactly on the line).
                steps.append(((float(qr), float(qc)), (er, ec)))
    return steps


def test_a_step_through_a_cell_corner_touches_it() -> None:
    steps = steps_through_corners()
    assert len(steps) > 1000
    cell = (np.array([0]), np.array([0]))
    touched = [
        bool(_segments_touch(np.array(q), np.array([e[0]]), np.array([e[1]]), *cell)[0])
        for q, e in steps
    ]
    missed = [s for s, t in zip(steps, touched, strict=True) if not t]
    assert missed == []


def corner_joined_map() -> tuple[MapPlanner, tuple[float, float]]:
    """A map whose walls meet at corners, and a point in one of its wall cells (4, 11).

    0.05 m cells, robot radius 0.05 m. The nearest admissible centre, (5, 8), is
    reached by a step crossing the wall cell (5, 10), joined to (4, 11) only at a
    corner.
    """
    rows = [
        ".....#....##",
        "...........#",
        "#.......#.#.",
        "............",
        "###.#....#.#",
        "......#...#.",
        "#........###",
        "#.#...#....#",
        "....#......#",
        ".........#.#",
        "#..........#",
        "....#.....#.",
    ]
    occupied = np.array([[ch == "#" for ch in row] for row in rows])
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    planner = MapPlanner(grid, robot_radius=0.05)
    return planner, (0.5756, 0.2489)


def test_a_wall_cell_joined_at_a_corner_is_part_of_the_points_obstacle() -> None:
    planner, point = corner_joined_map()
    grid = planner.grid
    cell = tuple(int(v) for v in grid.world_to_cell(np.array(point)))
    assert cell == (4, 11)
    found, clear_cut = reference_snap(planner, point)
    assert clear_cut and found
    nearest, centre = min(found)
    snapped = _passable(planner, point)
    assert math.dist(point, snapped) == pytest.approx(nearest, abs=1e-12)
    assert snapped == pytest.approx(centre, abs=1e-12)
    # The rule mattered: the step crosses an occupied cell that is not 4-connected
    # to the point's cell (a blob with 4-connectivity would call it another obstacle).
    occupied = ~np.isfinite(planner.costs) & ~grid.free()
    four, _ = ndimage.label(occupied)
    q = grid.world_to_cell(np.array(point), continuous=True)
    end = grid.world_to_cell(np.array(snapped))
    step = LineString([q, end])
    crossed = [
        (r, c)
        for r, c in np.argwhere(occupied)
        if step.intersects(box(r - 0.5, c - 0.5, r + 0.5, c + 0.5))
    ]
    assert any(four[rc] != four[cell] for rc in crossed)
