"""The start escape's 1e-9-cell margin at obstacle corners (session 30, FDESCAPE).

Hypothesis found five failures of ``test_the_escape_is_the_nearest_reachable_
passable_centre`` (``test_review21_start_tolerance_field_dstar.py``), all one
start: both cell fractions drawn equal, so the start lies on a diagonal of
cells, and the segments to two candidate centres, (6, 7) and (2, 3), pass the
corners of obstacle cells (4, 6) and (3, 5) at about 1e-16 cells. The test's
oracle (shapely, exact on float coordinates) took those segments; navkit
refuses any segment within ``1e-9`` cell sides of an obstacle's square, so
it escaped to the farther (2, 2), or found nothing within 0.5 m. navkit was
right by design (a rounding error must never let a segment through a wall's
corner), but only a private comment said so: the docs of
``FieldDStar.plan_world`` and ``MapPlanner.plan`` now state the margin, the
oracle uses it, and these cases are pinned here, checked with exact rational
arithmetic on the float start point.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner

RES = 0.125
ORIGIN = (-1.0, 2.0, 0.0)
# The failing map (7 rows; the shrunk cases dropped the last row), '#' occupied.
ROWS = (
    "..#...##....",
    ".#.......#..",
    "#.....##..##",
    "#....#..#..#",
    "..##..#....#",
    "....#.......",
    "...#.#......",
)
# Both cell fractions of the start hypothesis drew: the start is on a cell diagonal.
FRACTION = 0.9247694168553324
START = (-0.2594038228930835, 2.6155961771069167)  # in band cell (4, 5)
MARGIN = Fraction(1, 10**9)


def occupancy(rows: int) -> NDArray[np.bool_]:
    return np.array([[ch == "#" for ch in line] for line in ROWS[:rows]])


def scene(rows: int) -> tuple[OccupancyGrid, NDArray[np.float64], FieldDStar]:
    grid = OccupancyGrid.from_occupancy(occupancy(rows), resolution=RES, origin=ORIGIN)
    costs = grid.traversal_costs(robot_radius=RES)
    planner = FieldDStar(costs, resolution=RES, origin=ORIGIN, obstacles=grid.occupied())
    return grid, costs, planner


def touches(q: tuple[Fraction, Fraction], cell: tuple[int, int], square: Any,
            grow: Fraction) -> bool:
    """Exactly: does the segment from ``q`` to ``cell``'s centre meet the grown square?"""
    lo, hi = Fraction(0), Fraction(1)
    for axis in (0, 1):
        d = cell[axis] - q[axis]
        a = square[axis] - Fraction(1, 2) - grow - q[axis]
        b = square[axis] + Fraction(1, 2) + grow - q[axis]
        if d == 0:
            if not a <= 0 <= b:
                return False
            continue
        lo, hi = max(lo, min(a / d, b / d)), min(hi, max(a / d, b / d))
    return lo <= hi


def exact_escape(
    costs: NDArray[np.float64], hard: NDArray[np.bool_], start: Any, tolerance: float,
    grow: Fraction, origin: tuple[float, float] = ORIGIN[:2],
) -> tuple[int, int] | None:
    """The documented escape cell from the float start point, in exact arithmetic."""
    x, y = (Fraction(float(v)) for v in start)
    q = ((y - Fraction(origin[1])) / Fraction(RES) - Fraction(1, 2),
         (x - Fraction(origin[0])) / Fraction(RES) - Fraction(1, 2))
    reach = (Fraction(tolerance) / Fraction(RES)) ** 2
    squares = [(int(r), int(c)) for r, c in np.argwhere(hard)]
    candidates = sorted(
        ((r - q[0]) ** 2 + (c - q[1]) ** 2, int(r), int(c))
        for r, c in np.argwhere(np.isfinite(costs))
        if (r - q[0]) ** 2 + (c - q[1]) ** 2 <= reach
    )
    for _, r, c in candidates:
        if not any(touches(q, (r, c), s, grow) for s in squares):
            return r, c
    return None


def centre_of(grid: OccupancyGrid, cell: tuple[int, int]) -> tuple[float, float]:
    x, y = grid.cell_to_world(cell)
    return float(x), float(y)


# (map rows, goal cell, tolerance in cells, what navkit does, escape with no margin)
CASES = [
    (7, (4, 9), 5.0, "unreachable from (2, 2)", (6, 7)),
    (7, (0, 4), 5.0, "escape (2, 2)", (6, 7)),
    (6, (0, 4), 5.0, "escape (2, 2)", (2, 3)),
    (6, (0, 4), 4.0, "nothing within", (2, 3)),
    (6, (0, 0), 4.0, "nothing within", (2, 3)),
]


