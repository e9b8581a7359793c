"""What a MapPlanner keeps per cell, as its docstring says (review 29, SIMMEM).

``MapPlanner(planner="field_dstar")`` keeps its costs beside Field D*'s padded
copy (8 of its 68 bytes a cell). The duplicate stays: :attr:`MapPlanner.costs`
is a read-only C-contiguous array of its own, which a view into the planner's
padded costs (strided, written by ``update_costs``) would not be, and sums or
kernels over a strided view may round differently. The docstring now gives the
memory per cell; these tests hold the planner to it.
"""

from __future__ import annotations

import copy
import tracemalloc
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning.grid import FieldDStar, MapPlanner

N = 400


def _grid() -> OccupancyGrid:
    occupied = np.zeros((N, N), dtype=bool)
    occupied[: N - 40, N // 2 : N // 2 + 4] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05)


def _mapped_bytes(made: Any) -> int:
    """Bytes of the Field D* queue in pages mapped on their own (unseen by tracemalloc).

    Since review 37 (FDFRESH) a large queue's keys and nodes are anonymous
    mappings, zeroed by the kernel where a search first writes: kept all the
    same (address space, and memory where written).
    """
    fd = getattr(made, "_prepared", None)
    if not isinstance(fd, FieldDStar):
        return 0
    total = 0
    for arr in fd._heap[:2]:
        base = arr
        while isinstance(base, np.ndarray) and base.base is not None:
            base = base.base
        if isinstance(base, memoryview):
            total += arr.nbytes
    return total


def _kept_per_cell(make: Callable[[], Any]) -> tuple[float, Any]:
    """Bytes a cell still allocated once ``make`` returned (its result kept)."""
    make()
    tracemalloc.start()
    try:
        before, _ = tracemalloc.get_traced_memory()
        made = make()
        after, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return (after - before + _mapped_bytes(made)) / (N * N), made


@pytest.mark.parametrize(
    ("planner", "low", "high"), [("astar", 11.0, 13.5), ("field_dstar", 66.0, 71.0)]
)
def test_a_planner_keeps_the_documented_bytes_a_cell(planner: str, low: float, high: float) -> None:
    grid = _grid()
    kept, made = _kept_per_cell(lambda: MapPlanner(grid, robot_radius=0.1, planner=planner))
    # 12 and 68 documented (68 = 12 + Field D*'s 56 a node, (N + 1)² nodes).
    assert low < kept < high, kept
    assert isinstance(made._prepared, FieldDStar) == (planner == "field_dstar")


def test_a_copy_of_a_field_dstar_planner_adds_only_its_search_state() -> None:
    planner = MapPlanner(_grid(), robot_radius=0.1, planner="field_dstar")
    kept, twin = _kept_per_cell(lambda: copy.copy(planner))
    assert 54.0 < kept < 59.0, kept  # 56 a node documented: the costs stay shared
    assert twin.costs is planner.costs


def test_the_costs_are_their_own_array_untouched_by_searches() -> None:
    planner = MapPlanner(_grid(), robot_radius=0.1, planner="field_dstar")
    costs = planner.costs
    kept = costs.copy()
    assert costs.flags.c_contiguous and not costs.flags.writeable and costs.dtype == np.float64
    assert not np.shares_memory(costs, planner._prepared._pad)
    for start, goal in (((0.5, 0.5), (19.0, 0.5)), ((19.0, 18.0), (0.5, 19.0))):
        planner.plan(start, goal)
    assert planner.costs is costs
    np.testing.assert_array_equal(costs, kept)
