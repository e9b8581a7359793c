"""The distance field's padded border is written, not found blocked by luck (mutation review).

The bucket-queue kernel pads the grid with a border of impassable cells so no move needs a
bounds test; the border's traversability bytes live in an ``np.empty`` array. Mutants that
skip writing one side of the border (or write it one cell off) survived every other test:
fresh memory from the allocator is zeros, which reads as "blocked" anyway. Here the memory
the field's scratch arrays are about to receive is first filled with 0xFF bytes (NumPy's
small-buffer cache and the C allocator hand a just-freed block of the same size back), and a
wall across the whole grid must still separate its two halves: a border cell wrongly read as
free would join them around the end of the wall. Oracle: SciPy's Dijkstra on the grid graph
(``grid_oracle``), in which the far side of the wall is unreachable.
"""

from __future__ import annotations

import numpy as np
import pytest
from grid_oracle import scipy_costs_from

from navkit.planning import distance_field


def _poison_allocator(n_bytes: int) -> None:
    """Leave freed blocks of ``n_bytes`` (and the float64 size of as many cells) full of 0xFF."""
    blocks = [np.full(n, 0xFF, dtype=np.uint8) for n in (n_bytes, 8 * n_bytes) for _ in range(6)]
    del blocks


def _walled(rows: int, cols: int, horizontal: bool, uniform: bool) -> np.ndarray:
    rng = np.random.default_rng(rows * 100 + cols)
    costs = np.ones((rows, cols)) if uniform else 1.0 + rng.random((rows, cols))
    if horizontal:
        costs[rows // 2, :] = np.inf  # bypassed only through the left or right border
    else:
        costs[:, cols // 2] = np.inf  # bypassed only through the top or bottom border
    return costs


@pytest.mark.parametrize("uniform", [True, False])
@pytest.mark.parametrize("horizontal", [True, False])
@pytest.mark.parametrize(("connectivity", "corner_cutting"), [(4, False), (8, False), (8, True)])
def test_a_wall_across_the_grid_is_not_bypassed_through_the_border(
    uniform: bool, horizontal: bool, connectivity: int, corner_cutting: bool
) -> None:
    rows, cols = 5, 7
    costs = _walled(rows, cols, horizontal, uniform)
    n_padded = (rows + 2) * (cols + 2)
    # Goals in every corner region: each side of the border is next to a goal's half.
    for goal in ((0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)):
        expected = scipy_costs_from(costs, goal, connectivity, corner_cutting)
        # The far half of the wall is unreachable in the oracle.
        far = (slice(rows // 2 + 1, None) if goal[0] == 0 else slice(0, rows // 2), slice(None))
        if not horizontal:
            far = (slice(None), slice(cols // 2 + 1, None) if goal[1] == 0 else slice(0, cols // 2))
        assert np.all(np.isinf(expected[far]))
        for _ in range(3):
            _poison_allocator(n_padded)
            field = distance_field(
                costs, goal, connectivity=connectivity, corner_cutting=corner_cutting
            )
            np.testing.assert_allclose(field, expected, rtol=1e-12)
            assert np.array_equal(np.isinf(field), np.isinf(expected))


@pytest.mark.parametrize(("connectivity", "dearest"), [(4, 60.0), (8, 40.0)])
def test_long_runs_of_empty_buckets_do_not_end_the_search(
    connectivity: int, dearest: float
) -> None:
    # A corridor of the dearest cells from a goal of the cheapest: each move skips
    # dearest / cheapest - 1 buckets, close to the whole ring (the widest cost range the
    # bucket queue takes, 64 slots). The search ends only after a whole ring of empty
    # buckets; a mutant ending it after half a ring left the corridor unreached.
    costs = np.full((3, 12), np.inf)
    costs[1, :] = dearest
    costs[1, 0] = 1.0
    costs[0, 5] = costs[2, 7] = dearest  # dead ends beside the corridor
    goal = (1, 0)
    expected = scipy_costs_from(costs, goal, connectivity, False)
    field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=False)
    np.testing.assert_allclose(field, expected, rtol=1e-12)
    assert np.array_equal(np.isinf(field), np.isinf(expected))
