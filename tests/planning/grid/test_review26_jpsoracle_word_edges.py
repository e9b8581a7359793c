"""Jump point search against a cell-by-cell reference, where the bit scans cross 64-cell words.

Review 26. The JPS kernels find jump points 64 cells at a time in bit rows
(:func:`navkit.planning.grid._jps_kernels._scan_line`): the side rows'
words are shifted by one cell, each borrowing the edge bit of its
neighbouring word. A mistake there (the edge bit dropped, taken from the
wrong word or bit, shifted the wrong way) adds or loses jump points only
at the word edges, which on the earlier tests' maps changed no path cost:
every cost and path test still passed.

So these tests compare every search's *whole state* with a reference that
applies the documented rules one cell at a time, with no bit tables:
Harabor and Grastien's successor rules without corner cutting (MovingAI's
graph, the variant of :mod:`~navkit.planning.grid._jps_kernels`) and with
it (the 2011 rules, :mod:`~navkit.planning.grid._jps_cut_kernels`),
including the kernels' documented shortcuts (one-cell corridor corners
passed through; diagonal jump points of the second kind recorded, not
queued). The kernels are run directly, every argument explicit, on fresh
records, and must give the reference's expansion count, the set of nodes
reached and closed, and each reached node's cost (bit for bit), parent and
arrival direction; the public planner must report the same expansion
count and path. An extra or lost jump point anywhere shows, queued or not.

The queue order is reproduced too (f with its lowest ``F_TIE_BITS`` bits
cleared below ``F_BAND_COSTS``, review 40, then the tie key of
:func:`~navkit.planning.grid._search_heap.tie_key`: a total order, so a
binary heap pops in the kernels' order), since which parent reaches a node
first decides its arrival direction and so its successors. A change to the
kernels' queue or shortcuts that keeps their costs exact will need the
reference updated with it: that is the point of pinning their expansions.

Grids are 1-6 cells by 63, 64, 65, 127, 128 or 129 (the padded lines then
end just before, at or just after a word edge), either way round (the
row and the column tables), with obstacles, walls and ends in columns
62-66 and 126-130, where a padded position crosses a word; and, exhaustively,
every blocked / free pattern of the four side cells around a word edge.

Checked against 14 mutants of the edge handling in ``_scan_line`` and
``_free`` (edge bit dropped or forced free, borrowed from the wrong word,
bit or direction; ``_free``'s word and the scan's first word off by one at
the edge): the default run of this file kills all 14, in the search(es)
each one changes. The other JPS tests kill the 10 that lose jump points
(costs change) but none of the 4 that only add jump points in one scan
direction, except a no-corner-cutting east one, by the expansion bound on
an open grid.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner
from navkit.planning.grid._jps_cut_kernels import jps_cut_search
from navkit.planning.grid._jps_kernels import jps_search, jps_tables
from navkit.planning.grid._search_heap import F_BAND, F_BAND_COSTS

SQRT2 = math.sqrt(2.0)
OCTILE_EXTRA = SQRT2 - 1.0

# Directions as the kernels number them: N, S, W, E, NW, NE, SW, SE.
DIRS = ((-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1))
INDEX = {d: k for k, d in enumerate(DIRS)}

WIDTHS = (63, 64, 65, 127, 128, 129)
# Cells whose padded position (cell + 1) is 63-67 or 127-131: each side of a word edge.
EDGE_CELLS = (62, 63, 64, 65, 66, 126, 127, 128, 129, 130)

Cell = tuple[int, int]


@dataclass
class Outcome:
    """What a search did: the kernels' results and node records, in plain Python."""

    expanded: int
    found: bool
    closed: set[int] = field(default_factory=set)
    # Node -> (cost from the start, parent node or -1, arrival direction or -1).
    records: dict[int, tuple[float, int, int]] = field(default_factory=dict)
    cells: list[Cell] = field(default_factory=list)


