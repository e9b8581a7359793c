"""A*'s and jump point search's tie keys far from the goal (review 38, ASTARTIE).

Both searches break ties in f towards the smaller h, the heuristic distance to
the goal in cells, quantised to 1/16 of a cell, then towards the smaller node
id (:func:`~navkit.planning.grid._search_heap.tie_key_bits`, ``tie_key``).
Until review 38 the quantised tie saturated at ``2**20 - 1``: from 65,536
cells away from the goal every tie went by node id alone, which prefers the
grid's upper rows, so on a tall open grid with the goal at the bottom A*
expanded the plateau of equal f row by row down to 65,536 cells from the goal
(4-connected 70,000 x 16: 136,960 cells where the path has 70,015; 70,000 x
8: 101,248 for 70,007). The tie
now has as many bits as the key leaves (31 in A*'s integer keys, 21 in
JPS's float keys) at a resolution chosen per grid
(:func:`~navkit.planning.grid._search_heap.tie_resolution`: 1/16 cell on every
grid with ``rows + cols`` below 2**27, or 2**17 for JPS, and coarser by halves
on longer ones), so it never saturates.

The searches are checked against references written here (A*: heapq with the
priority ``(f, floor(16 h), node)`` in Python integers, which cannot saturate)
and, for JPS, against the cell-by-cell reference of
``test_review26_jpsoracle_word_edges`` (its tie key is the documented rule).
"""

from __future__ import annotations

import heapq
import math

import numpy as np
import pytest
from test_review26_jpsoracle_word_edges import check_against_reference

from navkit.planning import astar
from navkit.planning.grid._limits import MAX_NODES
from navkit.planning.grid._search_heap import (
    FLOAT_TIE_LIMIT,
    HEAP_TIE_LIMIT,
    TIE_RESOLUTION,
    node_of,
    tie_key,
    tie_key_bits,
    tie_resolution,
)

SQRT2 = math.sqrt(2.0)
MOVES = (
    (-1, 0, 1.0), (1, 0, 1.0), (0, -1, 1.0), (0, 1, 1.0),
    (-1, -1, SQRT2), (-1, 1, SQRT2), (1, -1, SQRT2), (1, 1, SQRT2),
)  # fmt: skip


def reference_astar(
    costs: np.ndarray,
    start: tuple[int, int],
    goal: tuple[int, int],
    eight: bool,
    corner_cutting: bool,
) -> tuple[int, float | None]:
    """(expanded, cost) of a lazy-deletion heapq A* with ties by (floor(16 h), node).

    The kernels' float arithmetic (move ``step * 0.5 * (c_u + c_v)``, octile or
    Manhattan h in cells, ``f = g + smallest cost * h``) and their documented
    total order, with the quantised tie a Python integer: no limit.
    """
    rows, cols = costs.shape
    flat = costs.ravel().tolist()
    scale = float(costs[np.isfinite(costs)].min())
    gr, gc = goal

    def h(r: int, c: int) -> float:
        dr, dc = abs(r - gr), abs(c - gc)
        if eight:
            return max(dr, dc) + (SQRT2 - 1.0) * min(dr, dc)
        return float(dr + dc)

    source = start[0] * cols + start[1]
    target = goal[0] * cols + goal[1]
    g = {source: 0.0}
    closed: set[int] = set()
    queue = [(scale * h(*start), math.floor(16 * h(*start)), source)]
    expanded = 0
    while queue:
        _, _, u = heapq.heappop(queue)
        if u in closed:
            continue
        closed.add(u)
        expanded += 1
        if u == target:
            return expanded, g[u]
        r, c = divmod(u, cols)
        for dr, dc, step in MOVES if eight else MOVES[:4]:
            r2, c2 = r + dr, c + dc
            if not (0 <= r2 < rows and 0 <= c2 < cols):
                continue
            v = r2 * cols + c2
            if v in closed or flat[v] == math.inf:
                continue
            if (
                dr
                and dc
                and not corner_cutting
                and (flat[(r + dr) * cols + c] == math.inf or flat[r * cols + c + dc] == math.inf)
            ):
                continue
            new_g = g[u] + step * 0.5 * (flat[u] + flat[v])
            if new_g >= g.get(v, math.inf):
                continue
            g[v] = new_g
            hv = h(r2, c2)
            heapq.heappush(queue, (new_g + scale * hv, math.floor(16 * hv), v))
    return expanded, None


# --- the searches ----------------------------------------------------------------


