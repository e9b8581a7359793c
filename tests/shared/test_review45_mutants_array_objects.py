"""What callers of ``navkit._shared.array_objects`` see, where its mutants survived
(review 45, MUTANT24).

A mutation review of the module's intrinsics found these behaviours unpinned:

* the NumPy C-API slot it calls for new arrays is ``PyArray_Empty``, what
  ``np.empty`` calls (slot 183, ``PyArray_Zeros``, made arrays of the same
  values once the kernel had filled them, so no caller's test told them apart;
  an object array does: ``None`` from the one, ``0`` from the other);
* the views it gives a kernel: shape ``(N, 2)`` (a view of shape ``(N, 1)``
  passed, as ``world_to_cell``'s kernel indexes without bounds checks),
  itemsize 8, ``(-1, empty view)`` for a refused object, and a new array's
  view as long as the array (a view of 0 rows passed: the kernel loops over
  the points, not the view); ``float_matrix``'s strides (a view with strides
  (8, 8) passed: numba indexes a C array by its shape, and only ``.strides``
  shows them);
* arrays that fail exactly one of ``float_pairs``' tests (ndim, shape[1],
  either stride, the dtype): each test could be dropped or weakened, as the
  earlier refused arrays failed several at once (the int64 points had
  negative values, NaN when read as float64, so were refused as not finite);
* kernels compiled with ``LAYOUT_OK`` False take nothing (the test under a
  faked NumPy major read the real, right layout, so ``float_vector`` and
  ``float_matrix`` ignoring the flag passed it).
"""

from __future__ import annotations

import ctypes
import sys
from typing import Any

import numpy as np
import pytest

from navkit._shared import array_objects as ao
from navkit._shared.jit import jit_disabled

pytestmark = pytest.mark.skipif(
    jit_disabled(), reason="NUMBA_DISABLE_JIT=1: the intrinsics are not used"
)


def _registered_empty() -> ctypes._CFuncPtr:
    """The C function the compiled code calls as ``PyArray_Empty``, through ctypes."""
    from llvmlite import binding

    prototype = ctypes.PYFUNCTYPE(
        ctypes.py_object,
        ctypes.c_int,
        ctypes.POINTER(ctypes.c_ssize_t),
        ctypes.py_object,
        ctypes.c_int,
    )
    return prototype(binding.address_of_symbol(ao._ARRAY_EMPTY))


@pytest.mark.parametrize("fortran", [0, 1])
def test_the_registered_allocator_is_numpys_empty(fortran: int) -> None:
    """Its arrays are ``np.empty``'s: an object array of Nones, in the order asked for
    (mutant: the C-API table's slot 183, ``PyArray_Zeros``, gave zeros)."""
    empty = _registered_empty()
    # A descriptor of its own (np.dtype(object) is NumPy's shared one, whose count
    # other code moves). NumPy 2.3's own PyArray_Empty keeps one reference of the
    # descriptor of each Fortran-order array it makes (not 2.4's): the registered
    # function, which is NumPy's, may keep what np.empty keeps, and no more.
    descr = np.dtype([("v", object)])
    start = sys.getrefcount(descr)
    np.empty((3, 2), dtype=descr, order="F" if fortran else "C")
    numpys = sys.getrefcount(descr) - start
    before = sys.getrefcount(descr)
    ctypes.pythonapi.Py_IncRef(ctypes.py_object(descr))  # PyArray_Empty steals one
    got = empty(2, (ctypes.c_ssize_t * 2)(3, 2), descr, fortran)
    assert sys.getrefcount(descr) == before + 1  # the array's own reference
    assert got.dtype is descr
    want = np.empty((3, 2), dtype=[("v", object)], order="F" if fortran else "C")
    assert type(got) is np.ndarray and got.dtype == want.dtype
    assert got.tolist() == want.tolist() == [[(None,), (None,)]] * 3
    assert got.strides == want.strides
    del got
    assert sys.getrefcount(descr) == before + numpys


