"""Field D*'s node values are one evaluation of corner_cost in every drawing (review 41, PLANREV2).

Review 40 left open whether the interpolated corner cost could come out an ulp
apart where the same value is evaluated twice: the search evaluates a node's
pairs at five LLVM-inlined sites (``_pair_value`` for a whole node,
``_pairs_through`` for the two pairs through a node that changed), and a
mirrored grid evaluates each pair from the other side of the ring. The
arguments are the same in every case (the axis neighbour's value, the
diagonal one's, the crossed cell's cost, the edge cell's; checked on the pair
tables), so the value is too: every consistent node's value equals the least
of its eight pairs recomputed here with ``corner_cost``'s Python function, bit
for bit, after fresh plans and after repairs; and the settled node values of
the eight drawings of a grid (quarter turns and mirror images) are the same
floats. (Review 41: 51,059 and 88,615 nodes of random grids, none apart.)
Paths may still differ between drawings: the walk takes the first of tied
candidates (see the class notes).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from test_review40_planrev_field_dstar_ties import settled

from navkit.errors import NoPathError
from navkit.planning import FieldDStar
from navkit.planning.grid import _dstar_lite_kernels as kernels

INF = math.inf
CORNER_COST = kernels.corner_cost.py_func

#: The eight drawings of an array (its quarter turns and their mirror images).
DRAWINGS: list[Callable[[np.ndarray], np.ndarray]] = [
    lambda a: a,
    np.rot90,
    lambda a: np.rot90(a, 2),
    lambda a: np.rot90(a, 3),
    np.flipud,
    np.fliplr,
    np.transpose,
    lambda a: np.rot90(a, 2).T,
]


def pair_value(planner: FieldDStar, i: int, j: int, k: int) -> float:
    """Pair k of node (i, j) as the kernel's ``_pair_value`` evaluates it."""
    pad, width, ncols, g = planner._pad, planner._width, planner._ncols, planner._g
    base = i * width + j
    c = float(pad[base + kernels.PAIR_CR[k] * width + kernels.PAIR_CC[k]])
    b = float(pad[base + kernels.PAIR_BR[k] * width + kernels.PAIR_BC[k]])
    if c == INF and b == INF:
        return INF
    # Either cell is passable, so the axis node is on the grid; with c passable the
    # diagonal node is too.
    g1 = float(g[(i + kernels.PAIR_AR[k]) * ncols + j + kernels.PAIR_AC[k]])
    if c == INF:
        return b + g1
    g2 = float(g[(i + kernels.PAIR_DR[k]) * ncols + j + kernels.PAIR_DC[k]])
    return float(CORNER_COST(g1, g2, c, b, planner._interp))


def assert_values_are_their_pairs(planner: FieldDStar) -> int:
    """Every consistent node but the goal is the least of its pairs, bit for bit."""
    rows, cols = planner._nrows, planner._ncols
    g = np.asarray(planner._g)
    rhs = np.asarray(planner._rhs)
    assert planner._goal is not None
    checked = 0
    for i in range(rows):
        for j in range(cols):
            s = i * cols + j
            if (i, j) == planner._goal or not (g[s] == rhs[s] < INF):
                continue
            least = min(pair_value(planner, i, j, k) for k in range(8))
            assert least == rhs[s], ((i, j), least, rhs[s])
            checked += 1
    return checked


costs_and_ends = st.tuples(st.integers(2, 9), st.integers(2, 9)).flatmap(
    lambda shape: st.tuples(
        st.lists(
            st.sampled_from([1.0, 1.0, 1.5, 2.0, 3.7, 1.3, INF]),
            min_size=shape[0] * shape[1],
            max_size=shape[0] * shape[1],
        ).map(lambda v: np.array(v).reshape(shape)),
        st.tuples(st.integers(0, shape[0]), st.integers(0, shape[1])),
        st.tuples(st.integers(0, shape[0]), st.integers(0, shape[1])),
    )
)
options = st.sampled_from([{}, {"lookahead": False}, {"interpolate": False}])


@settings(max_examples=40)
@given(costs_and_ends, options)
def test_node_values_are_the_same_floats_in_every_drawing(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]], opts: dict[str, bool]
) -> None:
    costs, start, goal = case
    ids = np.arange((costs.shape[0] + 1) * (costs.shape[1] + 1)).reshape(
        costs.shape[0] + 1, costs.shape[1] + 1
    )
    first: np.ndarray | None = None
    for draw in DRAWINGS:
        drawn = draw(ids)
        s = tuple(int(v) for v in np.argwhere(drawn == ids[start])[0])
        t = tuple(int(v) for v in np.argwhere(drawn == ids[goal])[0])
        planner = FieldDStar(np.ascontiguousarray(draw(costs)), **opts)
        try:
            planner.plan(s, t)
        except (NoPathError, ValueError):
            return  # an end on impassable cells only, or no way (in every drawing)
        assert_values_are_their_pairs(planner)
        g, done = settled(planner, (s[0], s[1]))
        # Back in the first drawing's places: NaN where not settled.
        values = np.full(ids.size, np.nan)
        values[drawn[done]] = g[done]
        if first is None:
            first = values
            continue
        both = ~np.isnan(first) & ~np.isnan(values)
        np.testing.assert_array_equal(values[both], first[both])


@settings(max_examples=25)
@given(costs_and_ends, options)
def test_repaired_values_are_their_pairs(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]], opts: dict[str, bool]
) -> None:
    costs, start, goal = case
    planner = FieldDStar(costs, **opts)
    try:
        planner.plan(start, goal)
    except (NoPathError, ValueError):
        return
    assert_values_are_their_pairs(planner)
    rows, cols = costs.shape
    for step in range(3):
        # _pairs_through lowers the neighbours of each node whose value changed.
        cell = np.array([[(step * 7 + start[0]) % rows, (step * 5 + goal[1]) % cols]])
        planner.update_costs(cell, [1.0, INF, 2.0][step])
        try:
            planner.replan()
        except (NoPathError, ValueError):
            return
        assert_values_are_their_pairs(planner)