class Reference:
    """Jump point search one cell at a time, as the kernels' docstrings describe it."""

    def __init__(self, free: np.ndarray, cutting: bool) -> None:
        self.free_cells = free.tolist()
        self.rows, self.cols = free.shape
        self.cutting = cutting
        # The kernels' tie resolution: 1/16 cell unless rows + cols >= 2**17, where
        # it halves until every tie (h < rows + cols) stays below 2**21 (review 38).
        self.tie_resolution = 16.0
        while self.tie_resolution * (self.rows + self.cols) >= 2.0**21:
            self.tie_resolution *= 0.5
        # Per search: the goal, node records, open and closed nodes, queue.
        self.goal: Cell = (-1, -1)
        self.records: dict[int, tuple[float, int, int]] = {}
        self.opened: set[int] = set()
        self.closed: set[int] = set()
        self.heap: list[tuple[float, float, int]] = []

    def free(self, r: int, c: int) -> bool:
        return 0 <= r < self.rows and 0 <= c < self.cols and bool(self.free_cells[r][c])

    # --------------------------------------------------------------------- the rules

    def forced_straight(self, r: int, c: int, dr: int, dc: int) -> bool:
        """Whether a straight scan (dr, dc) stops at (r, c) for a forced side neighbour."""
        for sr, sc in ((dc, dr), (-dc, -dr)):
            if self.cutting:
                # A blocked side cell whose cell ahead is free.
                if not self.free(r + sr, c + sc) and self.free(r + sr + dr, c + sc + dc):
                    return True
            elif self.free(r + sr, c + sc) and not self.free(r + sr - dr, c + sc - dc):
                # A free side cell whose cell behind is blocked.
                return True
        return False

    def scan(self, r: int, c: int, k: int, goal: Cell) -> int | None:
        """Steps from (r, c) along straight direction k to the goal or a jump point; None: wall."""
        dr, dc = DIRS[k]
        steps = 0
        while True:
            r += dr
            c += dc
            steps += 1
            if not self.free(r, c):
                return None
            if (r, c) == goal or self.forced_straight(r, c, dr, dc):
                return steps

    def successors(self, r: int, c: int, d: int) -> list[int]:
        """Directions to scan from (r, c) reached by move d (-1: the start), ascending."""
        if d < 0:
            return list(range(8))
        dr, dc = DIRS[d]
        if d >= 4:
            out = {INDEX[(dr, 0)], INDEX[(0, dc)], d}
            if self.cutting:
                if not self.free(r, c - dc) and self.free(r + dr, c - dc):
                    out.add(INDEX[(dr, -dc)])
                if not self.free(r - dr, c) and self.free(r - dr, c + dc):
                    out.add(INDEX[(-dr, dc)])
            return sorted(out)
        out = {d}
        for sr, sc in ((dc, dr), (-dc, -dr)):
            if self.cutting:
                if not self.free(r + sr, c + sc) and self.free(r + sr + dr, c + sc + dc):
                    out.add(INDEX[(dr + sr, dc + sc)])
            elif self.free(r + sr, c + sc) and not self.free(r + sr - dr, c + sc - dc):
                out |= {INDEX[(sr, sc)], INDEX[(dr + sr, dc + sc)]}
        return sorted(out)

    def diagonal_forced(self, r: int, c: int, dr: int, dc: int) -> bool:
        """Corner cutting: whether (r, c), reached diagonally, has a forced neighbour."""
        return (not self.free(r, c - dc) and self.free(r + dr, c - dc)) or (
            not self.free(r - dr, c) and self.free(r - dr, c + dc)
        )

    def jump_diagonal(self, r: int, c: int, k: int, goal: Cell) -> int | None:
        """Without corner cutting: diagonal steps to the next jump point; None: wall."""
        dr, dc = DIRS[k]
        steps = 0
        while True:
            nr, nc = r + dr, c + dc
            if not (self.free(nr, nc) and self.free(nr, c) and self.free(r, nc)):
                return None
            r, c = nr, nc
            steps += 1
            if (r, c) == goal:
                return steps
            if self.scan(r, c, INDEX[(0, dc)], goal) is not None:
                return steps
            if self.scan(r, c, INDEX[(dr, 0)], goal) is not None:
                return steps

    # -------------------------------------------------------------------- the search

    def flat(self, cell: Cell) -> int:
        return cell[0] * self.cols + cell[1]

    def reach(self, v: Cell, g: float, parent: Cell, k: int) -> bool:
        """Record ``v`` reached at cost g from ``parent`` by move k, unless no cheaper."""
        i = self.flat(v)
        if i in self.closed or (i in self.opened and g >= self.records[i][0]):
            return False
        self.opened.add(i)
        self.records[i] = (g, self.flat(parent), k)
        return True

    def push(self, v: Cell, g: float) -> None:
        """Queue ``v`` by f = g + octile h, banded, then the kernels' tie key (h to 1/16, node)."""
        adr, adc = abs(v[0] - self.goal[0]), abs(v[1] - self.goal[1])
        h = max(adr, adc) + OCTILE_EXTRA * min(adr, adc)
        key = math.floor(h * self.tie_resolution) * float(2**32) + self.flat(v)
        heapq.heappush(self.heap, (self.queued_f(g + h), key, self.flat(v)))

    @staticmethod
    def queued_f(f: float) -> float:
        """f as the kernels queue it: lowest ``F_TIE_BITS`` bits cleared below ``F_BAND_COSTS``."""
        if f >= F_BAND_COSTS:
            return f
        return float((np.float64(f).view(np.uint64) & F_BAND).view(np.float64))

    @staticmethod
    def along(u: Cell, k: int, steps: int) -> Cell:
        return (u[0] + steps * DIRS[k][0], u[1] + steps * DIRS[k][1])

    def corridor(self, v: Cell, k: int) -> Cell | None:
        """The node to queue for the straight jump point ``v`` reached by move k; None: none.

        With the cell ahead blocked and exactly one forced side, ``v``'s only
        successor is the straight scan along that side: the kernels follow it at once.
        """
        while v != self.goal:
            if self.free(*self.along(v, k, 1)):
                return v
            turns = [j for j in self.successors(*v, k) if j < 4 and j != k]
            if len(turns) != 1:
                return v
            k = turns[0]
            steps = self.scan(*v, k, self.goal)
            if steps is None:
                return None
            w = self.along(v, k, steps)
            if not self.reach(w, self.records[self.flat(v)][0] + steps, v, k):
                return None
            v = w
        return v

    def expand(self, u: Cell, gu: float, d: int) -> None:
        """Scan from ``u`` (cost gu, reached by move d) without corner cutting."""
        for k in self.successors(*u, d):
            if k < 4:
                steps = self.scan(*u, k, self.goal)
                if steps is None:
                    continue
                g = gu + steps
            else:
                steps = self.jump_diagonal(*u, k, self.goal)
                if steps is None:
                    continue
                g = gu + SQRT2 * steps
            v = self.along(u, k, steps)
            if not self.reach(v, g, u, k):
                continue
            if k < 4 and v != self.goal and not self.free(*self.along(v, k, 1)):
                w = self.corridor(v, k)
                if w is None:
                    continue
                v = w
                g = self.records[self.flat(v)][0]
            self.push(v, g)

    def expand_cutting(self, u: Cell, gu: float, d: int) -> None:
        """Scan from ``u`` (cost gu, reached by move d) with corner cutting."""

        def add_on_line(z: Cell, k: int, steps: int, gz: float) -> None:
            v = self.along(z, k, steps)
            if self.reach(v, gz + steps, z, k):
                self.push(v, gz + steps)

        for k in self.successors(*u, d):
            if k < 4:
                steps = self.scan(*u, k, self.goal)
                if steps is not None:
                    add_on_line(u, k, steps, gu)
                continue
            dr, dc = DIRS[k]
            kh, kv = INDEX[(0, dc)], INDEX[(dr, 0)]
            parent = u
            z = u
            steps = 0
            while True:
                z = (z[0] + dr, z[1] + dc)
                if not self.free(*z):
                    break
                steps += 1
                gz = gu + SQRT2 * steps
                if z == self.goal or self.diagonal_forced(*z, dr, dc):
                    if self.reach(z, gz, parent, k):
                        self.push(z, gz)
                    break
                xh = self.scan(*z, kh, self.goal)
                xv = self.scan(*z, kv, self.goal)
                if xh is None and xv is None:
                    continue
                # A jump point only for its straight scans: recorded, not
                # queued; its straight successors are queued at once.
                if not self.reach(z, gz, parent, k):
                    break
                parent = z
                for kk, x in ((kh, xh), (kv, xv)):
                    if x is not None:
                        add_on_line(z, kk, x, gz)

    def search(self, start: Cell, goal: Cell) -> Outcome:
        """A* over the jump points from ``start`` to ``goal``, in the kernels' order."""
        self.goal = goal
        self.records = {self.flat(start): (0.0, -1, -1)}
        self.opened = set()
        self.closed = set()
        self.heap = []
        expanded = 0
        u = start
        while u != goal:
            self.closed.add(self.flat(u))
            expanded += 1
            gu, _, d = self.records[self.flat(u)]
            (self.expand_cutting if self.cutting else self.expand)(u, gu, d)
            while self.heap:
                _, _, i = heapq.heappop(self.heap)
                if i not in self.closed:
                    u = divmod(i, self.cols)
                    break
            else:
                return Outcome(expanded, False, self.closed, self.reached())
        cells = [goal]
        i = self.flat(goal)
        while self.records[i][1] >= 0:
            parent = self.records[i][1]
            pr, pc = divmod(parent, self.cols)
            r, c = cells[-1]
            sr, sc = (pr > r) - (pr < r), (pc > c) - (pc < c)
            while (r, c) != (pr, pc):
                r, c = r + sr, c + sc
                cells.append((r, c))
            i = parent
        return Outcome(expanded + 1, True, self.closed, self.reached(), cells[::-1])

    def reached(self) -> dict[int, tuple[float, int, int]]:
        """Records of the nodes reached or closed (the start's only once expanded)."""
        return {v: rec for v, rec in self.records.items() if v in self.opened or v in self.closed}


