"""A cost grid in a misaligned buffer reaches the grid kernels as an aligned copy (review 46).

``np.ascontiguousarray`` keeps a float64 view of bytes at an odd offset as
it is, and numba's dispatcher types such an array as an *aligned* one
(``numba.typeof`` does not look at the alignment flag), so the A*, JPS and
distance-field kernels read the caller's buffer with loads LLVM assumes
8-byte aligned: undefined behaviour, harmless on x86-64 and AArch64 only
because they execute such loads as unaligned ones. The converter every grid
planner calls (:func:`~navkit.planning.grid._limits.converted_costs`) now
copies a misaligned grid; aligned ones are still used in place.
"""

from __future__ import annotations

import numpy as np
import pytest

from misaligned_arrays import misaligned
from navkit.planning import AStarPlanner, astar, distance_field
from navkit.planning.grid import _astar
from navkit.planning.grid._limits import checked_cost_range, converted_costs


def corridor() -> np.ndarray:
    costs = np.ones((30, 41))
    costs[3:27, 20] = np.inf
    costs[10, 5:35] = 2.0
    return costs


def test_the_converters_copy_a_misaligned_grid_and_keep_an_aligned_one() -> None:
    costs = corridor()
    odd = misaligned(costs, writeable=False)
    for grid in (
        converted_costs(odd),
        checked_cost_range(odd)[0],
        _astar._checked_grid(odd, 8, False, 1.0, "jps")[0],
        _astar._checked_grid(odd, 8, False, 1.0, "astar")[0],
    ):
        assert grid.flags.aligned and grid.flags.c_contiguous
        assert not np.shares_memory(grid, odd)
        np.testing.assert_array_equal(grid, costs)
    assert converted_costs(costs) is costs
    assert checked_cost_range(costs)[0] is costs
    np.testing.assert_array_equal(odd, costs)


@pytest.mark.parametrize("method", ["astar", "jps"])
def test_searches_on_a_misaligned_grid_are_those_on_its_aligned_copy(method: str) -> None:
    costs = np.where(np.random.default_rng(46).random((40, 50)) < 0.1, np.inf, 1.0)
    costs[0, 0] = costs[39, 49] = 1.0
    odd = misaligned(costs, writeable=False)
    want = astar(costs, (0, 0), (39, 49), method=method)
    for got in (
        astar(odd, (0, 0), (39, 49), method=method),
        AStarPlanner(odd, method=method).plan((0, 0), (39, 49)),
    ):
        np.testing.assert_array_equal(got.cells, want.cells)
        assert (got.cost, got.expanded) == (want.cost, want.expanded)
    field = distance_field(odd, (39, 49))
    np.testing.assert_array_equal(np.asarray(field), np.asarray(distance_field(costs, (39, 49))))
