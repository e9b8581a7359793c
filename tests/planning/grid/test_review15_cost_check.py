"""The compiled cost check of the grid planners agrees with the NumPy one it replaced.

:func:`navkit.planning.grid._limits.checked_cost_range` checks the values in
one compiled pass over their bit patterns (``_scan_cost_bits``) and leaves
naming the culprit to :func:`~navkit.planning.grid._limits.cost_range`, the
NumPy reductions it used before (issue 17, the A* ÷ pyastar2d row). Both must
accept the same grids with the same range and refuse the same grids with the
same message, whatever the value's bit pattern (negative zero, subnormals,
NaN payloads of either sign, the neighbours of 1 and 1e12) and wherever it
lies (first cell, last cell, any block of the NumPy scan).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kernel_signatures import compiled_signatures
from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field
from navkit.planning.grid import _limits


def _bits(pattern: int) -> float:
    return float(np.array(pattern, dtype=np.uint64).view(np.float64))


#: Values at and around every boundary of the accepted set ``[1, 1e12] ∪ {inf}``.
SPECIAL = [
    1.0,
    math.nextafter(1.0, 2.0),
    math.nextafter(1.0, 0.0),
    1e12,
    math.nextafter(1e12, 0.0),
    math.nextafter(1e12, math.inf),
    math.inf,
    -math.inf,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    -1.0,
    np.finfo(np.float64).max,
    math.nan,
    _bits(0x7FF0000000000001),  # signalling NaN, just above inf's pattern
    _bits(0x7FFFFFFFFFFFFFFF),  # the largest positive pattern
    _bits(0xFFF8000000000000),  # NaN with its sign bit set
    _bits(0x8000000000000001),  # the negative subnormal next to -0.0
    2.0,
    1234.5,
]


def numpy_check(costs: Any) -> tuple[np.ndarray, float, float]:
    """The check as it was: conversion, then the NumPy reductions of ``cost_range``."""
    grid = _limits.converted_costs(costs)
    lowest, highest = _limits.cost_range(grid)
    return grid, lowest, highest


def outcome(check: Any, costs: Any) -> tuple[str, Any]:
    """("ok", (lowest, highest)) or ("error", (type, message)) of ``check(costs)``."""
    try:
        _, lowest, highest = check(costs)
    except (ValueError, TypeError) as exc:
        return "error", (type(exc), str(exc))
    return "ok", (lowest, highest)


def same_outcome(costs: Any) -> None:
    new = outcome(_limits.checked_cost_range, costs)
    old = outcome(numpy_check, costs)
    assert new == old


@pytest.mark.parametrize("value", SPECIAL, ids=[repr(v) for v in SPECIAL])
@pytest.mark.parametrize("where", ["first", "middle", "last"])
def test_each_boundary_value_is_judged_as_by_numpy(value: float, where: str) -> None:
    costs = np.full((5, 7), 3.0)
    costs[2, ::2] = np.inf
    cell = {"first": (0, 0), "middle": (2, 3), "last": (4, 6)}[where]
    costs[cell] = value
    before = costs.copy()
    same_outcome(costs)
    accepted = value == math.inf or 1.0 <= value <= 1e12
    status, detail = outcome(_limits.checked_cost_range, costs)
    assert status == ("ok" if accepted else "error")
    if accepted:
        finite = costs[np.isfinite(costs)]
        assert detail == (float(costs.min()), float(finite.max()))
    assert np.array_equal(costs.view(np.int64), before.view(np.int64))  # not modified


def test_the_culprit_is_named_in_a_later_block() -> None:
    # 70_000 cells: the NumPy scan's second block (65_536 cells a block).
    costs = np.full((200, 350), 2.0)
    costs[::9, ::4] = np.inf
    costs[199, 300] = 4e12
    with pytest.raises(ValueError, match=r"<= 1e\+12 .* found 4000000000000\.0 at \(199, 300\)"):
        _limits.checked_cost_range(costs)
    same_outcome(costs)
    costs[199, 300] = 7.0
    assert _limits.checked_cost_range(costs)[1:] == (2.0, 7.0)


def test_grids_without_a_finite_cost() -> None:
    assert _limits.checked_cost_range(np.full((3, 4), np.inf))[1:] == (math.inf, -math.inf)
    same_outcome(np.full((3, 4), np.inf))
    same_outcome(np.full((1, 1), -np.inf))


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.int32, np.uint8, np.int64])
def test_converted_dtypes_and_read_only_input(dtype: Any) -> None:
    costs = np.array([[1, 5, 200], [7, 1, 3]], dtype=dtype)
    costs.flags.writeable = False
    grid, lowest, highest = _limits.checked_cost_range(costs)
    assert grid.dtype == np.float64 and grid.flags.c_contiguous
    assert (lowest, highest) == (1.0, 200.0)
    zero = np.array([[1, 0], [2, 3]], dtype=dtype)
    same_outcome(zero)
    with pytest.raises(ValueError, match="costs"):
        _limits.checked_cost_range(zero)


def test_a_strided_view_is_checked_by_its_values() -> None:
    base = np.full((6, 8), 2.0)
    base[:, 1::2] = 0.25  # only in the columns the view skips
    base[3, 4] = np.inf
    view = base[:, ::2]
    assert _limits.checked_cost_range(view)[1:] == (2.0, 2.0)
    same_outcome(view)
    same_outcome(base[::-1, 1::2])


_values = st.one_of(
    st.sampled_from(SPECIAL),
    st.floats(1.0, 1e12),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(0, 2**64 - 1).map(_bits),
)


@settings(max_examples=300, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 9), st.integers(1, 9)),
    data=st.data(),
)
def test_any_grid_is_judged_as_by_numpy(shape: tuple[int, int], data: st.DataObject) -> None:
    rows, cols = shape
    fill = data.draw(st.sampled_from([1.0, 2.5, math.inf, 1e12]), label="fill")
    costs = np.full(shape, fill)
    for _ in range(data.draw(st.integers(0, 4), label="changes")):
        r = data.draw(st.integers(0, rows - 1), label="row")
        c = data.draw(st.integers(0, cols - 1), label="col")
        costs[r, c] = data.draw(_values, label="value")
    same_outcome(costs)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(
    block=st.integers(0, 3),
    offset=st.integers(0, 65_535),
    value=st.sampled_from([v for v in SPECIAL if not (v == math.inf or 1.0 <= v <= 1e12)]),
)
def test_a_bad_value_in_any_block_of_a_large_grid(block: int, offset: int, value: float) -> None:
    costs = np.full(4 * 65_536, 1.5)
    costs[::11] = np.inf
    costs[4 * 65_536 - 1] = 80.0
    index = block * 65_536 + offset
    costs[index] = value
    grid = costs.reshape(512, 512)
    status, detail = outcome(_limits.checked_cost_range, grid)
    assert status == "error"
    assert detail == outcome(numpy_check, grid)[1]


def test_planners_report_the_same_errors() -> None:
    costs = np.ones((4, 5))
    costs[2, 3] = math.nextafter(1e12, math.inf)
    message = outcome(numpy_check, costs)[1][1]
    for call in (
        lambda: astar(costs, (0, 0), (3, 4)),
        lambda: astar(costs, (0, 0), (3, 4), connectivity=4, heuristic_weight=2.0),
        lambda: AStarPlanner(costs),
        lambda: distance_field(costs, (0, 0)),
        lambda: FieldDStar(costs),
    ):
        with pytest.raises(ValueError) as info:
            call()
        assert str(info.value) == message


SCRIPT = """
import numpy as np
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, astar, distance_field
costs = np.ones((12, 12))
costs[2:9, 5] = np.inf
ro = costs.copy()
ro.flags.writeable = False
astar(costs, (0, 0), (11, 11))
astar(ro, (0, 0), (11, 11), connectivity=4)
astar(np.ones((12, 12), dtype=np.int32), (0, 0), (11, 11), heuristic_weight=0.5)
AStarPlanner(costs[:, ::2])
distance_field(costs, (0, 0))
distance_field(ro.astype(np.float32), (0, 0))
FieldDStar(costs + 1.0)
MapPlanner(OccupancyGrid.from_occupancy(np.zeros((8, 9), dtype=bool), resolution=0.1))
"""


def test_the_scan_kernel_is_compiled_for_one_signature() -> None:
    # Every validating entry point, every input kind: one compilation of the scan.
    signatures = compiled_signatures(SCRIPT, ["navkit.planning.grid._limits"])
    assert list(signatures) == ["_limits._scan_cost_bits"]
    assert len(signatures["_limits._scan_cost_bits"]) == 1