def _kernels() -> tuple[object, object, object, object]:
    """Small compiled callers of the intrinsics (an OBJECT argument, no cache)."""
    import numba
    from numba import types

    @numba.njit(_nrt=False)
    def pairs(obj: object) -> tuple[int, int, int, int, int, int, float]:
        n, pts = ao.float_pairs(obj)
        total = 0.0
        for i in range(pts.shape[0]):
            for j in range(pts.shape[1]):
                total += pts[i, j] * (1 + 10 * j)
        return n, pts.shape[0], pts.shape[1], pts.strides[0], pts.strides[1], pts.itemsize, total

    @numba.njit(_nrt=False)
    def cells(n: int) -> object:
        new, out = ao.new_int_pairs(n)
        if ao.is_null(new):
            return new
        for i in range(out.shape[0]):
            for j in range(out.shape[1]):
                out[i, j] = 10 * i + j + 1000 * out.itemsize
        return new

    @numba.njit(_nrt=False)
    def vector(obj: object) -> tuple[bool, int, int, int, float]:
        ok, v = ao.float_vector(obj)
        total = 0.0
        for i in range(v.shape[0]):
            total += v[i] * (1 + i)
        return ok, v.shape[0], v.strides[0], v.itemsize, total

    @numba.njit(_nrt=False)
    def matrix(obj: object) -> tuple[bool, int, int, int, int, int, float]:
        ok, m = ao.float_matrix(obj)
        total = 0.0
        for i in range(m.shape[0]):
            for j in range(m.shape[1]):
                total += m[i, j] * (1 + i + 10 * j)
        return ok, m.shape[0], m.shape[1], m.strides[0], m.strides[1], m.itemsize, total

    return (
        pairs.compile((ao.OBJECT,)),
        cells.compile((types.int64,)),
        vector.compile((ao.OBJECT,)),
        matrix.compile((ao.OBJECT,)),
    )


@pytest.fixture(scope="module")
def kernels() -> tuple[object, ...]:
    if not ao.LAYOUT_OK:
        pytest.skip("NumPy's structs are not laid out as the module reads them")
    return _kernels()


def _weighted(a: np.ndarray, row: int, col: int) -> float:
    """What the kernels sum: each value times ``1 + row * i + col * j``."""
    total = 0.0
    for index, value in np.ndenumerate(a):
        i, j = (*index, 0)[:2]
        total += float(value) * (1 + row * i + col * j)
    return total


@pytest.mark.parametrize("rows", [1, 2, 5])
def test_float_pairs_gives_an_n_by_2_view_of_the_points(rows: int, kernels: Any) -> None:
    """A caller sees the points as an (N, 2) array with strides (16, 8): its loops over
    ``shape[1]`` read both columns (mutant: a view of shape (N, 1), which a kernel
    indexing ``[i, 1]`` without bounds checks read all the same)."""
    pts = np.arange(2.0 * rows).reshape(rows, 2) + 0.5
    assert kernels[0](pts) == (rows, rows, 2, 16, 8, 8, _weighted(pts, 0, 10))
    # Refused: -1 and an empty view.
    assert kernels[0](pts.astype(np.float32)) == (-1, 0, 2, 16, 8, 8, 0.0)


@pytest.mark.parametrize("rows", [0, 1, 7])
def test_new_int_pairs_gives_an_n_by_2_view_of_the_new_array(rows: int, kernels: Any) -> None:
    """Writes through the view's shape fill the whole new (N, 2) array."""
    got = kernels[1](rows)
    want = np.empty((rows, 2), dtype=np.int64)
    want[:] = 10 * np.arange(rows)[:, None] + np.arange(2) + 8000  # itemsize 8
    assert type(got) is np.ndarray and got.dtype == want.dtype
    assert got.shape == want.shape and got.strides == want.strides
    np.testing.assert_array_equal(got, want)


