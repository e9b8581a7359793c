"""Review 9: distance fields on uniform grids whose walls touch the grid's edges.

Mutation testing showed that nothing checked the bucket-queue kernel's
impassable border on uniform grids (where costs are not read, only the
traversability mask): a free border column would let paths run just outside
the grid around a wall that touches its edge. The fields are compared with a
plain-Python Dijkstra over the documented graph.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
import pytest

from navkit.planning import distance_field


def _reference(costs: np.ndarray, goal: tuple[int, int], eight: bool, cutting: bool) -> np.ndarray:
    """Dijkstra over the documented moves: step·(c_u + c_v)/2, MovingAI corner rule."""
    rows, cols = costs.shape
    free = np.isfinite(costs)
    dist = np.full(costs.shape, np.inf)
    dist[goal] = 0.0
    queue = [(0.0, goal)]
    moves = [(-1, 0), (1, 0), (0, -1), (0, 1)]
    if eight:
        moves += [(-1, -1), (-1, 1), (1, -1), (1, 1)]
    while queue:
        g, (r, c) = heapq.heappop(queue)
        if g > dist[r, c]:
            continue
        for dr, dc in moves:
            nr, nc = r + dr, c + dc
            if not (0 <= nr < rows and 0 <= nc < cols and free[nr, nc]):
                continue
            if dr and dc and not cutting and not (free[r + dr, c] and free[r, c + dc]):
                continue
            step = math.sqrt(2.0) if dr and dc else 1.0
            new = g + step * (costs[r, c] + costs[nr, nc]) / 2.0
            if new < dist[nr, nc]:
                dist[nr, nc] = new
                heapq.heappush(queue, (new, (nr, nc)))
    return dist


def _walls_to_every_edge(value: float) -> np.ndarray:
    """A 9 × 9 grid of one cost with four walls, each touching one edge of the grid."""
    costs = np.full((9, 9), value)
    costs[2, 2:] = np.inf  # touches the right edge
    costs[6, :7] = np.inf  # touches the left edge
    costs[:2, 5] = np.inf  # touches the top edge
    costs[7:, 3] = np.inf  # touches the bottom edge
    return costs


@pytest.mark.parametrize("value", [1.0, 7.0])
@pytest.mark.parametrize(("connectivity", "cutting"), [(8, False), (8, True), (4, False)])
@pytest.mark.parametrize("goal", [(0, 8), (8, 0), (0, 0), (8, 8), (4, 4)])
def test_paths_never_leave_the_grid_around_walls_at_its_edges(
    value: float, connectivity: int, cutting: bool, goal: tuple[int, int]
) -> None:
    costs = _walls_to_every_edge(value)
    field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=cutting)
    expected = _reference(costs, goal, connectivity == 8, cutting)
    np.testing.assert_array_equal(np.isinf(field), np.isinf(expected))
    np.testing.assert_allclose(field, expected, rtol=1e-12)


def test_bucket_ring_holds_the_dearest_diagonal_move() -> None:
    # Costs 1 and 5: an orthogonal move between two cost-5 cells spans 5 buckets and
    # a diagonal one sqrt(2)·5 ≈ 7.1, so a ring sized for the orthogonal move (8 slots)
    # would wrap a diagonal move onto the bucket being expanded. The bucket kernel
    # serves this range (a ratio below about 40), so it must size for the diagonal.
    mismatches = 0
    for seed in range(20):
        rng = np.random.default_rng(seed)
        costs = np.where(rng.random((12, 12)) < 0.7, 5.0, 1.0)
        costs[0, 0] = 1.0
        field = distance_field(costs, (0, 0))
        expected = _reference(costs, (0, 0), True, False)
        mismatches += not np.allclose(field, expected, rtol=1e-12)
    assert mismatches == 0
