"""Field D*: geometry, optimality against exact any-angle paths, incremental repair, errors.

Paths come back in continuous cell coordinates (node (i, j) at (i - 0.5, j - 0.5));
the oracles work in node coordinates, where cell (r, c) covers [r, r+1] × [c, c+1],
so the tests add 0.5 to the points (:func:`nodes_of`).

The oracles here share no code with the planner: the path cost is integrated by
a plain-Python splitter, blocked-interior crossings are measured with shapely,
and exact any-angle shortest paths come from a visibility graph over the
blocked cells' convex corners (exact integer visibility test, Dijkstra from
scipy.sparse.csgraph).
"""

from __future__ import annotations

import math
from functools import partial
from itertools import pairwise

import numpy as np
import pytest
import scipy.sparse
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit
from numpy.typing import NDArray
from scipy.sparse.csgraph import dijkstra

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.geometry import Pose2D
from navkit.planning import FieldDStar, Path2D, field_dstar
from navkit.planning.grid import _field_dstar as field_dstar_module
from navkit.planning.grid._dstar_lite_kernels import corner_cost
from navkit.planning.grid._polyline_kernels import polyline_cost

FloatArray = NDArray[np.float64]
SQRT2 = math.sqrt(2.0)


# ----------------------------------------------------------------------------- oracles


def nodes_of(path: Path2D) -> FloatArray:
    """A grid path's points in node coordinates (cell (r, c) covers [r, r+1] × [c, c+1])."""
    assert path.frame == "grid"
    return path.points + 0.5


def true_cost(costs: FloatArray, points: FloatArray) -> float:
    """Integral of the cell cost along the polyline (plain Python, exact splitting).

    A piece running along a grid line pays the cheaper cell beside it; off-grid
    cells are impassable.
    """
    rows, cols = costs.shape

    def cell(r: int, c: int) -> float:
        if 0 <= r < rows and 0 <= c < cols:
            return float(costs[r, c])
        return math.inf

    total = 0.0
    for (r0, c0), (r1, c1) in pairwise(points.tolist()):
        ts = {0.0, 1.0}
        for a0, a1 in ((r0, r1), (c0, c1)):
            if a0 != a1:
                lo, hi = sorted((a0, a1))
                for line in range(math.ceil(lo), math.floor(hi) + 1):
                    ts.add((line - a0) / (a1 - a0))
        cuts = sorted(t for t in ts if 0.0 <= t <= 1.0)
        seg_len = math.hypot(r1 - r0, c1 - c0)
        for ta, tb in pairwise(cuts):
            piece = (tb - ta) * seg_len
            if piece < 1e-12:
                continue
            mr = r0 + 0.5 * (ta + tb) * (r1 - r0)
            mc = c0 + 0.5 * (ta + tb) * (c1 - c0)
            if r0 == r1 and float(r0).is_integer():
                cost = min(cell(int(r0) - 1, math.floor(mc)), cell(int(r0), math.floor(mc)))
            elif c0 == c1 and float(c0).is_integer():
                cost = min(cell(math.floor(mr), int(c0) - 1), cell(math.floor(mr), int(c0)))
            else:
                cost = cell(math.floor(mr), math.floor(mc))
            total += cost * piece
    return total


def blocked_union(costs: FloatArray) -> shapely.Geometry:
    rows, cols = np.nonzero(~np.isfinite(costs))
    if not rows.size:  # shapely 2.0's coverage union of no geometry warns (invalid value)
        return shapely.GeometryCollection()
    boxes = shapely.box(cols, rows, cols + 1.0, rows + 1.0)
    # Unit cells at integer corners: a coverage (edge to edge, never overlapping),
    # whose union GEOS builds ten times faster than unary_union's, the same geometry.
    # The GEOS of shapely 2.0 (the oldest supported) takes some such coverages for
    # overlapping and refuses them: unary_union then.
    try:
        return shapely.coverage_union_all(boxes)
    except shapely.errors.GEOSException:
        return shapely.unary_union(boxes)


def blocked_crossing_length(costs: FloatArray, points: FloatArray) -> float:
    """Length of the path inside the interior of the impassable cells (shapely, x=col)."""
    union = blocked_union(costs)
    if union.is_empty:
        return 0.0
    line = shapely.LineString(points[:, ::-1])
    # Pieces on the union's boundary (along an edge, through a corner) are allowed.
    inside = shapely.difference(shapely.intersection(line, union), union.boundary)
    return float(shapely.length(inside))


@njit(cache=True)
def _visible(blocked: NDArray[np.bool_], r0: int, c0: int, r1: int, c1: int) -> bool:
    """Exact (integer) test: the open segment between two nodes misses every blocked
    cell interior and never runs along an edge with blocked cells on both sides."""
    rows, cols = blocked.shape
    dr = r1 - r0
    dc = c1 - c0
    if dr == 0 or dc == 0:
        # Along a grid line: blocked only where the cells on both sides are.
        n = abs(dr) + abs(dc)
        for s in range(n):
            if dr == 0:
                r = r0
                c = min(c0, c1) + s
                up = r - 1 < 0 or blocked[r - 1, c]
                down = r >= rows or blocked[r, c]
            else:
                c = c0
                r = min(r0, r1) + s
                up = c - 1 < 0 or blocked[r, c - 1]
                down = c >= cols or blocked[r, c]
            if up and down:
                return False
        return True
    # Walk the column strips (c, c+1): the segment's open row range in the strip
    # is (ra, rb) with ra, rb rationals (num / dc); cell k is crossed iff k < rb
    # and k + 1 > ra.
    step = 1 if dc > 0 else -1
    adc = abs(dc)
    c = c0
    while c != c1:
        cl = min(c, c + step)
        # rows at both ends of the strip, times |dc| (exact integers)
        na = r0 * adc + (c - c0) * dr * step
        nb = r0 * adc + (c + step - c0) * dr * step
        lo = min(na, nb)
        hi = max(na, nb)
        k = lo // adc
        while k * adc < hi:
            if (k + 1) * adc > lo and 0 <= k < rows and blocked[k, cl]:
                return False
            k += 1
        c += step
    return True


def exact_shortest(costs: FloatArray, start: tuple[int, int], goal: tuple[int, int],
                   bound: float) -> float:
    """Shortest any-angle path length on a binary map (free cost 1).

    Visibility graph over start, goal and convex corners of the blocked cells
    (the only places a taut path bends); vertices and edges that cannot lie on a
    path shorter than ``bound`` (an upper bound, e.g. a planner's result) are
    pruned by the ellipse test |s-u| + |u-v| + |v-g| <= bound.
    """
    blocked = ~np.isfinite(costs)
    rows, cols = blocked.shape
    pad = np.ones((rows + 2, cols + 2), dtype=bool)
    pad[1:-1, 1:-1] = blocked
    nw = pad[:-1, :-1]
    ne = pad[:-1, 1:]
    sw = pad[1:, :-1]
    se = pad[1:, 1:]
    count = nw.astype(int) + ne + sw + se
    convex = (count == 1) | ((count == 2) & ((nw & se) | (ne & sw)))
    vi, vj = np.nonzero(convex)
    verts = np.unique(np.vstack([np.array([start, goal]), np.column_stack([vi, vj])]), axis=0)
    s = np.asarray(start, dtype=float)
    g = np.asarray(goal, dtype=float)
    vf = verts.astype(float)
    ds = np.hypot(*(vf - s).T)
    dg = np.hypot(*(vf - g).T)
    keep = ds + dg <= bound + 1e-9
    verts, vf, ds, dg = verts[keep], vf[keep], ds[keep], dg[keep]
    n = verts.shape[0]
    src: list[int] = []
    dst: list[int] = []
    w: list[float] = []
    for a in range(n):
        d = np.hypot(*(vf - vf[a]).T)
        useful = np.minimum(ds[a] + d + dg, ds + d + dg[a]) <= bound + 1e-9
        cand = np.nonzero(useful & (np.arange(n) > a))[0]
        for b in cand:
            if _visible(blocked, verts[a, 0], verts[a, 1], verts[b, 0], verts[b, 1]):
                src.append(a)
                dst.append(int(b))
                w.append(float(d[b]))
    graph = scipy.sparse.csr_matrix((w, (src, dst)), shape=(n, n))
    index = {tuple(v): k for k, v in enumerate(verts.tolist())}
    dist = dijkstra(graph, directed=False, indices=index[tuple(start)])
    return float(dist[index[tuple(goal)]])