@pytest.mark.parametrize(
    ("shape", "connectivity", "corner_cutting", "straight"),
    [
        # Path cells: rows + cols - 1 (4-connected), rows (8-connected, rows > cols).
        # Before review 38 (downhill): 101,248 / 74,463 / 74,463 expanded.
        ((70_000, 8), 4, True, 70_007),
        ((70_000, 8), 8, True, 70_000),
        ((70_000, 8), 8, False, 70_000),
    ],
)
@pytest.mark.parametrize("downhill", [True, pytest.param(False, marks=pytest.mark.slow)])
def test_tall_open_grid_expands_the_path_alone_as_ties_towards_the_goal_do(
    shape: tuple[int, int], connectivity: int, corner_cutting: bool, straight: int, downhill: bool
) -> None:
    # Start at the top, goal at the bottom (downhill) or the reverse: every
    # cell between them is on the plateau of equal f, and only ties towards
    # the goal keep A* on one path through it (node ids favour the top rows).
    rows, cols = shape
    costs = np.ones(shape)
    start, goal = ((0, 0), (rows - 1, cols - 1)) if downhill else ((rows - 1, cols - 1), (0, 0))
    eight = connectivity == 8
    expected, expected_cost = reference_astar(costs, start, goal, eight, corner_cutting)
    assert expected == straight  # ties towards the goal: no cell off the path
    path = astar(costs, start, goal, connectivity=connectivity, corner_cutting=corner_cutting)
    assert path.expanded == expected
    assert len(path.cells) == straight
    assert path.cost == expected_cost


@pytest.mark.parametrize(
    ("shape", "density", "cutting"),
    [
        # Before review 38: 366 and 470 jump points expanded, other nodes reached.
        ((70_000, 4), 0.2, True),
        ((70_000, 8), 0.2, False),
        pytest.param((70_000, 8), 0.1, True, marks=pytest.mark.slow),  # found, 111,550
    ],
)
def test_jump_point_search_far_from_the_goal_is_the_reference_search(
    shape: tuple[int, int], density: float, cutting: bool
) -> None:
    rng = np.random.default_rng(3)
    costs = np.ones(shape)
    costs[rng.random(shape) < density] = np.inf
    start, goal = (0, 0), (shape[0] - 1, shape[1] - 1)
    costs[start] = costs[goal] = 1.0
    # Every node's cost, parent and arrival direction, the closed set and the
    # expansion count, against a reference whose ties never saturate.
    check_against_reference(costs, start, goal, cutting)


# --- the keys ----------------------------------------------------------------------

SHAPES = [
    (1, 1),
    (1024, 1024),
    (46_340, 46_340),  # the largest square grid
    (70_000, 16),
    (65_536, 65_535),  # rows + cols = 2**17 - 1: JPS's last 1/16
    (65_536, 65_536),
    (8, 2**27 - 9),  # rows + cols = 2**27 - 1: A*'s last 1/16
    (8, 2**27 - 8),
    (3, 2**29),
    (1, MAX_NODES),
]


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("limit", [HEAP_TIE_LIMIT, FLOAT_TIE_LIMIT])
def test_tie_resolution_is_the_finest_that_fits_every_tie_of_the_grid(
    shape: tuple[int, int], limit: float
) -> None:
    rows, cols = shape
    resolution = tie_resolution(rows, cols, limit)
    assert resolution <= TIE_RESOLUTION
    assert math.frexp(resolution)[0] == 0.5  # a power of two: resolution * h exact
    span = rows + cols  # above every h of the grid, octile or Manhattan
    assert resolution * span < limit
    assert resolution == TIE_RESOLUTION or 2 * resolution * span >= limit
    # The largest key either queue can hold on the grid: exact and below its bound.
    node = rows * cols - 1
    top_h = float(max(rows, cols) - 1) + (SQRT2 - 1.0) * float(min(rows, cols) - 1)
    if limit == HEAP_TIE_LIMIT:
        key = int(tie_key_bits(top_h, node, resolution))
        assert key == math.floor(resolution * top_h) << 32 | node
        assert key < 2**63
    else:
        fkey = float(tie_key(top_h, node, resolution))
        assert fkey == math.floor(resolution * top_h) * 2**32 + node < 2**53
        assert node_of(fkey) == node


def test_sixteenth_of_a_cell_up_to_the_documented_spans() -> None:
    assert tie_resolution(8, 2**27 - 9, HEAP_TIE_LIMIT) == 16.0
    assert tie_resolution(8, 2**27 - 8, HEAP_TIE_LIMIT) == 8.0
    assert tie_resolution(65_536, 65_535, FLOAT_TIE_LIMIT) == 16.0
    assert tie_resolution(65_536, 65_536, FLOAT_TIE_LIMIT) == 8.0


@pytest.mark.parametrize("h", [65_535.9, 65_535.9375, 65_536.0, 65_536.0625, 1e6, 2.0**26])
def test_keys_keep_ordering_by_h_past_the_old_saturation(h: float) -> None:
    # 16 h reached 2**20 - 1 at h = 65,535.9375: past it every key had the same tie.
    nearer = h - 1.0 / 16
    for resolution in (16.0, tie_resolution(70_000, 16, FLOAT_TIE_LIMIT)):
        below = int(tie_key_bits(nearer, 2**32 - 1, resolution))
        assert below < int(tie_key_bits(h, 0, resolution))
        if h < FLOAT_TIE_LIMIT / resolution:
            assert tie_key(nearer, 2**32 - 1, resolution) < tie_key(h, 0, resolution)
