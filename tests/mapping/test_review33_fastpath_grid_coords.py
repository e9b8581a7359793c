"""``OccupancyGrid.cell_to_world`` and ``world_to_cell(..., continuous=True)`` fast paths.

C-contiguous (N, 2) float64/int64 cells go to a compiled kernel, one cell or one
point as plain floats to Python float arithmetic; the oracle is the same values
byte-swapped (``>f8``/``>i8``), which take the general, validating way.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid

LIM = float(2**62)
_vals = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(-1e4, 1e4),
    st.sampled_from(
        [0.0, -0.0, 5e-324, -5e-324, LIM, -LIM, math.nextafter(LIM, math.inf), 2.0**53, 1e300]
    ),
)
_ints = st.one_of(
    st.integers(-(2**63), 2**63 - 1),
    st.integers(-1000, 1000),
    st.sampled_from([2**62, 2**62 + 1, 2**53 + 1, -(2**62) - 512, -(2**62) - 513]),
)
_grids = st.builds(
    lambda x, y, t, r: OccupancyGrid.empty(
        width=2.0, height=2.0, resolution=r, origin=Pose2D(x, y, t)
    ),
    st.floats(-1e9, 1e9),
    st.floats(-1e9, 1e9),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.05, 0.1, 1e-3, 1.0, 1e6, 0.0123]),
)


def _same(fast: object, general: object) -> None:
    """Both results, or both refusals (same type and message)."""
    assert type(fast) is type(general)
    if isinstance(general, Exception):
        assert str(fast) == str(general)
        return
    assert isinstance(fast, np.ndarray) and isinstance(general, np.ndarray)
    assert fast.dtype == general.dtype and fast.shape == general.shape
    assert fast.tobytes() == general.tobytes(), (fast, general)


def _call(f: object, *args: object, **kw: object) -> object:
    try:
        return f(*args, **kw)  # type: ignore[operator]
    except (TypeError, ValueError) as e:
        return e


@settings(max_examples=300, deadline=None)
@given(
    grid=_grids,
    cells=st.lists(st.tuples(_vals, _vals), max_size=12),
    icells=st.lists(st.tuples(_ints, _ints), min_size=1, max_size=12),
)
def test_cell_to_world_fast_equals_general(
    grid: OccupancyGrid, cells: list[tuple[float, float]], icells: list[tuple[int, int]]
) -> None:
    floats = np.array(cells, dtype=np.float64).reshape(-1, 2)
    ints = np.array(icells, dtype=np.int64)
    c2w = grid.cell_to_world
    _same(_call(c2w, floats), _call(c2w, floats.astype(">f8")))
    _same(_call(c2w, ints), _call(c2w, ints.astype(">i8")))
    first = icells[0]
    _same(_call(c2w, first), _call(c2w, np.array(first, dtype=">i8")))
    if cells:
        for one in (cells[0], list(cells[0]), np.array(cells[0])):
            _same(_call(c2w, one), _call(c2w, np.array(cells[0], dtype=">f8")))


@settings(max_examples=300, deadline=None)
@given(grid=_grids, point=st.tuples(_vals, _vals))
def test_world_to_cell_continuous_fast_equals_general(
    grid: OccupancyGrid, point: tuple[float, float]
) -> None:
    general = _call(grid.world_to_cell, np.array(point, dtype=">f8"), continuous=True)
    for one in (point, list(point), np.array(point), [np.float64(v) for v in point]):
        _same(_call(grid.world_to_cell, one, continuous=True), general)


@pytest.mark.parametrize(
    "bad",
    [
        [math.nan, 0.0],
        (0.0, math.inf),
        [1.0, 2.0, 3.0],
        np.array([[0.0, math.nan]]),
        np.array([[2.0**63, 0.0]]),
        ["a", 1.0],
        [2**63, 0],
    ],
)
def test_refusals_unchanged(bad: object) -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
    general = np.array(bad, dtype=object)[None] if not isinstance(bad, np.ndarray) else None
    calls = [grid.cell_to_world]
    beyond = np.array(bad, dtype=object).tolist() in ([[2.0**63, 0.0]], [2**63, 0])
    if not beyond:
        # Points beyond ±2**62 cells are valid (clamped); cells there are not.
        calls.append(lambda v: grid.world_to_cell(v, continuous=True))
    for call in calls:
        with pytest.raises((TypeError, ValueError)) as fast:
            call(bad)
        assert "cells" in str(fast.value) or "points_xy" in str(fast.value)
        if general is not None:
            with pytest.raises(type(fast.value)):
                call(general)


def test_layouts_compile_nothing_new_and_inputs_unchanged() -> None:
    # Read-only, unaligned and strided cells: the same answers; the fast path takes the
    # first two through its entries (no new specialisation), the last the general way.
    grid = OccupancyGrid.empty(
        width=5.0, height=4.0, resolution=0.05, origin=Pose2D(-2.0, -1.5, 0.4)
    )
    cells = np.array([[0, 1], [7, 3], [-2, 40]], dtype=np.int64)
    want = grid.cell_to_world(cells.astype(">i8"))
    readonly = cells.copy()
    readonly.flags.writeable = False
    buf = np.zeros(cells.nbytes + 1, dtype=np.uint8)
    unaligned = buf[1:].view(np.int64).reshape(3, 2)
    unaligned[:] = cells
    strided = np.repeat(cells, 2, axis=1)[:, ::2]
    for spelling in (cells, readonly, unaligned, strided):
        before = spelling.copy()
        assert grid.cell_to_world(spelling).tobytes() == want.tobytes()
        assert np.array_equal(spelling, before)
