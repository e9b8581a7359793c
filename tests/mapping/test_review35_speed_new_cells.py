"""``world_to_cell``'s fast path as one compiled call (session 39, issue 17).

The fast path used to test the points in Python (type, dtype, strides, shape:
about 0.12 µs), allocate the cells with ``np.empty`` (0.1 µs) and call the
kernel's compiled entry (0.13 µs): 1.9 times the kernel through numba's
dispatcher on ten points, above issue 17's 1.5. Now one compiled entry
(``navkit.mapping._new_cells_kernel``) takes ``points_xy`` as it is, tests it
in C, makes the cells with NumPy's ``PyArray_Empty`` and fills them with the
same kernel; anything it does not take goes the general way as before.

Pinned here: the fast path is that one call from Python; its cells are those
of ``np.empty`` and the kernel's entry, bit for bit, with the same dtype,
shape, strides and flags; exactly the arrays the Python tests took are taken
(and any other object returns None without being read); no reference is lost
or leaked (NaN points, whose new cells are dropped, included); an allocation
that fails raises NumPy's ``MemoryError`` as ``np.empty`` did.
"""

from __future__ import annotations

import math
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import navkit.mapping._grid as grid_module
from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping._grid_kernels import world_to_cell_entry
from navkit.mapping._new_cells_kernel import new_cells_entry

_ORIGIN = (-20.0, -15.0, 0.4, 0.05)


def _grid(x: float = -20.0, y: float = -15.0, yaw: float = 0.4, res: float = 0.05) -> Any:
    # A small grid: the cells of points outside it are computed all the same.
    return OccupancyGrid.empty(width=1.0, height=1.0, resolution=res, origin=Pose2D(x, y, yaw))


def _two_step(points: np.ndarray, *origin: float) -> np.ndarray:
    """The former fast path: ``np.empty`` of the points' shape, then the kernel's entry."""
    cells = np.empty(points.shape, np.int64)
    assert world_to_cell_entry()(points, *origin, cells)
    return cells


def _same_array(got: np.ndarray, want: np.ndarray) -> None:
    assert type(got) is np.ndarray
    assert got.dtype == want.dtype == np.int64 and got.dtype.byteorder == "="
    assert got.shape == want.shape and got.strides == want.strides
    assert got.tobytes() == want.tobytes()
    assert got.base is None and want.base is None
    for flag in ("C_CONTIGUOUS", "F_CONTIGUOUS", "OWNDATA", "WRITEABLE", "ALIGNED"):
        assert got.flags[flag] == want.flags[flag], flag


def _unaligned(pts: np.ndarray) -> np.ndarray:
    raw = np.zeros(pts.size * 8 + 1, dtype=np.uint8)
    out = raw[1:].view(np.float64).reshape(pts.shape)
    out[...] = pts
    return out


coordinate = st.floats(-1e6, 1e6) | st.floats(allow_nan=False, allow_infinity=False)


@given(
    st.integers(0, 40).flatmap(lambda n: hnp.arrays(np.float64, (n, 2), elements=coordinate)),
    st.floats(-1e3, 1e3),
    st.floats(-1e3, 1e3),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.01, 0.05, 0.1, 1.0, 0.3]),
)
@settings(max_examples=60, deadline=None)
# yaw = -pi: the grid's origin holds pi (angles wrap to (-pi, pi]), whose sine
# has the other sign, and a point on a cell edge falls in the cell beside
# (found under the thorough profile, review 41).
@example(pts=np.array([[0.0, 0.0]]), x=0.0, y=1.0, yaw=-math.pi, res=0.01)
def test_cells_bit_for_bit_those_of_empty_and_entry(
    pts: np.ndarray, x: float, y: float, yaw: float, res: float
) -> None:
    """Values, dtype, shape, strides and flags: the former fast path's, for every array."""
    grid = _grid(x, y, yaw, res)
    yaw = grid.origin.theta  # as the grid wrapped it: its cells are those of this yaw
    entry = new_cells_entry()
    want = _two_step(pts, x, y, yaw, res)
    for arr in (pts, _unaligned(pts), pts.copy()):
        arr.flags.writeable = arr is not pts  # read-only points too
        got = entry(arr, x, y, yaw, res)
        if arr.strides != (16, 8):  # NumPy's empty arrays may have strides (0, 0)
            assert got is None and arr.size == 0
        else:
            _same_array(got, want)
        public = grid.world_to_cell(arr)
        _same_array(public, want)
        assert public is not got and not np.shares_memory(public, arr)


