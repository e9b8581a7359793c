"""Jump point search through one-cell corridors (corner pass-through) stays exact.

JPS passes through corridor corners that have a single way on instead of
queueing them (issue 17); these mazes, with loops and dead ends, check its
costs against A* on every pair of a sample of cells, and its paths for
validity.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.planning import AStarPlanner


def corridor_maze(half: int, loops: float, seed: int) -> np.ndarray:
    """A (2 half + 1)² maze of one-cell corridors: a random spanning tree plus extra openings."""
    rng = np.random.default_rng(seed)
    size = 2 * half + 1
    costs = np.full((size, size), np.inf)
    seen = np.zeros((half, half), dtype=bool)
    stack = [(0, 0)]
    seen[0, 0] = True
    costs[1, 1] = 1.0
    while stack:
        i, j = stack[-1]
        options = [
            (i + di, j + dj)
            for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
            if 0 <= i + di < half and 0 <= j + dj < half and not seen[i + di, j + dj]
        ]
        if not options:
            stack.pop()
            continue
        ni, nj = options[rng.integers(len(options))]
        seen[ni, nj] = True
        costs[2 * ni + 1, 2 * nj + 1] = 1.0
        costs[i + ni + 1, j + nj + 1] = 1.0
        stack.append((ni, nj))
    # Extra openings in the walls between cells make loops.
    for r in range(1, size - 1):
        for c in range(1, size - 1):
            if (r + c) % 2 == 1 and costs[r, c] == np.inf and rng.random() < loops:
                costs[r, c] = 1.0
    return costs


def _valid(cells: np.ndarray, costs: np.ndarray) -> None:
    assert np.isfinite(costs[cells[:, 0], cells[:, 1]]).all()
    steps = np.abs(np.diff(cells, axis=0))
    assert (steps.max(axis=1) == 1).all()
    for (r, c), (dr, dc) in zip(cells[:-1], np.diff(cells, axis=0), strict=True):
        if dr and dc:  # no corner cutting
            assert np.isfinite(costs[r + dr, c]) and np.isfinite(costs[r, c + dc])


@pytest.mark.parametrize("loops", [0.0, 0.05, 0.3])
@pytest.mark.parametrize("seed", [0, 1])
def test_jps_costs_equal_astar_in_corridor_mazes(loops: float, seed: int) -> None:
    costs = corridor_maze(20, loops, seed)
    jps = AStarPlanner(costs, method="jps")
    reference = AStarPlanner(costs)
    free = np.argwhere(np.isfinite(costs))
    rng = np.random.default_rng(seed + 10)
    picks = free[rng.choice(len(free), size=(40, 2))]
    for start, goal in picks:
        s, t = (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1]))
        expected = reference.plan(s, t)
        path = jps.plan(s, t)
        assert path.cost == pytest.approx(expected.cost, rel=1e-12)
        assert path.cells[0].tolist() == list(s) and path.cells[-1].tolist() == list(t)
        _valid(path.cells, costs)


def test_jps_in_a_corridor_maze_with_a_walled_off_goal() -> None:
    costs = corridor_maze(10, 0.1, 3)
    costs[18:21, 18:21] = np.inf
    costs[19, 19] = 1.0
    with pytest.raises(NoPathError):
        AStarPlanner(costs, method="jps").plan((1, 1), (19, 19))
