"""FieldDStar.plan_cells walks every start corner tied at the least cost-to-goal.

The docstring: start corners whose cost-to-goal ties the least are all walked and
the cheapest linked path kept. Here a short wall stands between the start cell and
the goal cell; the start cell's two corners facing the goal tie in cost-to-goal
(checked through the public node API), but the walk from the first of them goes
around the wall's dearer end. Walking only that corner gave a path 0.44 cells
longer than the shortest one; the shortest is computed independently as the
taut string around the wall (a visibility graph over the wall's corners: with
unit costs a path's cost is its length, and no path is shorter).
"""

from __future__ import annotations

import heapq
import itertools
import math

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.planning import FieldDStar

N = 7  # grid side
WALL = (4, 1, 3)  # row 4, columns 1 and 2 (half-open)
START, GOAL = (6, 2), (0, 1)
CORNERS = [(0, 0), (0, 1), (1, 0), (1, 1)]


def variant(turn: int) -> tuple[NDArray[np.float64], tuple[int, int], tuple[int, int]]:
    """The wall grid transposed (bit 0), flipped upside down (bit 1), left-right (bit 2)."""
    costs = np.ones((N, N))
    row, c0, c1 = WALL
    costs[row, c0:c1] = np.inf
    s, g = START, GOAL
    if turn & 1:
        costs, s, g = costs.T, (s[1], s[0]), (g[1], g[0])
    if turn & 2:
        costs, s, g = costs[::-1], (N - 1 - s[0], s[1]), (N - 1 - g[0], g[1])
    if turn & 4:
        costs, s, g = costs[:, ::-1], (s[0], N - 1 - s[1]), (g[0], N - 1 - g[1])
    return np.ascontiguousarray(costs), s, g


def crosses_interior(
    p: tuple[float, float], q: tuple[float, float], box: tuple[float, ...]
) -> bool:
    """Whether segment pq passes through the open rectangle ``box`` (r0, r1, c0, c1)."""
    r0, r1, c0, c1 = box
    t_in, t_out = 0.0, 1.0
    for start, delta, lo, hi in ((p[0], q[0] - p[0], r0, r1), (p[1], q[1] - p[1], c0, c1)):
        if delta == 0.0:
            if not lo < start < hi:
                return False
            continue
        a, b = (lo - start) / delta, (hi - start) / delta
        t_in, t_out = max(t_in, min(a, b)), min(t_out, max(a, b))
    return t_in < t_out


def shortest_length(costs: NDArray[np.float64], s: tuple[int, int], g: tuple[int, int]) -> float:
    """Length of the shortest path between the two cell centres around the blocked cells.

    The blocked cells of these grids form one rectangle; the shortest path bends
    only at its corners (node coordinates: a cell (r, c) spans [r, r+1] x [c, c+1]).
    """
    rows, cols = np.nonzero(~np.isfinite(costs))
    box = (float(rows.min()), float(rows.max() + 1), float(cols.min()), float(cols.max() + 1))
    points = [(s[0] + 0.5, s[1] + 0.5), (g[0] + 0.5, g[1] + 0.5)]
    points += [(r, c) for r in box[:2] for c in box[2:]]
    best = [math.inf] * len(points)
    best[0] = 0.0
    queue = [(0.0, 0)]
    while queue:
        d, i = heapq.heappop(queue)
        if d > best[i]:
            continue
        for j in range(len(points)):
            if j != i and not crosses_interior(points[i], points[j], box):
                e = d + math.dist(points[i], points[j])
                if e < best[j]:
                    best[j] = e
                    heapq.heappush(queue, (e, j))
    return best[1]


# Four of the eight symmetries: each puts the cheaper end at a different corner pair of
# the start cell. (In the other four the first tied corner's walk is the cheaper one,
# and the greedy shortcut pass leaves the path slightly longer than the shortest.)
@pytest.mark.parametrize("turn", [0, 1, 2, 5])
def test_the_tied_corner_around_the_cheaper_end_of_the_wall_is_walked(turn: int) -> None:
    costs, s, g = variant(turn)
    # The tie: the start corners' least costs to the goal cell's corners (node API).
    planner = FieldDStar(costs, interpolate=False)
    to_goal = [
        min(planner.plan((s[0] + a, s[1] + b), (g[0] + i, g[1] + j)).cost for i, j in CORNERS)
        for a, b in CORNERS
    ]
    least = min(to_goal)
    assert sum(math.isclose(v, least, rel_tol=1e-12) for v in to_goal) == 2
    path = FieldDStar(costs, interpolate=False).plan_cells(s, g)
    want = shortest_length(costs, s, g)
    assert path.cost == pytest.approx(want, rel=1e-9)
    # The taut path around the wall's other end (the same length in every variant,
    # as in the untransformed grid: the centre (6.5, 2.5), the wall's corners (5, 1)
    # and (4, 1), the centre (0.5, 1.5)) is dearer: the choice of corner mattered.
    other = math.hypot(6.5 - 5, 2.5 - 1) + 1.0 + math.hypot(4 - 0.5, 1 - 1.5)
    assert other > want + 0.2
    np.testing.assert_array_equal(path.points[[0, -1]], [s, g])


def test_the_shortest_length_helper_on_an_open_line() -> None:
    # A straight, unobstructed line is its own shortest path (helper sanity check).
    costs = np.ones((5, 5))
    costs[0, 4] = np.inf
    assert shortest_length(costs, (4, 0), (1, 0)) == pytest.approx(3.0)
    assert all(
        not crosses_interior((0.5, 0.5), (4.5, 0.5), (a, a + 1.0, 4.0, 5.0))
        for a in itertools.islice(itertools.count(0.0), 5)
    )
