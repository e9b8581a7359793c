"""Field D* settle (review 15): the two pairs through an expanded node, read once.

When a node u's value falls, each neighbour s recomputes only its pairs m-1 and m
(u is ring[m] of s). ``_pairs_through`` evaluates both with the cells and g(u) they
share read once; it must give, bit for bit, what the former code gave: the least
(second pair only when strictly below) of ``_pair_value`` for the two pairs. The
kernel below runs both on random grids, with impassable cells (also at the
border, where a pair's far nodes are off the grid) and tied or infinite values.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

from hypothesis_twins import slow_twin
from navkit.planning import FieldDStar
from navkit.planning.grid._dstar_heap import RECORD
from navkit.planning.grid._dstar_lite_kernels import (
    RING_C,
    RING_R,
    _pair_value,
    _pairs_through,
)


@njit(cache=False)
def _both(
    pad: np.ndarray, width: int, vals: np.ndarray, nrows: int, ncols: int, interp: bool
) -> tuple[np.ndarray, np.ndarray]:
    """(new, former) value for every node s and every m with u = s + ring[m] on the grid."""
    new = np.full((nrows * ncols, 8), np.nan)
    old = np.full((nrows * ncols, 8), np.nan)
    for i in range(nrows):
        for j in range(ncols):
            for m in range(8):
                ui = i + RING_R[m]
                uj = j + RING_C[m]
                if ui < 0 or ui >= nrows or uj < 0 or uj >= ncols:
                    continue
                gu = vals[RECORD * (ui * ncols + uj)]
                new[i * ncols + j, m] = _pairs_through(pad, width, vals, ncols, i, j, m, gu, interp)
                # The former code: pair m, then pair m-1 where strictly below.
                v = _pair_value(pad, width, vals, ncols, i, j, m, interp)
                v2 = _pair_value(pad, width, vals, ncols, i, j, m - 1 if m > 0 else 7, interp)
                if v2 < v:
                    v = v2
                old[i * ncols + j, m] = v
    return new, old


# Few distinct values: ties between options and between pairs are common.
COST = st.sampled_from([1.0, 1.25, 2.0, 3.5, 7.0, np.inf])
G = st.one_of(st.sampled_from([0.0, 1.0, 1.5, 2.0, np.inf]), st.floats(0.0, 30.0))


@st.composite
def grids(draw: Any) -> tuple[np.ndarray, np.ndarray]:
    rows = draw(st.integers(1, 5))
    cols = draw(st.integers(1, 5))
    costs = np.array(draw(st.lists(COST, min_size=rows * cols, max_size=rows * cols)))
    g = np.array(draw(st.lists(G, min_size=(rows + 1) * (cols + 1),
                               max_size=(rows + 1) * (cols + 1))))
    return costs.reshape(rows, cols), g


def _run(costs: np.ndarray, g: np.ndarray, interp: bool) -> tuple[np.ndarray, np.ndarray]:
    rows, cols = costs.shape
    pad = np.full((rows + 2, cols + 2), np.inf)
    pad[1:-1, 1:-1] = costs
    # Records as the planner holds them: g, rhs (unused here, NaN) and the heap slot.
    records = np.full((g.size, RECORD), np.nan)
    records[:, 0] = g
    return _both(pad.ravel(), cols + 2, records.ravel(), rows + 1, cols + 1, interp)


@pytest.mark.parametrize("interp", [True, False])
@settings(max_examples=80, deadline=None)
@given(grid=grids())
def test_pairs_through_u_equal_the_former_two_pair_values_bit_for_bit(
    grid: tuple[np.ndarray, np.ndarray], interp: bool
) -> None:
    new, old = _run(*grid, interp)
    # Bit patterns, so that -0.0 / 0.0 or a NaN would differ too.
    np.testing.assert_array_equal(new.view(np.int64), old.view(np.int64))


test_pairs_through_u_equal_the_former_two_pair_values_bit_for_bit_thoroughly = slow_twin(
    test_pairs_through_u_equal_the_former_two_pair_values_bit_for_bit, max_examples=600
)


def test_every_pair_case_is_reached_on_a_dense_grid() -> None:
    # A fixed grid with every cell pattern around an axis and a diagonal u (both
    # cells beside the edge passable, one of them, neither), the values spread
    # so that each option of corner_cost wins somewhere.
    rng = np.random.default_rng(15)
    costs = rng.choice([1.0, 1.5, 2.5, 6.0, np.inf], size=(9, 11))
    g = rng.uniform(0.0, 12.0, size=10 * 12)
    g[rng.random(g.size) < 0.1] = np.inf
    for interp in (True, False):
        new, old = _run(costs, g, interp)
        np.testing.assert_array_equal(new.view(np.int64), old.view(np.int64))
        finite = np.isfinite(new)
        assert finite.sum() > 200 and (~finite & ~np.isnan(new)).sum() > 20


@pytest.mark.parametrize("interpolate", [True, False])
def test_repairs_still_equal_fresh_plans_value_for_value(interpolate: bool) -> None:
    # Every search lowers values through _pairs_through: a repaired planner must
    # end with the path, the cost and the start's value of a fresh plan.
    rng = np.random.default_rng(1515)
    costs = rng.uniform(1.0, 4.0, (30, 34))
    costs[rng.random(costs.shape) < 0.2] = np.inf
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    planner = FieldDStar(costs, interpolate=interpolate)
    planner.plan((0, 0), (30, 34))
    for step in range(4):
        cells = [tuple(int(v) for v in rng.integers(2, 28, 2)) for _ in range(3)]
        new = rng.uniform(1.0, 6.0, 3)
        new[step % 3] = np.inf
        planner.update_costs(cells, new)
        for cell, value in zip(cells, new, strict=True):
            costs[cell] = value
        got = planner.replan()
        fresh_planner = FieldDStar(costs, interpolate=interpolate)
        fresh = fresh_planner.plan((0, 0), (30, 34))
        np.testing.assert_array_equal(got.points, fresh.points)
        assert got.cost == fresh.cost
        assert planner._g[0] == fresh_planner._g[0]