def random_binary_map(rng: np.random.Generator, n: int, density: float) -> FloatArray:
    return np.where(rng.random((n, n)) < density, np.inf, 1.0)


def block_2x2(
    planner: FieldDStar, costs: FloatArray, at: shapely.Point
) -> tuple[list[tuple[int, int]], FloatArray]:
    """Block the 2 x 2 cells around the node-coordinate point ``at`` in the planner;
    returns those cells and a copy of ``costs`` with them blocked."""
    r, c = math.floor(at.x), math.floor(at.y)
    cells = [(r + dr, c + dc) for dr in (-1, 0) for dc in (-1, 0)]
    planner.update_costs(cells, np.inf)
    changed = costs.copy()
    for cell in cells:
        changed[cell] = np.inf
    return cells, changed


def free_node(
    rng: np.random.Generator, costs: FloatArray, near: tuple[int, int]
) -> tuple[int, int]:
    """A node close to ``near`` (random tie-break) touching at least one passable cell."""
    rows, cols = costs.shape
    pad = np.full((rows + 2, cols + 2), np.inf)
    pad[1:-1, 1:-1] = costs
    free = np.isfinite(pad)
    ok = free[:-1, :-1] | free[:-1, 1:] | free[1:, :-1] | free[1:, 1:]
    if not ok.any():
        raise AssertionError("no free node")
    ii, jj = np.indices(ok.shape)
    score = np.hypot(ii - near[0], jj - near[1]) + rng.random(ok.shape)
    score[~ok] = np.inf
    i, j = np.unravel_index(int(np.argmin(score)), ok.shape)
    return int(i), int(j)


