"""Peak memory of whole-grid distance fields (review 10).

The bucket-queue Dijkstra of :func:`distance_field` works on a padded copy of
the grid: a traversable flag (1 byte a cell), the padded costs (8, none on a
uniform grid) and the padded field (8), which becomes the float64 result in
place. The earlier code copied the field's interior into a second array (25
bytes a cell on a grid of varied costs, 17 on a uniform one). Bounds: peak
NumPy allocations (tracemalloc) in bytes a cell, with margin.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.planning import AStarPlanner, distance_field

SIDE = 1000
CELLS = SIDE * SIDE
GOAL = (SIDE // 2, SIDE // 2)


def _peak_per_cell(call: Callable[[], Any]) -> float:
    """Peak bytes a cell allocated while ``call`` runs (its result included)."""
    return peak_bytes(call)[0] / CELLS


def _costs(uniform: bool) -> np.ndarray:
    rng = np.random.default_rng(0)
    costs = np.ones((SIDE, SIDE)) if uniform else 1.0 + 3.0 * rng.random((SIDE, SIDE))
    costs[rng.random((SIDE, SIDE)) < 0.2] = np.inf
    costs[GOAL] = 1.0
    return costs


@pytest.mark.parametrize(("uniform", "bound"), [(True, 12.0), (False, 21.0)])
def test_distance_field_result_is_the_padded_field(uniform: bool, bound: float) -> None:
    costs = _costs(uniform)
    assert _peak_per_cell(lambda: distance_field(costs, GOAL)) < bound
    planner = AStarPlanner(costs)
    assert _peak_per_cell(lambda: planner.distance_field(GOAL)) < bound


def test_field_is_a_fresh_writable_c_contiguous_array() -> None:
    costs = _costs(False)[:50, :70].copy()
    costs[10, 10] = 1.0
    field = distance_field(costs, (10, 10))
    assert field.shape == (50, 70) and field.dtype == np.float64
    assert field.flags.c_contiguous and field.flags.writeable
    assert not np.shares_memory(field, costs)
    field[0, 0] = -1.0  # its own memory: a second call is unaffected
    again = distance_field(costs, (10, 10))
    assert again[10, 10] == 0.0 and again[0, 0] != -1.0
