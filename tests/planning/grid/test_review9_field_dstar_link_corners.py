"""FieldDStar.plan_cells links the cell centres to the corners of least cost.

The segment from a cell's centre to any of its four corners lies inside the
cell and costs half a diagonal times the cell's cost, whichever the corner.
plan_cells used to pick the link corners by position (the corner nearest the
other centre), so its path could cost more than the path through another pair
of corners. The reference here is independent of plan_cells: each of the 16
(start corner, goal corner) pairs forced through the public node API
(:meth:`FieldDStar.plan`) plus the two half-diagonal end segments.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from navkit.errors import NoPathError
from navkit.planning import FieldDStar

HALF_DIAGONAL = math.hypot(0.5, 0.5)
CORNERS = [(0, 0), (0, 1), (1, 0), (1, 1)]


def forced_corner_pairs(
    costs: NDArray[np.float64], s: tuple[int, int], g: tuple[int, int], **options: bool
) -> float:
    """Least cost over the 16 corner pairs: plan() between them plus both centre segments."""
    ends = HALF_DIAGONAL * (costs[s] + costs[g])
    best = math.inf
    for a in CORNERS:
        for b in CORNERS:
            try:
                path = FieldDStar(costs, **options).plan(
                    (s[0] + a[0], s[1] + a[1]), (g[0] + b[0], g[1] + b[1])
                )
            except NoPathError:
                continue
            best = min(best, path.cost + ends)
    return best


def random_costs(seed: int, rows: int, cols: int, kind: int) -> NDArray[np.float64]:
    """Uniform random costs with holes, or an inflated-looking occupancy map."""
    rng = np.random.default_rng(seed)
    if kind == 0:
        return np.where(rng.random((rows, cols)) < 0.2, np.inf, rng.uniform(1.0, 3.0, (rows, cols)))
    occupied = rng.random((rows, cols)) < 0.12
    # Chebyshev-like distance to the nearest obstacle by repeated dilation.
    dist = np.where(occupied, 0.0, np.inf)
    for step in range(1, max(rows, cols)):
        grown = dist.copy()
        pad = np.pad(dist, 1, constant_values=np.inf)
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                shifted = pad[1 + di : 1 + di + rows, 1 + dj : 1 + dj + cols]
                grown = np.minimum(grown, np.where(np.isfinite(shifted), step, np.inf))
        dist = np.minimum(dist, grown)
    band = 1.0 + 20.0 * np.exp(-dist / 1.5)
    if kind == 2:  # integer cost bands and a lethal inflation ring, as a costmap has
        band = np.where(dist <= 1, np.inf, np.round(band))
    return np.where(occupied, np.inf, band)


def two_free_cells(
    costs: NDArray[np.float64], pick: tuple[int, int]
) -> tuple[tuple[int, int], tuple[int, int]] | None:
    free = [(int(r), int(c)) for r, c in np.argwhere(np.isfinite(costs))]
    if len(free) < 2:
        return None
    i = pick[0] % len(free)
    j = pick[1] % (len(free) - 1)
    j += j >= i
    return free[i], free[j]


# A drawn grid (seed, rows, cols, kind, the picks of the two end cells), and the
# costs and end cells it stands for.
Grid = tuple[int, int, int, int, tuple[int, int]]
Case = tuple[NDArray[np.float64], tuple[int, int], tuple[int, int]]


def random_case(grid: Grid) -> Case | None:
    """The costs a drawn ``grid`` describes and its two end cells; None without two free cells."""
    seed, rows, cols, kind, pick = grid
    costs = random_costs(seed, rows, cols, kind)
    ends = two_free_cells(costs, pick)
    return None if ends is None else (costs, *ends)


grids = st.tuples(
    st.integers(0, 2**32 - 1),  # seed
    st.integers(2, 9),  # rows
    st.integers(2, 9),  # cols
    st.integers(0, 2),  # kind
    st.tuples(st.integers(0, 10**6), st.integers(0, 10**6)),  # the two cells
)


def test_wall_case_takes_the_cheaper_side_the_position_rule_missed() -> None:
    costs = np.ones((10, 10))
    costs[2:8, 4] = np.inf  # a wall from row 2 to row 7: its lower end is nearer
    path = FieldDStar(costs).plan_cells((5, 0), (5, 9))
    # The position rule linked the corners (5, 1) and (5, 9), level with the wall's
    # middle, and went over its upper end: 3.5 + 1 + 4.5 along the taut path, 11.65.
    under = math.hypot(8 - 5.5, 4 - 0.5) + 1.0 + math.hypot(8 - 5.5, 9.5 - 5)
    assert path.cost == pytest.approx(under, rel=1e-9)
    assert path.cost <= forced_corner_pairs(costs, (5, 0), (5, 9)) * (1 + 1e-9)
    flipped = FieldDStar(costs[::-1].copy()).plan_cells((4, 0), (4, 9))
    assert flipped.cost == pytest.approx(path.cost, rel=1e-9)


@settings(max_examples=40, deadline=None)
@given(grid=grids, interpolate=st.booleans())
# Review 49: the worst of 22,853 drawn queries, 1.95 % above (the bound was 1 %).
@example(grid=(2958058860, 8, 8, 0, (411672, 900256)), interpolate=True)
def test_plan_cells_costs_no_more_than_any_corner_pair(grid: Grid, interpolate: bool) -> None:
    case = random_case(grid)
    if case is None:
        return
    costs, s, g = case
    reference = forced_corner_pairs(costs, s, g, interpolate=interpolate)
    if reference == math.inf:
        with pytest.raises(NoPathError):
            FieldDStar(costs, interpolate=interpolate).plan_cells(s, g)
        return
    path = FieldDStar(costs, interpolate=interpolate).plan_cells(s, g)
    # The measured bound: the start corner is chosen by its interpolated value,
    # which can rank corners otherwise than their walked paths (27 of 22,853 such
    # queries above the reference, by at most 1.95 %, review 49; review 24 had
    # measured 3 of 5,479 and 0.6 %; the position rule used before was up to 20 %
    # above).
    assert path.cost <= reference * 1.03


def test_a_corner_ranked_by_its_value_may_walk_a_little_dearer() -> None:
    # Found by the property above (session 24): 7.7648 against the pair (3, 0)-(3, 4)'s
    # 7.7616, 0.04 % above it.
    case = random_case((936, 8, 5, 0, (36846, 17)))
    assert case is not None
    costs, s, g = case
    reference = forced_corner_pairs(costs, s, g, interpolate=True)
    cost = FieldDStar(costs, interpolate=True).plan_cells(s, g).cost
    assert reference < cost <= reference * 1.001


@settings(max_examples=40, deadline=None)
@given(grid=grids, axis=st.sampled_from([0, 1]), interpolate=st.booleans())
def test_a_mirrored_grid_gives_the_same_cost(grid: Grid, axis: int, interpolate: bool) -> None:
    # Unsmoothed: the shortcut pass is greedy along the path and may straighten a
    # mirrored path differently (see the FieldDStar Notes); the node values, the
    # corners they pick and the extracted path's cost are mirror symmetric.
    case = random_case(grid)
    if case is None:
        return
    costs, s, g = case
    shape = costs.shape

    def mirror(cell: tuple[int, int]) -> tuple[int, int]:
        return (shape[0] - 1 - cell[0], cell[1]) if axis == 0 else (cell[0], shape[1] - 1 - cell[1])

    mirrored = np.ascontiguousarray(np.flip(costs, axis))
    try:
        want = FieldDStar(costs, smooth=False, interpolate=interpolate).plan_cells(s, g).cost
    except NoPathError:
        with pytest.raises(NoPathError):
            FieldDStar(mirrored, smooth=False).plan_cells(mirror(s), mirror(g))
        return
    got = FieldDStar(mirrored, smooth=False, interpolate=interpolate).plan_cells(
        mirror(s), mirror(g)
    )
    assert got.cost == pytest.approx(want, rel=1e-9)


@settings(max_examples=30, deadline=None)
@given(grid=grids, changed=st.integers(0, 10**6), blocked=st.booleans())
def test_a_repair_after_plan_cells_equals_a_fresh_plan_cells(
    grid: Grid, changed: int, blocked: bool
) -> None:
    case = random_case(grid)
    if case is None:
        return
    costs, s, g = case
    # Any cell but the two ends, the goal cell's cost too (the corners' source value).
    cell = divmod(changed % costs.size, costs.shape[1])
    if cell == s:
        return
    value = np.inf if blocked and cell != g else 1.0 + (changed % 7)
    planner = FieldDStar(costs)
    try:
        planner.plan_cells(s, g)
    except NoPathError:
        return
    planner.update_costs([cell], value)
    new_costs = costs.copy()
    new_costs[cell] = value
    fresh = FieldDStar(new_costs)
    try:
        want = fresh.plan_cells(s, g)
    except NoPathError:
        with pytest.raises(NoPathError):
            planner.replan_world()
        return
    got = planner.replan_world()
    np.testing.assert_array_equal(got.points, fresh.node_to_world(want.points + 0.5))
    assert got.cost == want.cost
    # The node form repairs the same search: the node path from the chosen corner.
    np.testing.assert_array_equal(planner.replan().points, fresh.replan().points)


def test_replan_refuses_a_kept_cell_that_became_impassable() -> None:
    planner = FieldDStar(np.ones((5, 5)))
    planner.plan_cells((0, 0), (4, 4))
    planner.update_costs((4, 4), np.inf)
    with pytest.raises(ValueError, match=r"goal_node: the cell \(4, 4\) kept from plan_cells"):
        planner.replan()
    with pytest.raises(ValueError, match=r"goal_xy \(4\.5, 4\.5\) .* impassable cell \(4, 4\)"):
        planner.replan_world()
    planner.update_costs([(4, 4), (0, 0)], [1.0, np.inf])
    with pytest.raises(ValueError, match=r"start_node: the cell \(0, 0\) kept from plan_cells"):
        planner.replan()
