"""validate_costs refuses more cells than the grid planners take, before allocating.

A broadcast 50000 × 50000 cost grid (a view of one number, no memory) reached
its float64 conversion and failed with NumPy's MemoryError for 18.6 GiB (or,
where the system overcommits, filled the memory). The grid planners refuse
more than 2**31 - 1 cells before converting; ``validate_costs`` now does too,
with a ValueError naming the argument (review 21, known defects).
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import navkit._shared.costs as shared_costs
from navkit.mapping import validate_costs
from navkit.planning.grid._search_heap import MAX_NODES


def test_the_limit_is_the_grid_planners() -> None:
    assert shared_costs.MAX_COST_CELLS == MAX_NODES == 2**31 - 1


@pytest.mark.parametrize("value", [1.0, np.int32(2), np.array(3.0, dtype=object)])
def test_a_broadcast_50000_square_is_refused_without_allocating(value: object) -> None:
    grid = np.broadcast_to(np.asarray(value), (50000, 50000))
    with pytest.raises(ValueError):  # first: what a first call imports is not counted
        validate_costs(grid)
    tracemalloc.start()
    try:
        with pytest.raises(ValueError) as info:
            validate_costs(grid)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert str(info.value) == (
        "costs has 2.5e+09 cells (shape (50000, 50000), 18.6 GiB as float64); cost grids, "
        "like the grid planners, take at most 2**31 - 1 = 2147483647 cells"
    )
    assert peak < 1 << 20  # nothing converted (the object array's items not listed either)


@given(rows=st.integers(1, 12), cols=st.integers(1, 12), limit=st.integers(1, 100))
def test_refused_exactly_above_the_limit(rows: int, cols: int, limit: int) -> None:
    costs = np.ones((rows, cols))
    costs[0, 0] = np.inf
    before = costs.copy()
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(shared_costs, "MAX_COST_CELLS", limit)
        if rows * cols > limit:
            with pytest.raises(ValueError, match=rf"^costs has {rows * cols} cells \(shape "):
                validate_costs(costs)
        else:
            assert validate_costs(costs) is costs  # taken as it is
    np.testing.assert_array_equal(costs, before)


def test_other_mistakes_are_reported_as_before_at_any_size(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(shared_costs, "MAX_COST_CELLS", 4)
    with pytest.raises(ValueError, match="must be 2-D"):
        validate_costs(np.ones((3, 3, 3)))
    with pytest.raises(ValueError, match="must be 2-D"):
        validate_costs(np.ones(9))
    with pytest.raises(ValueError, match=">= 1 where traversable"):
        validate_costs(np.zeros((2, 2)))