@pytest.mark.parametrize(("rows", "goal_cell", "cells", "outcome", "no_margin"), CASES)
def test_the_five_hypothesis_failures(
    rows: int, goal_cell: tuple[int, int], cells: float, outcome: str,
    no_margin: tuple[int, int],
) -> None:
    grid, costs, planner = scene(rows)
    hard = grid.occupied()
    # The start hypothesis drew, as the property test builds it.
    start = planner.node_to_world((4 + FRACTION, 5 + FRACTION))
    assert start.tolist() == list(START)
    goal = np.array(centre_of(grid, goal_cell))
    tolerance = cells * RES
    # Without the margin the nearer centre would qualify: its segment misses an
    # obstacle's corner by about 1e-16 cells (not touching it, exactly) ...
    assert exact_escape(costs, hard, START, tolerance, Fraction(0)) == no_margin
    assert exact_escape(costs, hard, START, tolerance, Fraction(1, 10**15)) != no_margin
    # ... with it, the documented rule, the escape is navkit's.
    want = exact_escape(costs, hard, START, tolerance, MARGIN)
    if outcome == "nothing within":
        assert want is None
        with pytest.raises(ValueError, match=r"\(4, 5\) .* no passable cell centre within "
                           r"start_tolerance \(0\.5 m\)"):
            planner.plan_world(START, goal, start_tolerance=tolerance)
        return
    assert want == (2, 2)
    if outcome.startswith("unreachable"):
        with pytest.raises(NoPathError, match=r"\(escaped to cell \(2, 2\)\) to goal_xy "):
            planner.plan_world(START, goal, start_tolerance=tolerance)
        return
    path = planner.plan_world(START, goal, start_tolerance=tolerance)
    assert path.points[0].tolist() == list(START)
    assert path.points[1].tolist() == [-0.6875, 2.3125]  # the centre of cell (2, 2)
    rest = FieldDStar(costs, resolution=RES, origin=ORIGIN, obstacles=hard).plan_world(
        path.points[1], goal
    )
    np.testing.assert_array_equal(path.points[1:], rest.points)


@pytest.mark.parametrize("backend", ["astar", "field_dstar"])
@pytest.mark.parametrize(("rows", "cells"), [(7, 5.0), (6, 5.0), (6, 4.0)])
def test_map_planner_shares_the_escape_and_its_margin(
    backend: str, rows: int, cells: float
) -> None:
    grid, _, planner = scene(rows)
    mp = MapPlanner(grid, robot_radius=RES, planner=backend)
    goal = centre_of(grid, (2, 4))
    if cells == 4.0:
        with pytest.raises(ValueError, match="no passable cell centre within"):
            mp.plan(START, goal, start_tolerance=cells * RES)
        return
    got = mp.plan(START, goal, start_tolerance=cells * RES)
    assert got.points[1].tolist() == list(centre_of(grid, (2, 2)))
    field = planner.plan_world(START, goal, start_tolerance=cells * RES)
    assert field.points[1].tolist() == got.points[1].tolist()


@pytest.mark.parametrize(("offset", "escape"), [(0.0, None), (1e-10, None), (1e-8, (3, 7))])
def test_the_margin_is_a_billionth_of_a_cell(offset: float, escape: tuple[int, int] | None) -> None:
    # An obstacle at (4, 7), free cells (3, 7) and (5, 7) beyond its corners, the
    # start in band cell (4, 6) moved by ``offset`` cells up-left off the diagonal
    # through the corner (3.5, 6.5): the segment to (3, 7) misses that corner by
    # about ``offset`` cells. (5, 7) stays behind the corner (4.5, 6.5). MapPlanner
    # runs the same search (the test above), on costs it builds itself.
    hard = np.zeros((10, 10), dtype=bool)
    hard[4, 7] = True
    costs = np.ones((10, 10))
    costs[2:7, 4:7] = np.inf  # band cells, not obstacles
    costs[4, 7] = np.inf
    start = ((6.5 - offset) * RES, (4.5 - offset) * RES)
    tolerance = 0.2
    assert exact_escape(costs, hard, start, tolerance, MARGIN, origin=(0.0, 0.0)) == escape
    planner = FieldDStar(costs, resolution=RES, obstacles=hard)
    goal = (1.1875, 1.1875)
    if escape is None:
        with pytest.raises(ValueError, match="no passable cell centre within"):
            planner.plan_world(start, goal, start_tolerance=tolerance)
    else:
        got = planner.plan_world(start, goal, start_tolerance=tolerance).points[1]
        assert got.tolist() == [0.9375, 0.4375]  # the centre of cell (3, 7)