def kernel_outcome(costs: np.ndarray, start: Cell, goal: Cell, cutting: bool) -> Outcome:
    """Run the JPS kernel on fresh records and read back what it did."""
    rows, cols = costs.shape
    n = rows * cols
    row_bits, col_bits, _, _ = jps_tables(costs)
    records = np.zeros(2 * n, dtype=np.float64)
    meta = records.view(np.int32)
    blocks = np.zeros(3 * ((n + 63) // 64), dtype=np.int64)
    heap = np.empty(2 * (16 * n + 64), dtype=np.float64)  # never fills on these grids
    search = jps_cut_search if cutting else jps_search
    expanded, found, k, _ = search(
        row_bits,
        col_bits,
        rows,
        cols,
        start[0] * cols + start[1],
        goal[0] * cols + goal[1],
        records,
        meta,
        blocks,
        heap,
        1,
    )
    assert found in (0, 1)
    out = Outcome(int(expanded), bool(found))
    for v in range(n):
        b = 3 * (v >> 6)
        if blocks[b] != 1:
            continue
        bit = 1 << (v & 63)
        if int(blocks[b + 2]) & bit:
            out.closed.add(v)
        if (int(blocks[b + 1]) | int(blocks[b + 2])) & bit:
            out.records[v] = (float(records[2 * v]), int(meta[4 * v + 2]), int(meta[4 * v + 3]))
    if found:
        out.cells = [(int(r), int(c)) for r, c in heap[: 2 * k].reshape(k, 2)]
    return out


def check_against_reference(costs: np.ndarray, start: Cell, goal: Cell, cutting: bool) -> None:
    want = Reference(np.isfinite(costs), cutting).search(start, goal)
    got = kernel_outcome(costs, start, goal, cutting)
    assert (got.expanded, got.found) == (want.expanded, want.found)
    # Nodes the reference reached that the kernel did not, and the reverse: a
    # lost or extra jump point (queued or not) shows here even when the path
    # and its cost do not change.
    cols = costs.shape[1]
    missing = sorted(divmod(v, cols) for v in want.records.keys() - got.records.keys())
    extra = sorted(divmod(v, cols) for v in got.records.keys() - want.records.keys())
    assert (missing, extra) == ([], [])
    assert got.closed == want.closed
    assert got.records == want.records
    assert got.cells == want.cells
    # The public planner reports the same search.
    planner = AStarPlanner(costs, method="jps", corner_cutting=cutting)
    if want.found:
        path = planner.plan(start, goal)
        assert path.expanded == want.expanded
        assert [tuple(cell) for cell in path.cells.tolist()] == want.cells
    else:
        with pytest.raises(NoPathError) as info:
            planner.plan(start, goal)
        assert info.value.expanded == want.expanded


# ------------------------------------------------------------------ the reference itself


def test_reference_reproduces_hand_worked_searches() -> None:
    # The reference must not share a mistake with the kernels unnoticed: two
    # searches worked out by hand from the rules.
    # 3 x 5, one pillar at (0, 2); from (1, 0) to (1, 4), no corner cutting.
    costs = np.ones((3, 5))
    costs[0, 2] = np.inf
    out = Reference(np.isfinite(costs), cutting=False).search((1, 0), (1, 4))
    # The start scans all eight ways and finds one jump point: east, (1, 3),
    # whose north side cell (0, 3) is free with (0, 2) behind it blocked.
    # Expanding it reaches the goal one step east: three expansions, the
    # goal's included.
    assert out.records[1 * 5 + 3] == (3.0, 1 * 5 + 0, 3)
    assert out.found and out.expanded == 3
    assert out.cells == [(1, 0), (1, 1), (1, 2), (1, 3), (1, 4)]
    # With corner cutting the east scan stops one cell earlier, at (1, 2):
    # its north side cell (0, 2) is blocked and the one ahead of it free.
    out = Reference(np.isfinite(costs), cutting=True).search((1, 0), (1, 4))
    assert out.records[1 * 5 + 2] == (2.0, 1 * 5 + 0, 3)
    assert out.found and out.expanded == 3


@pytest.mark.parametrize("cutting", [False, True])
@pytest.mark.parametrize("edge", [63, 127])
def test_every_side_row_pattern_at_a_word_edge(edge: int, cutting: bool) -> None:
    # Cells edge - 2 .. edge + 1 of a side row are bits 62, 63 of one word and
    # 0, 1 of the next (cell c is padded position c + 1): the scans along the
    # middle row borrow one of them across the edge. Every blocked / free
    # pattern of the four, scans starting at and beside the edge, both ways
    # along the rows and (transposed) the columns.
    width = 131
    for pattern in range(16):
        costs = np.ones((3, width))
        for i in range(4):
            if pattern >> i & 1:
                costs[0, edge - 2 + i] = np.inf
        for c in (0, edge - 2, edge - 1, edge, edge + 1, width - 1):
            for goal in ((2, 0), (2, width - 1)):
                check_against_reference(costs, (1, c), goal, cutting)
                check_against_reference(costs.T.copy(), (c, 1), goal[::-1], cutting)


@pytest.mark.parametrize("cutting", [False, True])
@pytest.mark.parametrize("width", WIDTHS)
def test_every_lone_obstacle_beside_a_word_edge(width: int, cutting: bool) -> None:
    # One blocked cell at every row and edge column of a 3-row grid whose
    # lines end before, at or after a word edge; scans both ways along the
    # rows and (transposed) the columns.
    for x in [c for c in EDGE_CELLS if c < width] + [width - 2, width - 1]:
        for r in range(3):
            costs = np.ones((3, width))
            costs[r, x] = np.inf
            for start, goal in (((1, 0), (0, width - 1)), ((1, width - 1), (2, 0))):
                for s, t in ((start, goal), (goal, start)):
                    if math.isfinite(costs[s]) and math.isfinite(costs[t]):
                        check_against_reference(costs, s, t, cutting)
                        check_against_reference(costs.T.copy(), s[::-1], t[::-1], cutting)


# ---------------------------------------------------------------------------- the grids


@st.composite
def word_edge_cases(draw: st.DrawFn) -> tuple[np.ndarray, Cell, Cell]:
    """A 1-6 x 63..129 grid (or its transpose) with features beside the words' edges.

    Random obstacles of some density, then blocked cells, short walls across
    the grid (with or without a gap) and free cells at the cells beside a
    word edge; the ends are drawn there half the time. A third of the goals
    are walled in, so the search reaches every jump point it can.
    """
    long = draw(st.sampled_from(WIDTHS))
    short = draw(st.sampled_from([2, 3, 4, 5, 6, 1]))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    blocked = rng.random((short, long)) < draw(st.sampled_from([0.1, 0.2, 0.3, 0.0]))
    edges = [x for x in EDGE_CELLS if x < long] + [long - 2, long - 1]
    for _ in range(draw(st.integers(0, 8))):
        x = int(rng.choice(edges))
        r = int(rng.integers(short))
        kind = draw(st.sampled_from(["cell", "wall", "gap", "free"]))
        if kind == "cell":
            blocked[r, x] = True
        elif kind == "free":
            blocked[r, x] = False
        else:
            blocked[:, x] = True
            if kind == "gap":
                blocked[r, x] = False
    free = np.argwhere(~blocked)
    if free.shape[0] == 0:
        blocked[0, 0] = False
        free = np.array([[0, 0]])
    near = free[np.isin(free[:, 1], edges)]

    def end() -> Cell:
        pool = near if near.shape[0] and draw(st.booleans()) else free
        i = draw(st.integers(0, pool.shape[0] - 1))
        return int(pool[i, 0]), int(pool[i, 1])

    start, goal = end(), end()
    if start != goal and draw(st.integers(0, 2)) == 0:
        r, c = goal
        blocked[max(r - 1, 0) : r + 2, max(c - 1, 0) : c + 2] = True
        blocked[goal] = False
        blocked[start] = False
    costs = np.where(blocked, np.inf, 1.0)
    if draw(st.booleans()):
        return costs.T.copy(), start[::-1], goal[::-1]
    return costs, start, goal


@pytest.mark.parametrize("cutting", [False, True])
@settings(max_examples=300, deadline=None)
@given(case=word_edge_cases())
def test_jps_search_is_the_reference_search_across_word_edges(
    case: tuple[np.ndarray, Cell, Cell], cutting: bool
) -> None:
    check_against_reference(*case, cutting)


test_jps_search_is_the_reference_search_across_word_edges_thoroughly = slow_twin(
    test_jps_search_is_the_reference_search_across_word_edges, max_examples=1500
)