def _refused() -> dict[str, Any]:
    pts = np.random.default_rng(1).uniform(-3, 3, size=(6, 2))
    wide = np.zeros((6, 4))
    wide[:, ::2] = pts

    class Sub(np.ndarray):
        pass

    return {
        "list": pts.tolist(),
        "tuple": tuple(map(tuple, pts.tolist())),
        "None": None,
        "int": 7,
        "float": 1.5,
        "str": "1.0, 2.0",
        "object": object(),
        "subclass": pts.view(Sub),
        "float32": pts.astype(np.float32),
        "big-endian": pts.astype(">f8"),
        "int64": pts.astype(np.int64),
        "complex": pts.astype(np.complex128),
        "object array": pts.astype(object),
        "fortran": np.asfortranarray(pts),
        "strided": wide[:, ::2],
        "reversed": pts[::-1],
        "one row of (1, 2) broadcast": np.broadcast_to(pts[:1], (6, 2)),
        "1-D pair": pts[0].copy(),
        "1-D": pts.ravel(),
        "(N, 3)": np.zeros((4, 3)),
        "(N, 1)": np.zeros((4, 2))[:, :1],
        "3-D": np.zeros((2, 3, 2)),
        "0-D": np.array(1.0),
        "NaN": np.array([[0.0, 0.0], [math.nan, 1.0]]),
        "inf": np.array([[0.0, math.inf]]),
        "-inf": np.array([[-math.inf, 0.0], [1.0, 2.0]]),
    }


@pytest.mark.parametrize("name", list(_refused()))
def test_anything_else_goes_the_general_way(name: str) -> None:
    """None from the entry (nothing allocated for a non-array, nothing changed), and
    the public call's answer or error is the general path's."""
    value = _refused()[name]
    before = repr(value)
    assert new_cells_entry()(value, *_ORIGIN) is None, name
    assert repr(value) == before
    grid = _grid()
    try:
        want: Any = grid_module.as_pairs(value, "points_xy")
    except (TypeError, ValueError) as exc:
        with pytest.raises(type(exc)) as info:
            grid.world_to_cell(value)
        assert str(info.value) == str(exc)
        return
    pts, single = want
    cells = grid._cells(pts)
    np.testing.assert_array_equal(grid.world_to_cell(value), cells[0] if single else cells)


def test_taken_exactly_where_the_python_tests_took_them() -> None:
    """The C tests accept what ``type is ndarray``, float64, strides (16, 8) and two
    columns accepted (the empty arrays' strides aside: either way gives the same cells)."""
    tagged = np.dtype(np.float64, metadata={"m": 1})
    values = {**_refused(), "plain": np.zeros((3, 2)), "one": np.zeros((1, 2)),
              "unaligned": _unaligned(np.zeros((3, 2))), "empty": np.ones((3, 2))[:0],
              "metadata": np.zeros((3, 2), dtype=tagged)}  # fmt: skip
    for name, value in values.items():
        python = (
            type(value) is np.ndarray
            and value.dtype == np.float64
            and value.dtype.byteorder == "="
            and value.strides == (16, 8)
            and value.shape[1] == 2
            and bool(np.isfinite(value).all())
        )
        assert (new_cells_entry()(value, *_ORIGIN) is not None) == python, name


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: the entry is Python")
def test_fast_path_is_one_call_from_python() -> None:
    """The compiled entry is the only call the fast path makes (no np.empty, no
    attribute of the points read in Python)."""
    grid = _grid()
    pts = np.random.default_rng(2).uniform(-30, 30, size=(10, 2))
    want = grid.world_to_cell(pts)
    calls: list[str] = []

    def profile(frame: Any, event: str, arg: Any) -> None:
        if event == "c_call":
            calls.append(getattr(arg, "__qualname__", repr(arg)))

    sys.setprofile(profile)
    try:
        got = grid.world_to_cell(pts)
    finally:
        sys.setprofile(None)
    np.testing.assert_array_equal(got, want)
    # The entry is a compiled function: one C call (the profile's own setprofile(None)
    # is the other C call seen).
    assert len([c for c in calls if "setprofile" not in c]) == 1, calls


