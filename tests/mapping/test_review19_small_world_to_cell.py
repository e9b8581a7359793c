"""``OccupancyGrid.world_to_cell``: which arrays take the fast path (session 23, issue 17).

The fast path hands ``points_xy`` itself to one compiled entry (session 39,
``navkit.mapping._new_cells_kernel``), which tests in C that it is an exact
ndarray of native float64 with strides ``_PAIR_STRIDES`` (16, 8) and two
columns (sessions 26-38 tested that in Python, before them
``ndarray.flags.num``'s C-contiguous and aligned bits) and returns the cells,
or None for the general path. These tests pin what goes that way: exactly the
exact, C-contiguous (N, 2) float64 ndarrays, aligned or not; a strided or
Fortran-ordered array must reach the general path's entry (which checks
nothing and is compiled for unaligned data) only as a contiguous copy.
The kernel is compiled without numba's reference counting (no per-argument
MemInfo at each call); the cells stay those of the grid-frame arithmetic.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import navkit.mapping._grid as grid_module
from navkit._shared.jit import jit_disabled
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping._grid_kernels import world_to_cell_kernel, world_to_continuous_kernel
from navkit.mapping._new_cells_kernel import new_cells_entry


def _grid(yaw: float = 0.4) -> OccupancyGrid:
    return OccupancyGrid.empty(
        width=5.0, height=4.0, resolution=0.05, origin=Pose2D(-2.0, -1.5, yaw)
    )


def _unaligned(pts: np.ndarray) -> np.ndarray:
    """The same values in a C-contiguous float64 array whose data is not 8-byte aligned."""
    raw = np.zeros(pts.size * 8 + 1, dtype=np.uint8)
    out = raw[1:].view(np.float64).reshape(pts.shape)
    out[...] = pts
    return out


@pytest.fixture
def passed(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[Any]]:
    """The point arrays handed to the fast path's entry and whether it answered, in order."""
    entry = new_cells_entry()
    seen: list[Any] = []

    def recording(points: Any, *args: Any) -> Any:
        cells = entry(points, *args)
        seen.append((points, cells is not None))
        return cells

    monkeypatch.setattr(grid_module, "_NEW_CELLS", recording)
    yield seen


def _expected(grid: OccupancyGrid, pts: np.ndarray) -> np.ndarray:
    """Cells from the one-point Python arithmetic (the kernel's, operation for operation)."""
    rows = []
    for x, y in pts.tolist():
        row, col = grid._grid_frame(x, y)
        rows.append([math.floor(row), math.floor(col)])
    return np.array(rows, dtype=np.int64).reshape(-1, 2)


def test_pair_strides_select_c_contiguous_pairs() -> None:
    """Strides ``_PAIR_STRIDES`` and two columns: a C-contiguous (N, 2) float64 array."""
    base = np.zeros((6, 2))
    cases = [
        np.zeros((3, 2)),
        np.zeros((3, 2), order="F"),
        np.zeros((2, 3)).T,
        base[::2],
        base[::-1],
        base[:, :1],  # strides (16, 8), one column
        np.zeros((3, 4))[:, :2],
        np.broadcast_to(np.zeros(2), (3, 2)),
        _unaligned(np.zeros((3, 2))),
        np.zeros((0, 2)),
        np.zeros((1, 2)),
    ]
    for arr in cases:
        fast = arr.strides == grid_module._PAIR_STRIDES and arr.shape[1] == 2
        if arr.size == 0:
            # numpy may give an empty array strides (0, 0): either way is right,
            # the general path returns the same empty int64 cells.
            got = _grid().world_to_cell(arr)
            assert got.shape == (0, 2) and got.dtype == np.int64
            continue
        assert fast == (arr.flags.c_contiguous and arr.shape[1] == 2), (arr.strides, arr.shape)
    assert not _unaligned(np.zeros((3, 2))).flags.aligned  # the case is real


@given(
    st.integers(2, 40).flatmap(
        lambda n: hnp.arrays(np.float64, (n, 2), elements=st.floats(-50.0, 50.0))
    ),
    st.floats(-math.pi, math.pi),
)
@settings(max_examples=40, deadline=None)
def test_fast_path_only_for_c_aligned_float64(pts: np.ndarray, yaw: float) -> None:
    grid = _grid(yaw)
    want = _expected(grid, pts)
    entry = grid_module._CELLS_ENTRY or grid_module._cells_entry()
    new_entry = new_cells_entry()
    seen: list[Any] = []  # the general path's entry's points
    tried: list[Any] = []  # the fast path's: (points, answered)

    def recording(points: Any, *args: Any) -> Any:
        seen.append(points)
        return entry(points, *args)

    def new_recording(points: Any, *args: Any) -> Any:
        cells = new_entry(points, *args)
        tried.append((points, cells is not None))
        return cells

    old, old_new = grid_module._CELLS_ENTRY, grid_module._NEW_CELLS
    grid_module._CELLS_ENTRY = recording
    grid_module._NEW_CELLS = new_recording
    try:
        wide = np.zeros((pts.shape[0], 4))
        wide[:, ::2] = pts
        cases = {
            "exact": (pts.copy(), True),
            "unaligned": (_unaligned(pts), True),
            "fortran": (np.asfortranarray(pts), False),
            "strided": (wide[:, ::2], False),
        }
        for name, (arr, fast) in cases.items():
            before = arr.copy()
            seen.clear()
            tried.clear()
            got = grid.world_to_cell(arr)
            np.testing.assert_array_equal(got, want, err_msg=name)
            assert got.dtype == np.int64 and got.flags.writeable and got.flags.c_contiguous
            assert got.flags.owndata and got.base is None, name
            np.testing.assert_array_equal(arr, before, err_msg=name)  # input unmodified
            assert len(tried) == 1 and tried[0][0] is arr, name
            if fast:
                assert tried[0][1] and not seen, name
            else:
                assert not tried[0][1] and seen, name
                assert all(p is not arr for p in seen), name
                assert all(p.flags.c_contiguous for p in seen), name
    finally:
        grid_module._CELLS_ENTRY, grid_module._NEW_CELLS = old, old_new


def test_non_finite_through_fast_path_still_raises(passed: list[Any]) -> None:
    pts = np.array([[0.0, 0.0], [math.nan, 1.0]])
    with pytest.raises(ValueError, match="points_xy"):
        _grid().world_to_cell(pts)
    # Tried fast (not answered), then explained by the general path.
    assert len(passed) == 1 and passed[0][0] is pts and not passed[0][1]


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_kernels_compiled_without_refcounting() -> None:
    """No MemInfo per array argument per call: the kernels allocate nothing."""
    for kernel in (world_to_cell_kernel, world_to_continuous_kernel):
        dispatcher: Any = kernel
        options = dispatcher.targetoptions  # loads numba: a dispatcher
        assert options.get("_nrt") is False, kernel
