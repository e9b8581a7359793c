"""``OccupancyGrid.world_to_cell``'s fast path (the compiled entry) equals the general path."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, _grid_kernels
from navkit.mapping._grid_kernels import world_to_cell_entry, world_to_cell_kernel

coords = st.floats(-1e6, 1e6, allow_nan=False)


@settings(max_examples=40, deadline=None)
@given(
    pts=arrays(np.float64, st.tuples(st.integers(0, 12), st.just(2)), elements=coords),
    x=st.floats(-100, 100),
    y=st.floats(-100, 100),
    yaw=st.floats(-3.1, 3.1),
    res=st.floats(1e-3, 10.0),
    readonly=st.booleans(),
)
def test_fast_path_equals_general_path(
    pts: np.ndarray, x: float, y: float, yaw: float, res: float, readonly: bool
) -> None:
    grid = OccupancyGrid.empty(width=3.0, height=2.0, resolution=res, origin=Pose2D(x, y, yaw))
    before = pts.copy()
    pts.flags.writeable = not readonly
    fast = grid.world_to_cell(pts)
    general = grid.world_to_cell(pts.tolist()) if len(pts) else grid.world_to_cell(pts[:0].copy())
    assert fast.dtype == np.int64 and fast.shape == (len(pts), 2)
    assert np.array_equal(fast, general)
    # The kernel as Python on the same arguments: the entry is that kernel. (Not
    # the dispatcher: for these aligned points it would compile a second version,
    # which test_one_signature_per_mapping_kernel would count.)
    out = np.empty((len(pts), 2), dtype=np.int64)
    o = grid.origin
    as_python = getattr(world_to_cell_kernel, "py_func", world_to_cell_kernel)  # NUMBA_DISABLE_JIT
    # min2/max2 are numba intrinsics (review 50), not callable from Python: run the
    # kernel's Python with the builtins they stand for, as NUMBA_DISABLE_JIT binds them.
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(_grid_kernels, "min2", min)
        patch.setattr(_grid_kernels, "max2", max)
        as_python(np.array(pts), o.x, o.y, o.theta, grid.resolution, out)
    assert np.array_equal(fast, out)
    assert np.array_equal(pts, before)


def test_other_layouts_and_dtypes_take_the_general_path() -> None:
    grid = OccupancyGrid.empty(width=5.0, height=4.0, resolution=0.1, origin=Pose2D(-1, -2, 0.3))
    pts = np.random.default_rng(3).uniform(-10, 10, size=(9, 2))
    want = grid.world_to_cell(pts)
    wide = np.random.default_rng(3).uniform(-10, 10, size=(9, 3))
    for variant in (
        np.asfortranarray(pts),
        pts.astype(np.float32).astype(np.float64),
        pts.astype(">f8"),
        np.array(pts, dtype=np.float64, order="C")[::1],
    ):
        assert np.array_equal(grid.world_to_cell(variant), want)
    assert np.array_equal(grid.world_to_cell(wide[:, :2]), grid.world_to_cell(wide[:, :2].copy()))
    # An unaligned float64 buffer: same cells (the entry reads unaligned data too).
    buf = np.zeros(pts.size * 8 + 1, dtype=np.uint8)
    unaligned = np.frombuffer(buf.data, dtype=np.float64, count=pts.size, offset=1).reshape(9, 2)
    assert not unaligned.flags.aligned
    unaligned_w = np.ndarray((9, 2), dtype=np.float64, buffer=buf, offset=1)
    unaligned_w[:] = pts
    assert np.array_equal(grid.world_to_cell(unaligned), want)
    with pytest.raises(ValueError, match=r"shape \(N, 2\)"):
        grid.world_to_cell(wide)
    with pytest.raises(ValueError, match="points_xy"):
        grid.world_to_cell(np.array([[0.0, math.nan]]))


def test_results_are_new_arrays() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5)
    pts = np.array([[0.1, 0.1], [0.6, 0.6]])
    a = grid.world_to_cell(pts)
    b = grid.world_to_cell(pts)
    assert a is not b and not np.shares_memory(a, b)
    a[0, 0] = 99
    assert b[0, 0] == 0 and a.flags.writeable


def test_entry_is_the_compiled_kernel() -> None:
    entry = world_to_cell_entry()
    assert entry is world_to_cell_entry()  # compiled once, then found
    out = np.empty((1, 2), dtype=np.int64)
    assert entry(np.array([[1.2, 0.4]]), 0.0, 0.0, 0.0, 0.5, out)
    assert out.tolist() == [[0, 2]]
    infinite = np.array([[math.inf, 0.4]])  # its grid row is 0 * inf: NaN
    # False, compiled or as Python (NUMBA_DISABLE_JIT=1: the entry then runs the
    # kernel as Python, whose math.floor of NaN raises and whose NumPy scalars obey
    # np.seterr, inside an errstate of its own): the caller's general path then
    # names points_xy.
    with np.errstate(all="raise"):
        assert not entry(infinite, 0.0, 0.0, 0.0, 0.5, out)