def test_no_reference_lost_or_leaked() -> None:
    """The points, the int64 dtype and the cells hold the references they should,
    after many calls, taken or refused (NaN points: new cells made and dropped)."""
    entry = new_cells_entry()
    pts = np.random.default_rng(3).uniform(-3, 3, size=(10, 2))
    bad = np.array([[0.0, 0.0], [math.nan, 1.0]])
    int64 = np.dtype(np.int64)
    counts = (sys.getrefcount(pts), sys.getrefcount(bad), sys.getrefcount(int64))
    for _ in range(2000):
        cells = entry(pts, *_ORIGIN)
        assert entry(bad, *_ORIGIN) is None
        assert entry([[1.0, 2.0]], *_ORIGIN) is None
    assert sys.getrefcount(cells) == 2  # the name and the argument: no extra reference
    del cells
    assert (sys.getrefcount(pts), sys.getrefcount(bad), sys.getrefcount(int64)) == counts


def test_failed_allocation_raises_memory_error() -> None:
    """Cells too large to allocate: NumPy's MemoryError, as np.empty raised it (the
    points are never read: they are a view of 16 bytes claiming 2**50 rows)."""
    huge = np.lib.stride_tricks.as_strided(np.zeros(2), shape=(2**50, 2), strides=(16, 8))
    with pytest.raises(MemoryError):
        np.empty(huge.shape, np.int64)
    with pytest.raises(MemoryError):
        new_cells_entry()(huge, *_ORIGIN)
    with pytest.raises(MemoryError):
        _grid().world_to_cell(huge)


_MODULES = ["navkit.mapping._new_cells_kernel", "navkit.mapping._grid_kernels"]
#: Lists, tuples and arrays of one point, which the fast path does not take.
_NOT_TAKEN = (
    "from navkit.mapping import OccupancyGrid\n"
    "g = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)\n"
    "g.world_to_cell([0.1, 0.2]); g.world_to_cell(((0.1, 0.2),))\n"
    "import numpy as np\n"
    "g.world_to_cell(np.array([0.1, 0.2])); g.world_to_cell(np.array([[1, 2]]))\n"
    "g.world_to_cell(np.array([[0.1, 0.2]], order='F')[:, ::-1])\n"
    "assert g.contains([0.1, 0.2])\n"
)


@pytest.fixture(scope="module")
def taken_signatures() -> dict[str, list[str]]:
    """The kernels' signatures in a fresh process after points the fast path takes.

    A fresh process: the test process's kernels keep the signatures of every
    earlier test's direct calls (the entry's dispatcher compiled for other
    argument types, say), which ran before under another order or split of the
    suite (xdist). One process serves both tests reading it.
    """
    arrays = _NOT_TAKEN + (
        "import numpy as np\n"
        "g.world_to_cell(np.array([[0.1, 0.2], [0.3, 0.4]]))\n"
        "g.world_to_cell([[0.1, 0.2], [0.3, 0.4]])\n"  # the general way's entry
    )
    return compiled_signatures(arrays, _MODULES)


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_entry_is_compiled_without_refcounting(taken_signatures: dict[str, list[str]]) -> None:
    """One compiled entry, no NRT: no MemInfo per call (it allocates through NumPy)."""
    from navkit.mapping import _new_cells_kernel

    dispatcher: Any = _new_cells_kernel.world_to_new_cells
    assert dispatcher.targetoptions.get("_nrt") is False
    entry = taken_signatures.get("_new_cells_kernel.world_to_new_cells", [])
    assert len(entry) == 1, taken_signatures


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_lists_and_one_point_compile_nothing_arrays_one_entry(
    taken_signatures: dict[str, list[str]],
) -> None:
    """In a fresh process, lists, tuples and arrays of one point the fast path does not
    take (the general way) load or compile no kernel, as before; the first points
    it takes load its entry, whose kernel code is the general way's one signature."""
    assert compiled_signatures(_NOT_TAKEN, _MODULES) == {}
    assert sorted(taken_signatures) == [
        "_grid_kernels.world_to_cell_kernel",
        "_new_cells_kernel.world_to_new_cells",
    ]
    assert all(len(signatures) == 1 for signatures in taken_signatures.values()), taken_signatures


def test_loading_leaves_ctypes_pythonapi_as_it_was() -> None:
    """The NumPy C-API table is read through a ctypes prototype of navkit's own: the
    process-wide ``ctypes.pythonapi.PyCapsule_GetPointer`` keeps its types."""
    code = (
        "import ctypes\n"
        "f = ctypes.pythonapi.PyCapsule_GetPointer\n"
        "before = (f.restype, f.argtypes)\n"
        "import navkit._shared.array_objects\n"
        "assert (f.restype, f.argtypes) == before, (f.restype, f.argtypes)\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)