def test_float_vector_and_matrix_give_the_arrays_shape_and_strides(kernels: Any) -> None:
    x = np.arange(4.0) + 0.25
    m = np.arange(12.0).reshape(3, 4) - 5.0
    assert kernels[2](x) == (True, 4, 8, 8, _weighted(x, 1, 0))
    assert kernels[3](m) == (True, 3, 4, 32, 8, 8, _weighted(m, 1, 10))
    assert kernels[2](m) == (False, 0, 0, 8, 0.0)
    assert kernels[3](x) == (False, 0, 0, 0, 0, 8, 0.0)


def _near_misses() -> dict[str, np.ndarray]:
    """float64 arrays that pass every test of ``float_pairs`` but one."""
    pts = np.arange(8.0).reshape(4, 2) + 0.5
    as_strided = np.lib.stride_tricks.as_strided
    return {
        # 3-D, with (N, 2)'s first two strides (16, 8): only ndim differs.
        "(N, 2, 1)": pts.reshape(4, 2, 1),
        # Three columns read at strides (16, 8) (overlapping rows): only shape[1] differs.
        "(N, 3) at (16, 8)": as_strided(np.arange(10.0), shape=(4, 3), strides=(16, 8)),
        # Rows 24 bytes apart: only strides[0] differs.
        "two of three columns": np.arange(12.0).reshape(4, 3)[:, :2],
        # Columns swapped: only strides[1] differs.
        "columns reversed": pts[:, ::-1],
        # Only the dtype differs. Non-negative: the earlier tests' int64 points had
        # negative values, whose bits read as float64 are NaN, so that the mutant
        # taking any dtype still returned None there (the points not all finite).
        "int64": np.arange(8, dtype=np.int64).reshape(4, 2),
        "uint64": np.arange(8, dtype=np.uint64).reshape(4, 2),
    }


@pytest.mark.parametrize("name", sorted(_near_misses()))
def test_arrays_failing_one_test_go_the_general_way(name: str) -> None:
    """``world_to_cell``'s entry returns None for each, and the public call answers as
    the general way (mutants: each of the ndim, shape and stride tests dropped or
    weakened, which no refused array of the earlier tests needed)."""
    from navkit.geometry import Pose2D
    from navkit.mapping import OccupancyGrid
    from navkit.mapping import _grid as grid_module
    from navkit.mapping._new_cells_kernel import new_cells_entry

    value = _near_misses()[name]
    before = value.copy()
    origin = (-2.0, -1.0, 0.3, 0.25)
    assert new_cells_entry()(value, *origin) is None
    np.testing.assert_array_equal(value, before)
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.25, origin=Pose2D(*origin[:3]))
    try:
        pts, single = grid_module.as_pairs(value, "points_xy")
    except (TypeError, ValueError) as exc:
        with pytest.raises(type(exc)) as info:
            grid.world_to_cell(value)
        assert str(info.value) == str(exc)
        return
    assert not single
    np.testing.assert_array_equal(grid.world_to_cell(value), grid._cells(pts))
    np.testing.assert_array_equal(grid.world_to_cell(value), grid.world_to_cell(value.copy()))


def test_without_the_layout_every_object_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    """Kernels compiled where the layout check failed read no struct and take nothing
    (mutant: ``float_vector``/``float_matrix`` ignoring ``LAYOUT_OK``, which the earlier
    test under a faked NumPy major could not see: the real layout read right)."""
    monkeypatch.setattr(ao, "LAYOUT_OK", False)
    pairs, _, vector, matrix = _kernels()  # compiled now, reading LAYOUT_OK
    assert pairs(np.zeros((3, 2))) == (-1, 0, 2, 16, 8, 8, 0.0)
    assert vector(np.zeros(3)) == (False, 0, 0, 8, 0.0)
    assert matrix(np.zeros((3, 3))) == (False, 0, 0, 0, 0, 8, 0.0)
