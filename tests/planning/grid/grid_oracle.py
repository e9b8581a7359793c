"""Independent reference model of navkit's grid graph for the planner tests.

Written as plain Python loops on purpose: it shares no code with the numba
kernels it checks.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse
from hypothesis import strategies as st
from numpy.typing import NDArray
from scipy.sparse.csgraph import dijkstra

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

ORTHO = ((-1, 0), (1, 0), (0, -1), (0, 1))
DIAG = ((-1, -1), (-1, 1), (1, -1), (1, 1))


def move_allowed(
    costs: FloatArray, r: int, c: int, dr: int, dc: int, corner_cutting: bool
) -> bool:
    """Whether the move (r, c) -> (r + dr, c + dc) exists in the graph."""
    rows, cols = costs.shape
    r2, c2 = r + dr, c + dc
    if not (0 <= r2 < rows and 0 <= c2 < cols):
        return False
    if not (math.isfinite(costs[r, c]) and math.isfinite(costs[r2, c2])):
        return False
    if dr != 0 and dc != 0 and not corner_cutting:
        return bool(math.isfinite(costs[r + dr, c]) and math.isfinite(costs[r, c + dc]))
    return True


def move_cost(costs: FloatArray, r: int, c: int, dr: int, dc: int) -> float:
    step = math.sqrt(2.0) if dr != 0 and dc != 0 else 1.0
    return step * (float(costs[r, c]) + float(costs[r + dr, c + dc])) / 2.0


def grid_graph(
    costs: FloatArray, connectivity: int, corner_cutting: bool
) -> scipy.sparse.csr_matrix:
    """The planners' graph as a scipy sparse matrix over flat cell indices."""
    rows, cols = costs.shape
    moves = ORTHO + DIAG if connectivity == 8 else ORTHO
    src: list[int] = []
    dst: list[int] = []
    weight: list[float] = []
    for r in range(rows):
        for c in range(cols):
            for dr, dc in moves:
                if move_allowed(costs, r, c, dr, dc, corner_cutting):
                    src.append(r * cols + c)
                    dst.append((r + dr) * cols + c + dc)
                    weight.append(move_cost(costs, r, c, dr, dc))
    n = rows * cols
    return scipy.sparse.csr_matrix((weight, (src, dst)), shape=(n, n))


def scipy_costs_from(
    costs: FloatArray, source: tuple[int, int], connectivity: int, corner_cutting: bool
) -> FloatArray:
    """Least cost from ``source`` to every cell, shape (rows, cols), by scipy's Dijkstra."""
    graph = grid_graph(costs, connectivity, corner_cutting)
    cols = costs.shape[1]
    dist = dijkstra(graph, directed=True, indices=source[0] * cols + source[1])
    return np.asarray(dist, dtype=np.float64).reshape(costs.shape)


def assert_valid_path(
    costs: FloatArray,
    cells: IntArray,
    start: tuple[int, int],
    goal: tuple[int, int],
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
) -> tuple[float, float]:
    """Check a cell path move by move; return its recomputed (cost, length)."""
    assert cells.ndim == 2 and cells.shape[1] == 2
    assert tuple(cells[0]) == start
    assert tuple(cells[-1]) == goal
    total = 0.0
    length = 0.0
    for (r, c), (r2, c2) in zip(cells[:-1].tolist(), cells[1:].tolist(), strict=True):
        dr, dc = r2 - r, c2 - c
        assert (dr, dc) in ORTHO + DIAG, f"cells {(r, c)} and {(r2, c2)} are not neighbours"
        if connectivity == 4:
            assert (dr, dc) in ORTHO, f"diagonal move {(r, c)} -> {(r2, c2)} in 4-connectivity"
        assert move_allowed(costs, r, c, dr, dc, corner_cutting), (
            f"move {(r, c)} -> {(r2, c2)} crosses an impassable cell or cuts a corner"
        )
        total += move_cost(costs, r, c, dr, dc)
        length += math.hypot(dr, dc)
    return total, length


@st.composite
def weighted_grids(
    draw: st.DrawFn, max_side: int = 8, p_blocked: float = 0.25
) -> tuple[FloatArray, tuple[int, int], tuple[int, int]]:
    """A small random cost grid with a traversable start and goal."""
    rows = draw(st.integers(1, max_side))
    cols = draw(st.integers(1, max_side))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    costs = 1.0 + 4.0 * rng.random((rows, cols))
    # Some grids get integer costs so that exact ties between paths occur.
    if draw(st.booleans()):
        costs = np.floor(costs)
    costs[rng.random((rows, cols)) < p_blocked] = np.inf
    free = np.argwhere(np.isfinite(costs))
    if free.shape[0] == 0:
        costs[0, 0] = 1.0
        free = np.array([[0, 0]])
    i = draw(st.integers(0, free.shape[0] - 1))
    j = draw(st.integers(0, free.shape[0] - 1))
    return costs, (int(free[i, 0]), int(free[i, 1])), (int(free[j, 0]), int(free[j, 1]))