def random_query(rng: np.random.Generator, n: int, density: float
                 ) -> tuple[FloatArray, tuple[int, int], tuple[int, int]]:
    costs = random_binary_map(rng, n, density)
    start = free_node(rng, costs, (int(rng.integers(0, n // 4)), int(rng.integers(0, n))))
    goal = free_node(rng, costs, (int(rng.integers(3 * n // 4, n)), int(rng.integers(0, n))))
    return costs, start, goal


# ----------------------------------------------------------------------- interpolation


@settings(max_examples=50, deadline=None)
@given(
    g2=st.floats(0.0, 50.0),
    f=st.floats(-3.0, 60.0),
    c=st.one_of(st.floats(1.0, 20.0), st.just(math.inf)),
    b=st.one_of(st.floats(1.0, 20.0), st.just(math.inf)),
)
def test_corner_cost_is_the_cheapest_path_through_the_cell(
    g2: float, f: float, c: float, b: float
) -> None:
    """Against brute force over the path family the formula optimises: a stretch x
    along the edge s-s1 (cost min(b, c)), then straight through c to the point y
    on the edge s1-s2 (interpolated cost-to-go), or along the edge all the way."""
    g1 = g2 + f
    got = corner_cost(g1, g2, c, b, True)
    edge = min(b, c)
    best = edge + g1
    if math.isfinite(c):
        x = np.linspace(0.0, 1.0, 801)[:, None]
        y = np.linspace(0.0, 1.0, 801)[None, :]
        family = edge * x + c * np.hypot(1.0 - x, y) + g2 + f * (1.0 - y)
        best = min(best, float(family.min()))
    assert got <= best + 1e-9 * (1.0 + abs(best))
    # ... and it is achievable: never below the exact continuous minimum.
    if math.isfinite(c):
        assert got >= best - 2e-3 * c
    else:
        assert got == best


test_corner_cost_is_the_cheapest_path_through_the_cell_thoroughly = slow_twin(
    test_corner_cost_is_the_cheapest_path_through_the_cell, max_examples=200
)


def test_corner_cost_matches_the_paper_where_its_branch_is_cheapest() -> None:
    # f <= b branch of Ferguson & Stentz with interior y.
    g1, g2, c, b = 10.4, 10.0, 1.5, 2.0
    f = g1 - g2
    y = f / math.sqrt(c * c - f * f)
    paper = c * math.sqrt(1 + y * y) + f * (1 - y) + g2
    assert corner_cost(g1, g2, c, b, True) == pytest.approx(paper, abs=1e-12)
    # f > b branch: along the cheap edge, then cut.
    g1, g2, c, b = 20.0, 10.0, 3.0, 1.0
    x = 1 - min(b / math.sqrt(c * c - b * b), 1.0)
    paper = c * math.sqrt(1 + (1 - x) ** 2) + b * x + g2
    assert corner_cost(g1, g2, c, b, True) == pytest.approx(paper, abs=1e-12)
    # g1 <= g2: along the edge at the cheaper cost.
    assert corner_cost(5.0, 7.0, 3.0, 2.0, True) == 7.0
    # The 8-connected mode keeps only the edge and the diagonal.
    assert corner_cost(10.4, 10.0, 1.5, 2.0, False) == 10.4 + 1.5
    assert corner_cost(13.0, 10.0, 1.5, 2.0, False) == pytest.approx(10.0 + 1.5 * SQRT2)


def test_corner_cost_keeps_the_edge_beside_an_impassable_cell() -> None:
    # The paper's formula gives inf here (c = inf with g1 > g2); the edge is open.
    assert corner_cost(12.0, 10.0, math.inf, 1.0, True) == 13.0


# ----------------------------------------------------------------------- empty maps


@settings(max_examples=40, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 30), st.integers(1, 30)),
    data=st.data(),
    cost=st.floats(1.0, 10.0),
)
def test_uniform_map_gives_the_straight_segment(
    shape: tuple[int, int], data: st.DataObject, cost: float
) -> None:
    rows, cols = shape
    node = st.tuples(st.integers(0, rows), st.integers(0, cols))
    start = data.draw(node)
    goal = data.draw(node)
    path = field_dstar(np.full(shape, cost), start, goal)
    dist = math.hypot(goal[0] - start[0], goal[1] - start[1])
    assert path.cost == pytest.approx(cost * dist, rel=1e-9, abs=1e-9)
    assert path.length == pytest.approx(dist, rel=1e-9, abs=1e-9)
    assert path.points[0].tolist() == [start[0] - 0.5, start[1] - 0.5]
    assert path.points[-1].tolist() == [goal[0] - 0.5, goal[1] - 0.5]
    assert path.points.shape == ((2, 2) if start != goal else (1, 2))


def test_heading_of_20_degrees_in_an_empty_map() -> None:
    # Goal at 20° from the row axis, far from any multiple of 45°.
    goal = (55, 20)
    assert math.degrees(math.atan2(goal[1], goal[0])) == pytest.approx(20.0, abs=0.05)
    costs = np.ones((70, 70))
    path = field_dstar(costs, (0, 0), goal, smooth=False)
    # Without smoothing the raw interpolated path already keeps the heading over
    # nearly all of its length (it wiggles a little in the last cells).
    steps = np.diff(path.points, axis=0)
    headings = np.degrees(np.arctan2(steps[:, 1], steps[:, 0]))
    lengths = np.hypot(steps[:, 0], steps[:, 1])
    assert lengths[np.abs(headings - 20.0) < 2.0].sum() > 0.9 * lengths.sum()
    smooth = field_dstar(costs, (0, 0), goal)
    assert nodes_of(smooth).tolist() == [[0.0, 0.0], [55.0, 20.0]]
    assert path.cost < 1.001 * math.hypot(*goal)
    octile = field_dstar(costs, (0, 0), goal, interpolate=False)
    moves = np.diff(octile.points, axis=0)
    assert set(np.round(np.degrees(np.arctan2(moves[:, 1], moves[:, 0]))).tolist()) <= {
        0.0, 45.0, 90.0}
    assert octile.cost > 1.03 * path.cost


# ----------------------------------------------------------------------- obstacles


def _octile_or_none(
    costs: FloatArray, start: tuple[int, int], goal: tuple[int, int]
) -> Path2D | None:
    """The 8-connected D* Lite path, or None if there is none (Field D* must agree)."""
    try:
        return field_dstar(costs, start, goal, interpolate=False)
    except NoPathError:
        with pytest.raises(NoPathError):
            field_dstar(costs, start, goal)
        return None


def _check_path(costs: FloatArray, path: Path2D, start: tuple[int, int],
                goal: tuple[int, int]) -> float:
    nodes = nodes_of(path)
    assert nodes[0].tolist() == list(map(float, start))
    assert nodes[-1].tolist() == list(map(float, goal))
    assert blocked_crossing_length(costs, nodes) < 1e-9
    cost = true_cost(costs, nodes)
    assert path.cost == pytest.approx(cost, rel=1e-9)
    return cost


def test_wall_detour_is_exact_and_legal() -> None:
    costs = np.ones((10, 10))
    costs[2:8, 4] = np.inf
    path = field_dstar(costs, (5, 0), (5, 10))
    _check_path(costs, path, (5, 0), (5, 10))
    # Taut path over the wall's end corners (2, 4) and (2, 5) (or the mirror image).
    assert path.cost == pytest.approx(math.hypot(3, 4) + 1 + math.hypot(3, 5), rel=1e-9)


def test_diagonal_gap_between_two_corners_is_passable() -> None:
    costs = np.ones((2, 2))
    costs[0, 0] = costs[1, 1] = np.inf
    path = field_dstar(costs, (0, 2), (2, 0))
    _check_path(costs, path, (0, 2), (2, 0))
    assert path.cost == pytest.approx(2 * SQRT2)


def test_random_maps_legal_and_within_bounds() -> None:
    """64×64 to 128×128 maps, 10-35 % blocked: legal paths, true cost never > 0.5 %
    above the 8-connected D* Lite path, median ratio to the exact shortest <= 1.02."""
    rng = np.random.default_rng(6)
    ratios_exact = []
    ratios_octile = []
    for n, density in [(64, 0.10), (64, 0.2), (64, 0.35), (96, 0.25), (128, 0.15), (128, 0.3)]:
        for _ in range(2):
            costs, start, goal = random_query(rng, n, density)
            octile = _octile_or_none(costs, start, goal)
            if octile is None:
                continue
            path = field_dstar(costs, start, goal)
            cost = _check_path(costs, path, start, goal)
            _check_path(costs, octile, start, goal)
            ratios_octile.append(cost / octile.cost)
            ratios_exact.append(cost / exact_shortest(costs, start, goal, cost))
    assert len(ratios_exact) >= 8
    assert max(ratios_octile) <= 1.005
    assert min(ratios_exact) >= 1.0 - 1e-9
    assert float(np.median(ratios_exact)) <= 1.02


@settings(max_examples=25, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(4, 24),
    density=st.floats(0.0, 0.4),
)
def test_small_binary_maps_legal_and_never_worse_than_8_connected(
    seed: int, n: int, density: float
) -> None:
    rng = np.random.default_rng(seed)
    costs = random_binary_map(rng, n, density)
    start = free_node(rng, costs, (0, 0))
    goal = free_node(rng, costs, (n, n))
    octile = _octile_or_none(costs, start, goal)
    if octile is None:
        return
    for options in ({}, {"smooth": False}, {"smooth": False, "lookahead": False}):
        path = field_dstar(costs, start, goal, **options)
        cost = _check_path(costs, path, start, goal)
        # Without lookahead (and smoothing) the raw path is occasionally a few
        # per cent above the 8-connected one: the bound holds with the lookahead.
        if options.get("lookahead", True):
            assert cost <= 1.005 * octile.cost
    exact = exact_shortest(costs, start, goal, octile.cost)
    assert exact - 1e-9 <= field_dstar(costs, start, goal).cost


test_small_binary_maps_legal_and_never_worse_than_8_connected_thoroughly = slow_twin(
    test_small_binary_maps_legal_and_never_worse_than_8_connected, max_examples=60
)


@pytest.mark.slow
def test_random_maps_sweep_up_to_256() -> None:
    """The quality bounds on 64-256 maps, 10-35 % blocked (3 queries per case)."""
    rng = np.random.default_rng(2026)
    ratios_exact = []
    for n in (64, 128, 192, 256):
        for density in (0.10, 0.20, 0.30, 0.35):
            for _ in range(3):
                costs, start, goal = random_query(rng, n, density)
                octile = _octile_or_none(costs, start, goal)
                if octile is None:
                    continue
                cost = _check_path(costs, field_dstar(costs, start, goal), start, goal)
                assert cost <= 1.005 * octile.cost
                ratios_exact.append(cost / exact_shortest(costs, start, goal, cost))
    assert min(ratios_exact) >= 1.0 - 1e-9
    assert float(np.median(ratios_exact)) <= 1.02


def test_weighted_costs_are_integrated_exactly() -> None:
    rng = np.random.default_rng(3)
    costs = rng.uniform(1.0, 5.0, (40, 40))
    costs[rng.random((40, 40)) < 0.15] = np.inf
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    path = field_dstar(costs, (0, 0), (40, 40))
    _check_path(costs, path, (0, 0), (40, 40))
    octile = field_dstar(costs, (0, 0), (40, 40), interpolate=False)
    assert _check_path(costs, octile, (0, 0), (40, 40)) == pytest.approx(octile.cost)
    assert path.cost <= octile.cost * 1.005


# ----------------------------------------------------------------------- incremental


def test_replan_after_local_change_equals_fresh_plan_with_far_fewer_expansions() -> None:
    rng = np.random.default_rng(11)
    for _ in range(10):  # draw until the goal is reachable
        costs = random_binary_map(rng, 256, 0.2)
        start = free_node(rng, costs, (5, 5))
        goal = free_node(rng, costs, (250, 250))
        planner = FieldDStar(costs)
        try:
            first = planner.plan(start, goal)
            break
        except NoPathError:
            continue
    # Block a few cells just ahead of the robot on its path.
    ahead = shapely.LineString(nodes_of(first)).interpolate(4.0)
    r, c = math.floor(ahead.x), math.floor(ahead.y)
    cells = [(r + dr, c + dc) for dr in (-1, 0) for dc in (-1, 0)
             if 0 <= r + dr < 256 and 0 <= c + dc < 256]
    planner.update_costs(cells, np.inf)
    changed = costs.copy()
    for cell in cells:
        changed[cell] = np.inf
    repaired = planner.replan()
    fresh = FieldDStar(changed).plan(start, goal)
    assert repaired.cost == pytest.approx(fresh.cost, rel=1e-9)
    np.testing.assert_array_equal(repaired.points, fresh.points)
    assert repaired.expanded * 5 <= fresh.expanded
    assert repaired.cost > first.cost
    # The robot moves on and the cells open again.
    step = shapely.LineString(nodes_of(first)).interpolate(2.0)
    moved = free_node(rng, costs, (round(step.x), round(step.y)))
    planner.update_costs(cells, 1.0)
    again = planner.replan(moved)
    fresh_again = FieldDStar(costs).plan(moved, goal)
    assert again.cost == pytest.approx(fresh_again.cost, rel=1e-9)
    np.testing.assert_array_equal(again.points, fresh_again.points)
    assert again.expanded * 5 <= fresh_again.expanded


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), interpolate=st.booleans())
def test_any_update_sequence_matches_a_fresh_plan(seed: int, interpolate: bool) -> None:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((16, 16)) < 0.2, np.inf, rng.uniform(1.0, 3.0, (16, 16)))
    costs[0, 0] = costs[-1, -1] = 1.0
    planner = FieldDStar(costs, interpolate=interpolate)
    current = costs.copy()
    start = (0, 0)
    try:
        planner.plan(start, (16, 16))
    except NoPathError:
        return
    for _ in range(3):
        cells = rng.integers(0, 16, (3, 2))
        cells = cells[(cells != 15).any(axis=1)]  # keep the goal's only cell open
        values = np.where(rng.random(len(cells)) < 0.5, np.inf, rng.uniform(1.0, 3.0, len(cells)))
        planner.update_costs(cells, values)
        current[cells[:, 0], cells[:, 1]] = values
        start = (int(rng.integers(0, 3)), int(rng.integers(0, 3)))
        if not np.isfinite(current[max(start[0] - 1, 0) : start[0] + 1,
                                   max(start[1] - 1, 0) : start[1] + 1]).any():
            continue
        try:
            fresh = FieldDStar(current, interpolate=interpolate).plan(start, (16, 16))
        except NoPathError:
            with pytest.raises(NoPathError):
                planner.replan(start)
            continue
        repaired = planner.replan(start)
        assert repaired.cost == pytest.approx(fresh.cost, rel=1e-9)


def _replay_against_fresh(seed: int, steps: int = 6) -> int:
    """Random updates and start moves on a small weighted map; every replan
    (and a second one with nothing changed) must equal a fresh plan exactly.
    Returns the number of replans compared."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(8, 48))
    weight = float(rng.uniform(1.0, 5.0))
    costs = np.where(rng.random((n, n)) < rng.uniform(0.0, 0.35), np.inf,
                     rng.choice([1.0, weight], size=(n, n)))
    costs[0, 0] = costs[-1, -1] = 1.0
    interpolate = bool(rng.random() < 0.8)
    planner = FieldDStar(costs, interpolate=interpolate)
    current = costs.copy()
    start, goal = (0, 0), (n, n)
    try:
        planner.plan(start, goal)
    except NoPathError:
        return 0
    compared = 0
    for _ in range(steps):
        cells = rng.integers(0, n, (int(rng.integers(1, 6)), 2))
        # Keep the end cells (0, 0) and (n-1, n-1) open.
        cells = cells[(cells != n - 1).any(axis=1) & (cells != 0).any(axis=1)]
        values = np.where(rng.random(len(cells)) < 0.5, np.inf,
                          rng.uniform(1.0, 4.0, len(cells)))
        if rng.random() < 0.2:
            values = current[cells[:, 0], cells[:, 1]].copy()  # nothing changes
        planner.update_costs(cells, values)
        current[cells[:, 0], cells[:, 1]] = values
        if rng.random() < 0.5:
            start = (int(rng.integers(0, 4)), int(rng.integers(0, 4)))
        if not np.isfinite(current[max(start[0] - 1, 0) : start[0] + 1,
                                   max(start[1] - 1, 0) : start[1] + 1]).any():
            start = (0, 0)
        try:
            fresh = FieldDStar(current, interpolate=interpolate).plan(start, goal)
        except NoPathError:
            with pytest.raises(NoPathError):
                planner.replan(start)
            continue
        for _ in range(2):
            repaired = planner.replan(start)
            np.testing.assert_array_equal(repaired.points, fresh.points)
            assert repaired.cost == fresh.cost
        compared += 1
    return compared


def test_replans_equal_fresh_plans_when_keys_tie() -> None:
    # Seeds where, before the keys of nearly equal first components were
    # compared with a tolerance, a repair read a start value too early (rounding
    # ordered two tied keys the wrong way) and the path extraction got stuck.
    assert sum(_replay_against_fresh(seed) for seed in (5, 376, 419, 595)) > 0


@pytest.mark.parametrize("seed", range(30))
def test_random_update_sequences_equal_fresh_plans(seed: int) -> None:
    _replay_against_fresh(1000 + seed)


@pytest.mark.parametrize("seed", range(10))
def test_fallback_to_a_fresh_search_equals_a_fresh_plan(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Zero repair bounds cut every repair short: each replan is a fresh search.
    monkeypatch.setattr(field_dstar_module, "_REPAIR_FRACTION", 0.0)
    monkeypatch.setattr(field_dstar_module, "_REPAIR_CAP", 0.0)
    monkeypatch.setattr(field_dstar_module, "_REPAIR_MIN_WORK", 0)
    _replay_against_fresh(2000 + seed)


def test_costly_repair_falls_back_and_later_repairs_stay_local(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(field_dstar_module, "_REPAIR_MIN_WORK", 0)
    rng = np.random.default_rng(3)
    costs = random_binary_map(rng, 96, 0.15)
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    start, goal = (0, 0), (96, 96)
    planner = FieldDStar(costs)
    first = planner.plan(start, goal)
    # Block cells on the path 4 cells before the goal: nearly every value rises.
    line = shapely.LineString(nodes_of(first))
    _, changed = block_2x2(planner, costs, line.interpolate(line.length - 4.0))
    fresh = FieldDStar(changed).plan(start, goal)
    repaired = planner.replan()
    np.testing.assert_array_equal(repaired.points, fresh.points)
    assert repaired.cost == fresh.cost
    # Given up after its first stage, then a fresh search: the expansions of both
    # are counted.
    assert fresh.expanded < repaired.expanded < 1.2 * fresh.expanded
    # A local change near the start is repaired, not searched afresh.
    ahead = shapely.LineString(nodes_of(repaired)).interpolate(4.0)
    r, c = math.floor(ahead.x), math.floor(ahead.y)
    local = [(r + dr, c + dc) for dr in (-1, 0) for dc in (-1, 0) if (r + dr, c + dc) != (0, 0)]
    planner.update_costs(local, np.inf)
    for cell in local:
        changed[cell] = np.inf
    again = planner.replan()
    fresh_again = FieldDStar(changed).plan(start, goal)
    np.testing.assert_array_equal(again.points, fresh_again.points)
    assert again.expanded * 5 <= fresh_again.expanded


def test_replan_with_nothing_changed_returns_the_last_path_without_work() -> None:
    rng = np.random.default_rng(8)
    costs = random_binary_map(rng, 64, 0.2)
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    planner = FieldDStar(costs)
    first = planner.plan((0, 0), (64, 64))
    again = planner.replan()
    np.testing.assert_array_equal(again.points, first.points)
    assert (again.cost, again.length, again.expanded) == (first.cost, first.length, 0)
    # Writing the costs a cell already has changes nothing either.
    planner.update_costs([(10, 10), (10, 10)], [5.0, float(costs[10, 10])])
    third = planner.replan((0, 0))
    np.testing.assert_array_equal(third.points, first.points)
    assert third.expanded == 0
    # A real change, then the same start: repaired, equal to a fresh plan.
    blocked = tuple(int(v) for v in np.floor(nodes_of(first)[len(first.points) // 2]))
    cell = (min(blocked[0], 63), min(blocked[1], 63))
    planner.update_costs([cell], np.inf)
    changed = costs.copy()
    changed[cell] = np.inf
    np.testing.assert_array_equal(
        planner.replan().points, FieldDStar(changed).plan((0, 0), (64, 64)).points
    )
    # World form: the node path is reused, the linked end points are not.
    world = FieldDStar(costs, resolution=0.5)
    a = world.plan_world((0.1, 0.1), (31.9, 31.9))
    b = world.replan_world((0.2, 0.1))
    c_ = FieldDStar(costs, resolution=0.5).plan_world((0.2, 0.1), (31.9, 31.9))
    np.testing.assert_array_equal(b.points, c_.points)
    assert b.expanded == 0 and a.expanded > 0


# ----------------------------------------------------------------------- errors


def test_errors() -> None:
    costs = np.ones((5, 5))
    with pytest.raises(ValueError, match="start"):
        field_dstar(costs, (6, 0), (0, 0))
    with pytest.raises(ValueError, match="goal"):
        field_dstar(costs, (0, 0), (0, -1))
    walled = costs.copy()
    walled[:2, :2] = np.inf
    with pytest.raises(ValueError, match="start"):
        field_dstar(walled, (1, 1), (5, 5))
    with pytest.raises(ValueError, match="costs"):
        field_dstar(np.zeros((3, 3)), (0, 0), (1, 1))
    with pytest.raises(ValueError, match="costs"):
        field_dstar(np.full((3, 3), np.nan), (0, 0), (1, 1))
    cut = costs.copy()
    cut[:, 2] = np.inf
    with pytest.raises(NoPathError) as info:
        field_dstar(cut, (0, 0), (5, 5))
    assert info.value.expanded > 0
    planner = FieldDStar(costs)
    with pytest.raises(RuntimeError, match="plan"):
        planner.replan()
    with pytest.raises(ValueError, match="cells"):
        planner.update_costs([(5, 0)], 2.0)
    with pytest.raises(ValueError, match="cells"):
        planner.update_costs([(0.5, 0)], 2.0)
    with pytest.raises(ValueError, match="new_costs"):
        planner.update_costs([(0, 0)], 0.5)
    with pytest.raises(ValueError, match="new_costs"):
        planner.update_costs([(0, 0), (1, 1)], [2.0])
    with pytest.raises(ValueError, match="new_costs"):
        planner.update_costs([(0, 0)], np.nan)


def test_inputs_are_not_modified() -> None:
    costs = np.ones((6, 6))
    costs[2, 2] = np.inf
    before = costs.copy()
    planner = FieldDStar(costs)
    planner.plan((0, 0), (6, 6))
    planner.update_costs([(3, 3)], np.inf)
    planner.replan()
    np.testing.assert_array_equal(costs, before)
    assert planner.costs[3, 3] == np.inf


def test_exact_integer_visibility_oracle_agrees_with_shapely() -> None:
    rng = np.random.default_rng(1)
    costs = random_binary_map(rng, 12, 0.3)
    blocked = ~np.isfinite(costs)
    # The oracle treats the outside of the grid as blocked, so does this reference.
    outside = shapely.difference(shapely.box(-1, -1, 13, 13), shapely.box(0, 0, 12, 12))
    union = shapely.union(blocked_union(costs), outside)
    for _ in range(300):
        a = rng.integers(0, 13, 2)
        b = rng.integers(0, 13, 2)
        if (a == b).all():
            continue
        line = shapely.LineString([a[::-1], b[::-1]])
        inside = shapely.difference(shapely.intersection(line, union), union.boundary)
        expected = shapely.length(inside) < 1e-9
        assert _visible(blocked, int(a[0]), int(a[1]), int(b[0]), int(b[1])) == expected


def test_fraction_free_true_cost_oracle_sanity() -> None:
    costs = np.array([[1.0, 3.0], [2.0, 4.0]])
    # Along the shared row line between the rows pays the cheaper cell: 1 and 3.
    pts = np.array([[1.0, 0.0], [1.0, 2.0]])
    assert true_cost(costs, pts) == pytest.approx(1.0 + 3.0)
    pts = np.array([[0.0, 0.0], [2.0, 2.0]])
    assert true_cost(costs, pts) == pytest.approx(SQRT2 * (1.0 + 4.0))


# ----------------------------------------------------------------------- world entry


def test_plan_path_with_field_dstar_is_any_angle_and_legal() -> None:
    from navkit.mapping import OccupancyGrid
    from navkit.planning import plan_path

    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:15, 14:16] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    start, goal = (0.55, 0.55), (2.55, 0.55)
    path = plan_path(grid, start, goal, robot_radius=0.2, planner="field_dstar")
    assert path.frame == "world"
    grid_path = plan_path(grid, start, goal, robot_radius=0.2)
    np.testing.assert_allclose(path.points[0], start)
    np.testing.assert_allclose(path.points[-1], goal)
    assert path.length < grid_path.length
    assert path.cost == pytest.approx(path.length)
    # Clear of the inflated wall: back in (row, col) = (y, x) / resolution.
    costs = grid.traversal_costs(robot_radius=0.2)
    assert blocked_crossing_length(costs, path.points[:, ::-1] / 0.1) < 1e-9
    assert path.points[:, 1].max() > 1.5  # round the end of the wall (y < 1.5)
    with pytest.raises(NoPathError):
        blocked = occupied.copy()
        blocked[:, 14:16] = True
        plan_path(
            OccupancyGrid.from_occupancy(blocked, resolution=0.1), start, goal,
            planner="field_dstar",
        )


# ----------------------------------------------------------------------- cells


def test_plan_cells_runs_centre_to_centre_legally() -> None:
    costs = np.ones((10, 10))
    costs[2:8, 4] = np.inf
    planner = FieldDStar(costs)
    path = planner.plan_cells((5, 0), (5, 9))
    assert path.frame == "grid"
    assert path.points[0].tolist() == [5.0, 0.0]
    assert path.points[-1].tolist() == [5.0, 9.0]
    assert path.cells[[0, -1]].tolist() == [[5, 0], [5, 9]]
    nodes = nodes_of(path)
    assert blocked_crossing_length(costs, nodes) < 1e-9
    assert path.cost == pytest.approx(true_cost(costs, nodes), rel=1e-9)
    assert path.length == pytest.approx(
        float(np.hypot(*np.diff(path.points, axis=0).T).sum()), rel=1e-12
    )
    # The link corners are chosen by cost: the path goes under the wall's lower
    # end, taut over the corners (8, 4) and (8, 5) from centre to centre (over
    # the upper end, the old position rule's choice, it costs 11.65).
    taut = math.hypot(8 - 5.5, 4 - 0.5) + 1 + math.hypot(8 - 5.5, 9.5 - 5)
    assert path.cost == pytest.approx(taut, rel=1e-9)
    same = planner.plan_cells((3, 3), (3, 3))
    assert same.points.tolist() == [[3.0, 3.0]]
    assert (same.cost, same.length, same.expanded) == (0.0, 0.0, 0)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(3, 20), smooth=st.booleans())
def test_plan_cells_is_legal_on_random_maps(seed: int, n: int, smooth: bool) -> None:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((n, n)) < 0.25, np.inf, rng.uniform(1.0, 3.0, (n, n)))
    free = np.argwhere(np.isfinite(costs))
    if len(free) < 2:
        return
    s, g = (tuple(int(v) for v in free[i]) for i in rng.choice(len(free), 2, replace=False))
    planner = FieldDStar(costs, smooth=smooth)
    try:
        path = planner.plan_cells(s, g)
    except NoPathError:
        with pytest.raises(NoPathError):
            field_dstar(costs, tuple(np.add(s, 1)), tuple(np.add(g, 1)))
        return
    assert path.points[0].tolist() == list(map(float, s))
    assert path.points[-1].tolist() == list(map(float, g))
    nodes = nodes_of(path)
    assert blocked_crossing_length(costs, nodes) < 1e-9
    assert path.cost == pytest.approx(true_cost(costs, nodes), rel=1e-9)


# ----------------------------------------------------------------------- world


def test_world_node_conversions_follow_the_occupancy_grid_convention() -> None:
    from navkit.mapping import OccupancyGrid

    origin = Pose2D(3.0, -2.0, 0.6)
    planner = FieldDStar(np.ones((12, 15)), resolution=0.25, origin=origin)
    grid = OccupancyGrid.from_occupancy(np.zeros((12, 15), dtype=bool), resolution=0.25,
                                        origin=origin)
    rng = np.random.default_rng(4)
    nodes = rng.uniform(0.0, 12.0, (50, 2))
    world = planner.node_to_world(nodes)
    assert world.shape == (50, 2)
    # Node (i, j) is the continuous cell coordinate (i - 0.5, j - 0.5).
    np.testing.assert_allclose(world, grid.cell_to_world(nodes - 0.5), atol=1e-12)
    np.testing.assert_allclose(planner.world_to_node(world, continuous=True), nodes, atol=1e-9)
    # Node (0, 0) is the origin: the outer corner of cell (0, 0).
    np.testing.assert_allclose(planner.node_to_world((0, 0)), [3.0, -2.0], atol=1e-12)
    # The nearest node, one point in, one point out.
    one = planner.world_to_node(world[0])
    assert one.shape == (2,) and one.dtype == np.int64
    np.testing.assert_array_equal(one, np.floor(nodes[0] + 0.5))
    np.testing.assert_array_equal(planner.world_to_node(world), np.floor(nodes + 0.5))
    with pytest.raises(ValueError, match="points_xy"):
        planner.world_to_node(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="nodes"):
        planner.node_to_world([1.0, 2.0, 3.0])


def test_plan_world_runs_point_to_point_and_matches_the_grid_path() -> None:
    costs = np.ones((10, 10))
    costs[2:8, 4] = np.inf
    origin = Pose2D(1.0, -1.0, 0.3)
    planner = FieldDStar(costs, resolution=0.5, origin=origin)
    start_xy = planner.node_to_world((5.3, 0.6))
    goal_xy = planner.node_to_world((5.2, 9.7))
    path = planner.plan_world(start_xy, goal_xy)
    assert path.frame == "world"
    np.testing.assert_allclose(path.points[0], start_xy, atol=1e-12)
    np.testing.assert_allclose(path.points[-1], goal_xy, atol=1e-12)
    nodes = planner.world_to_node(path.points, continuous=True)
    assert blocked_crossing_length(costs, nodes) < 1e-9
    assert path.cost == pytest.approx(0.5 * true_cost(costs, nodes), rel=1e-9)
    assert path.length == pytest.approx(
        float(np.hypot(*np.diff(path.points, axis=0).T).sum()), rel=1e-9
    )
    # The nearest nodes (5, 1) and (5, 10) are level with the wall's middle and
    # the node path goes over its upper end: taut over the corners (2, 4), (2, 5).
    taut = math.hypot(5.3 - 2, 4 - 0.6) + 1 + math.hypot(5.2 - 2, 9.7 - 5)
    assert path.cost == pytest.approx(0.5 * taut, rel=1e-9)
    # Uniform map: the straight segment.
    open_map = FieldDStar(np.full((8, 8), 2.0), resolution=0.1)
    straight = open_map.plan_world((0.05, 0.12), (0.71, 0.33))
    np.testing.assert_allclose(straight.points, [[0.05, 0.12], [0.71, 0.33]], atol=1e-12)
    assert straight.cost == pytest.approx(2.0 * math.hypot(0.66, 0.21), rel=1e-9)


def test_replan_world_equals_a_fresh_world_plan() -> None:
    rng = np.random.default_rng(21)
    origin = Pose2D(-4.0, 2.0, -1.1)
    resolution = 0.05
    for _ in range(10):  # draw until the goal is reachable
        costs = random_binary_map(rng, 128, 0.2)
        costs[:3, :3] = costs[-3:, -3:] = 1.0
        planner = FieldDStar(costs, resolution=resolution, origin=origin)
        start_xy = planner.node_to_world((1.3, 1.6))
        goal_xy = planner.node_to_world((126.6, 127.2))
        try:
            first = planner.plan_world(start_xy, goal_xy)
            break
        except NoPathError:
            continue
    nodes = planner.world_to_node(first.points, continuous=True)
    cells, changed = block_2x2(planner, costs, shapely.LineString(nodes).interpolate(6.0))
    # The robot moved a little along its path (to a point inside a free cell).
    line = shapely.LineString(nodes)
    for distance in np.arange(2.5, 4.0, 0.1):
        step = line.interpolate(distance)
        here = (step.x, step.y)
        if np.isfinite(changed[math.floor(step.x), math.floor(step.y)]) and all(
            abs(v - round(v)) > 1e-6 for v in here
        ):
            break
    moved_xy = planner.node_to_world(here)
    fresh = FieldDStar(changed, resolution=resolution, origin=origin).plan_world(
        moved_xy, goal_xy
    )
    repaired = planner.replan_world(moved_xy)
    np.testing.assert_array_equal(repaired.points, fresh.points)
    assert repaired.cost == pytest.approx(fresh.cost, rel=1e-12)
    assert repaired.expanded * 5 <= fresh.expanded
    np.testing.assert_allclose(repaired.points[0], moved_xy, atol=1e-12)
    np.testing.assert_allclose(repaired.points[-1], goal_xy, atol=1e-12)
    # Without a new start the previous start point is kept.
    planner.update_costs(cells, 1.0)
    again = planner.replan_world()
    fresh_again = FieldDStar(costs, resolution=resolution, origin=origin).plan_world(
        moved_xy, goal_xy
    )
    np.testing.assert_array_equal(again.points, fresh_again.points)
    # The node form of the same repair is the grid path between the nodes.
    node_path = planner.replan()
    assert node_path.frame == "grid"
    np.testing.assert_array_equal(
        nodes_of(node_path)[[0, -1]],
        [planner.world_to_node(moved_xy), planner.world_to_node(goal_xy)],
    )


def test_replan_world_after_node_and_cell_plans_keeps_their_end_points() -> None:
    planner = FieldDStar(np.ones((6, 6)), resolution=2.0)
    planner.plan((0, 0), (6, 6))
    np.testing.assert_allclose(planner.replan_world().points, [[0.0, 0.0], [12.0, 12.0]])
    planner.plan_cells((0, 0), (5, 5))
    np.testing.assert_allclose(planner.replan_world().points, [[1.0, 1.0], [11.0, 11.0]])
    moved = planner.replan_world((3.0, 1.0))
    np.testing.assert_allclose(moved.points, [[3.0, 1.0], [11.0, 11.0]])
    # A plan to the start's own cell is a point, and its goal is the one kept
    # (it used to leave the previous plan's goal in place).
    assert planner.plan_cells((2, 2), (2, 2)).points.tolist() == [[2.0, 2.0]]
    np.testing.assert_allclose(planner.replan_world().points[[0, -1]], [[5.0, 5.0], [5.0, 5.0]])
    assert planner.replan_world().cost == 0.0
    back = planner.replan_world((11.0, 5.0))  # pushed 6 m along x: straight back
    np.testing.assert_allclose(back.points, [[11.0, 5.0], [5.0, 5.0]])
    assert back.cost == pytest.approx(6.0)
    fresh = FieldDStar(np.ones((6, 6)), resolution=2.0)
    fresh.plan_cells((2, 2), (2, 2))  # the first plan of a planner
    np.testing.assert_allclose(fresh.replan_world((1.0, 5.0)).points, [[1.0, 5.0], [5.0, 5.0]])


def test_replan_world_after_plan_cells_equals_a_search_to_the_same_goal_corner() -> None:
    """The goal keeps plan_cells' corner: a repaired plan equals one searched afresh to it."""
    rng = np.random.default_rng(7)
    for _ in range(40):
        costs = np.where(rng.random((8, 8)) < 0.2, np.inf, rng.uniform(1.0, 3.0, (8, 8)))
        free = [tuple(int(v) for v in c) for c in np.argwhere(np.isfinite(costs))]
        s, g, moved = (free[i] for i in rng.choice(len(free), 3, replace=False))
        changed = free[rng.integers(len(free))]
        moved_xy = (moved[1] + 0.3, moved[0] + 0.6)
        if changed in (s, g, moved):
            continue
        planner = FieldDStar(costs)
        try:
            planner.plan_cells(s, g)
        except NoPathError:
            continue
        planner.update_costs([changed], np.inf)
        new_costs = costs.copy()
        new_costs[changed] = np.inf
        reference = FieldDStar(new_costs)
        try:
            reference.plan_cells(s, g)  # the same goal corner (start cell unchanged)
            want = reference.replan_world(moved_xy)  # nothing changed: a start move only
        except NoPathError:
            with pytest.raises(NoPathError):
                planner.replan_world(moved_xy)
            continue
        got = planner.replan_world(moved_xy)
        np.testing.assert_allclose(got.points, want.points, atol=1e-12)
        assert got.cost == pytest.approx(want.cost, rel=1e-12)


def test_world_errors_and_options() -> None:
    costs = np.ones((5, 5))
    costs[2, 2] = np.inf
    planner = FieldDStar(costs, resolution=0.5)
    with pytest.raises(RuntimeError, match="plan"):
        planner.replan_world()
    with pytest.raises(ValueError, match=r"start_xy .* outside"):
        planner.plan_world((-0.1, 1.0), (2.0, 2.0))
    with pytest.raises(ValueError, match=r"goal_xy .* outside"):
        planner.plan_world((0.1, 0.1), (2.5, 1.0))  # x = 2.5 m is the far edge
    with pytest.raises(ValueError, match=r"goal_xy .* impassable cell \(2, 2\)"):
        planner.plan_world((0.1, 0.1), (1.2, 1.3))
    with pytest.raises(ValueError, match="start_xy"):
        planner.plan_world((0.1, 0.1, 0.0), (2.0, 2.0))
    with pytest.raises(ValueError, match=r"start_cell \(2, 2\) is on an impassable"):
        planner.plan_cells((2, 2), (0, 0))
    with pytest.raises(ValueError, match="goal_cell"):
        planner.plan_cells((0, 0), (5, 0))
    with pytest.raises(ValueError, match="start_node"):
        planner.plan((6, 0), (0, 0))
    for flag in ("interpolate", "lookahead", "smooth"):
        with pytest.raises(TypeError, match=flag):
            FieldDStar(costs, **{flag: 1})  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="resolution"):
        FieldDStar(costs, resolution=0.0)
    with pytest.raises(TypeError, match="origin"):
        FieldDStar(costs, origin="here")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        FieldDStar(costs, False)  # type: ignore[misc]
    other = FieldDStar(costs, interpolate=False, lookahead=False, smooth=False,
                       resolution=0.25, origin=(1.0, 2.0, 0.5))
    assert (other.interpolate, other.lookahead, other.smooth) == (False, False, False)
    assert other.resolution == 0.25
    assert other.origin == Pose2D(1.0, 2.0, 0.5)
    assert other.shape == (5, 5)
    assert "FieldDStar(<5x5 costs>" in repr(other)


@settings(max_examples=60, deadline=None)
@given(
    resolution=st.sampled_from([0.05, 0.1, 0.15, 0.2, 0.3, 0.7, 1.0 / 3.0]),
    yaw=st.sampled_from([0.0, 0.5, -2.0, math.pi / 2]),
    origin_cm=st.tuples(st.integers(-2000, 2000), st.integers(-2000, 2000)),
    points_cm=st.lists(
        st.tuples(st.integers(-3000, 3000), st.integers(-3000, 3000)), min_size=1, max_size=20
    ),
)
def test_world_points_fall_in_the_cell_of_the_occupancy_grid(
    resolution: float,
    yaw: float,
    origin_cm: tuple[int, int],
    points_cm: list[tuple[int, int]],
) -> None:
    """Points given to the centimetre (many on cell edges) land in the map's own cell.

    world_to_node divided by the resolution: 0.3 / 0.1 < 3, so the point
    x = 0.3 m fell in column 2 while OccupancyGrid.world_to_cell (and so the
    map the costs were built from) puts it in column 3.
    """
    from navkit.mapping import OccupancyGrid

    origin = (origin_cm[0] / 100, origin_cm[1] / 100, yaw)
    planner = FieldDStar(np.ones((4, 4)), resolution=resolution, origin=origin)
    grid = OccupancyGrid(np.zeros((4, 4)), resolution=resolution, origin=origin)
    points = np.array(points_cm, dtype=np.float64) / 100
    nodes = planner.world_to_node(points, continuous=True)
    np.testing.assert_array_equal(np.floor(nodes).astype(np.int64), grid.world_to_cell(points))
    for point in points[:3]:  # one point at a time too (the map's scalar path)
        one = planner.world_to_node(point, continuous=True)
        np.testing.assert_array_equal(np.floor(one).astype(np.int64), grid.world_to_cell(point))


def test_plan_world_accepts_a_point_on_a_cell_edge_as_the_map_does() -> None:
    costs = np.ones((3, 6))
    costs[:, 2] = np.inf  # column 2 blocked, column 3 free
    planner = FieldDStar(costs, resolution=0.1)
    # x = 0.3 m is the edge between columns 2 and 3: the map's column 3.
    path = planner.plan_world((0.3, 0.15), (0.55, 0.15))
    np.testing.assert_allclose(path.points[[0, -1]], [[0.3, 0.15], [0.55, 0.15]], atol=1e-12)
    assert path.cost == pytest.approx(0.25, rel=1e-9)


def test_replan_world_refuses_kept_end_points_whose_cell_became_impassable() -> None:
    # The link from a kept end point to its node ran through the now impassable
    # cell: the path cost was inf and Path2D raised "cost must be finite".
    planner = FieldDStar(np.ones((6, 6)))
    planner.plan_world((0.3, 0.6), (5.5, 5.2))
    planner.update_costs((0, 0), np.inf)
    with pytest.raises(ValueError, match=r"start_xy \(0\.3, 0\.6\) .* impassable cell \(0, 0\)"):
        planner.replan_world()
    # A fresh plan_world refuses the point the same way.
    with pytest.raises(ValueError, match=r"start_xy .* impassable cell \(0, 0\)"):
        FieldDStar(planner.costs).plan_world((0.3, 0.6), (5.5, 5.2))
    # A new start point in a free cell plans on.
    moved = planner.replan_world((1.5, 0.5))
    np.testing.assert_allclose(moved.points[[0, -1]], [[1.5, 0.5], [5.5, 5.2]], atol=1e-12)
    assert math.isfinite(moved.cost)
    planner.update_costs((5, 5), np.inf)
    with pytest.raises(ValueError, match=r"goal_xy \(5\.5, 5\.2\) .* impassable cell \(5, 5\)"):
        planner.replan_world((1.5, 0.5))
    # After plan_cells the kept goal is the goal cell's centre.
    cells = FieldDStar(np.ones((6, 6)), resolution=0.5)
    cells.plan_cells((0, 0), (4, 3))
    cells.update_costs((4, 3), np.inf)
    with pytest.raises(ValueError, match=r"goal_xy \(1\.75, 2\.25\) .* impassable cell \(4, 3\)"):
        cells.replan_world()
    # End points on nodes (plan) have no link: a node with a passable cell around it
    # stays valid (the node check, see the next test).
    nodes = FieldDStar(np.ones((6, 6)))
    nodes.plan((1, 1), (5, 5))
    nodes.update_costs([(0, 0), (1, 1), (4, 4)], np.inf)
    path = nodes.replan_world()
    np.testing.assert_allclose(path.points[[0, -1]], [[1.0, 1.0], [5.0, 5.0]], atol=1e-12)


# The four cells around node (3, 3) of a 6 x 6 grid.
_AROUND_3_3 = [(2, 2), (2, 3), (3, 2), (3, 3)]


def _error_of(call: object) -> tuple[type[BaseException], str] | None:
    """The exception class and message a call raises, or None."""
    assert callable(call)
    try:
        call()
    except (ValueError, NoPathError) as exc:
        return type(exc), str(exc)
    return None


@pytest.mark.parametrize(
    ("ends", "blocked", "name"),
    [
        (((0, 0), (3, 3)), _AROUND_3_3, "goal_node"),
        (((3, 3), (0, 0)), _AROUND_3_3, "start_node"),
        # Both enclosed: the start is reported, as plan() checks it first.
        (((3, 3), (0, 0)), [*_AROUND_3_3, (0, 0)], "start_node"),
        # Start and goal on one node: the replan returned the one-point path.
        (((3, 3), (3, 3)), _AROUND_3_3, "start_node"),
    ],
)
def test_replan_refuses_kept_nodes_enclosed_since_the_plan_as_a_fresh_plan_does(
    ends: tuple[tuple[int, int], tuple[int, int]], blocked: list[tuple[int, int]], name: str
) -> None:
    # A kept node whose cells all became impassable gave NoPathError (or a path),
    # where a fresh plan() between the same nodes raises ValueError.
    start, goal = ends
    planner = FieldDStar(np.ones((6, 6)))
    planner.plan(start, goal)
    planner.update_costs(blocked, np.inf)
    fresh = _error_of(lambda: FieldDStar(planner.costs).plan(start, goal))
    assert fresh is not None and fresh[0] is ValueError
    assert fresh[1].startswith(name)
    node = start if name == "start_node" else goal
    pattern = rf"{name} \({node[0]}, {node[1]}\) .*corner of impassable cells only"
    with pytest.raises(ValueError, match=pattern):
        planner.replan()
    # The world form of the same replan refuses the node's point.
    with pytest.raises(ValueError, match=r"_xy \(3\.0, 3\.0\) .*corner of impassable cells"):
        planner.replan_world()


def test_refused_replans_leave_the_planner_as_it_was() -> None:
    planner = FieldDStar(np.ones((6, 6)))
    planner.plan((0, 0), (3, 3))
    planner.update_costs(_AROUND_3_3, np.inf)
    # A valid new start with the goal enclosed: refused, and the start not moved.
    with pytest.raises(ValueError, match=r"goal_node \(3, 3\)"):
        planner.replan((6, 0))
    with pytest.raises(ValueError, match=r"goal_xy \(3\.0, 3\.0\)"):
        planner.replan_world((5.5, 0.5))
    planner.update_costs([(3, 3)], 1.0)
    again = planner.replan()
    fresh = FieldDStar(planner.costs).plan((0, 0), (3, 3))
    np.testing.assert_array_equal(again.points, fresh.points)
    assert again.cost == fresh.cost


def test_replan_after_a_world_plan_checks_the_kept_nodes() -> None:
    # replan() plans node to node: its kept nodes are checked as plan() checks them.
    planner = FieldDStar(np.ones((6, 6)))
    planner.plan_world((0.5, 0.5), (3.2, 3.2))  # goal node (3, 3)
    planner.update_costs(_AROUND_3_3, np.inf)
    assert _error_of(lambda: FieldDStar(planner.costs).plan((1, 1), (3, 3))) is not None
    with pytest.raises(ValueError, match=r"goal_node \(3, 3\) .*corner of impassable cells"):
        planner.replan()
    # replan_world keeps the world point: its cell is checked (as plan_world does).
    with pytest.raises(ValueError, match=r"goal_xy \(3\.2, 3\.2\) .* impassable cell \(3, 3\)"):
        planner.replan_world()


def test_replan_world_refuses_a_kept_point_on_a_node_whose_cell_became_impassable() -> None:
    # A plan_world end exactly on a node lies in the cell _world_end picks (its
    # lower corner); a fresh plan_world refuses it once that cell is impassable,
    # but the replan skipped points on nodes and returned a path.
    planner = FieldDStar(np.ones((6, 6)))
    planner.plan_world((0.5, 0.5), (3.0, 3.0))
    planner.update_costs([(3, 3)], np.inf)
    fresh = _error_of(lambda: FieldDStar(planner.costs).plan_world((0.5, 0.5), (3.0, 3.0)))
    assert fresh is not None and fresh[0] is ValueError
    with pytest.raises(ValueError, match=r"goal_xy \(3\.0, 3\.0\) .* impassable cell \(3, 3\)"):
        planner.replan_world()
    # A start moved onto a node by replan_world is a world point too.
    planner.update_costs([(3, 3)], 1.0)
    planner.replan_world((2.0, 1.0))
    planner.update_costs([(1, 2)], np.inf)
    with pytest.raises(ValueError, match=r"start_xy \(2\.0, 1\.0\) .* impassable cell \(1, 2\)"):
        planner.replan_world()
    # After replan(start_node) the start is a node again: the node check applies.
    planner.replan((1, 2))
    np.testing.assert_allclose(planner.replan_world().points[0], [2.0, 1.0])


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_replans_fail_as_fresh_plans_fail(seed: int) -> None:
    """Replan equals a fresh plan on the current costs, errors included.

    Updates close and open the cells around the kept ends too, so a kept
    node or point becomes invalid and valid again.
    """
    rng = np.random.default_rng(seed)
    n = 6
    costs = np.where(rng.random((n, n)) < 0.15, np.inf, 1.0)
    free = np.argwhere(np.isfinite(costs))
    if len(free) < 2:
        return
    a, b = free[rng.choice(len(free), 2, replace=False)]
    start, goal = (int(a[0]), int(a[1])), (int(b[0]), int(b[1]))
    start_xy, goal_xy = (start[1] + 0.5, start[0] + 0.5), (goal[1] + 0.5, goal[0] + 0.5)
    node_s = (start[0] + int(rng.integers(0, 2)), start[1] + int(rng.integers(0, 2)))
    node_g = (goal[0] + int(rng.integers(0, 2)), goal[1] + int(rng.integers(0, 2)))
    by_nodes, by_points = FieldDStar(costs), FieldDStar(costs)
    try:
        by_nodes.plan(node_s, node_g)
        by_points.plan_world(start_xy, goal_xy)
    except NoPathError:
        return
    ends = np.array([start, goal])
    for _ in range(4):
        near = ends[rng.integers(0, 2, 3)] + rng.integers(-1, 2, (3, 2))
        cells = np.clip(near, 0, n - 1)
        values = np.where(rng.random(3) < 0.7, np.inf, 1.0)
        by_nodes.update_costs(cells, values)
        by_points.update_costs(cells, values)
        reference = FieldDStar(by_nodes.costs)
        for replan, fresh in (
            (by_nodes.replan, partial(reference.plan, node_s, node_g)),
            (by_points.replan_world, partial(reference.plan_world, start_xy, goal_xy)),
        ):
            want = _error_of(fresh)
            if want is None:
                np.testing.assert_array_equal(replan().points, fresh().points)
                continue
            with pytest.raises(want[0]) as info:
                replan()
            # The same end is named, the same way.
            assert str(info.value).split(" ")[0] == want[1].split(" ")[0]
            assert ("impassable" in str(info.value)) == ("impassable" in want[1])


def test_world_end_nodes_round_as_world_to_node() -> None:
    # The search's start node used floor(p + 0.5), which rounds p + 0.5 first: a point
    # just below a half (0.5 - 2**-54 cells) went to the node above, unlike world_to_node.
    fd = FieldDStar(np.ones((4, 4)))
    below_half = 0.49999999999999994
    for node_xy in ([1.0, below_half], [below_half, 2.0], [2.5, 1.5]):
        world = fd.node_to_world(node_xy)
        _, node, _ = fd._world_end(world, "start_xy")
        assert node == tuple(fd.world_to_node(world).tolist())


def test_segment_a_hair_beside_a_grid_line_pays_the_cell_it_lies_in() -> None:
    # The polyline cost priced a segment within 1e-9 of a grid line as running
    # along it (the cheaper cell beside it): this straight path lies inside the
    # cost-100 column, 5e-10 cells from its edge, and was reported to cost 1.8.
    costs = np.array([[100.0, 1.0], [100.0, 1.0]])
    planner = FieldDStar(costs)
    path = planner.plan_world((1 - 5e-10, 0.1), (1 - 5e-10, 1.9))
    points = planner.world_to_node(path.points, continuous=True)
    assert path.cost == pytest.approx(true_cost(costs, points), rel=1e-12)
    assert path.cost <= 180.0
    # The straight segment itself, priced by the planner's own integrator.
    straight = np.array([[0.1, 1 - 5e-10], [1.9, 1 - 5e-10]])
    cost, _ = polyline_cost(planner._pad, planner._width, straight, 2)
    assert cost == pytest.approx(180.0, rel=1e-12)
    # Exactly on the line it pays the cheaper cell beside it.
    on_line = np.array([[0.1, 1.0], [1.9, 1.0]])
    assert polyline_cost(planner._pad, planner._width, on_line, 2)[0] == pytest.approx(1.8)


@pytest.mark.parametrize("smooth", [True, False])
def test_a_world_plan_from_a_point_to_itself_is_that_point(smooth: bool) -> None:
    # Off a node it was a trip to the nearest node and back ([p, p] smoothed, or
    # [p, node, p] with its cost), where on a node it was the one point.
    fd = FieldDStar(np.ones((4, 4)), smooth=smooth)
    for p in [(0.2, 0.2), (1.0, 1.0), (3.9, 0.05)]:
        path = fd.plan_world(p, p)
        assert path.points.tolist() == [list(p)] and path.cost == 0.0 and path.length == 0.0
        again = fd.replan_world()
        assert again.points.tolist() == [list(p)] and again.cost == 0.0
