"""``world_to_cell``'s fast path as one compiled call: check, allocate, convert (private).

:meth:`OccupancyGrid.world_to_cell <navkit.mapping.OccupancyGrid.world_to_cell>`
hands its ``points_xy``, whatever it is, to :func:`new_cells_entry`'s entry
with the grid's origin and resolution. The entry checks in C that the points
are an ``ndarray`` (exactly) of native float64 with shape ``(N, 2)`` and
strides ``(16, 8)``, makes the ``(N, 2)`` int64 result as ``np.empty``
does, fills it with :func:`~navkit.mapping._grid_kernels.world_to_cell_kernel`
(the same compiled code as the general way's, so the same cells bit for bit)
and returns it; it returns ``None`` for any other object and for points that
are not all finite, and the caller's general way then converts, validates
and raises. One dispatch instead of Python's type, dtype, stride and shape
tests, ``np.empty`` and a compiled call (issue 17: 0.25 µs against 0.50 µs on
ten points). See :mod:`navkit._shared.array_objects` for the types.

Examples
--------
>>> import numpy as np
>>> entry = new_cells_entry()
>>> entry(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5)
array([[0, 1]])
>>> entry([[0.7, 0.2]], 0.0, 0.0, 0.0, 0.5) is None  # not an ndarray: the general way
True
>>> entry(np.array([[np.nan, 0.2]]), 0.0, 0.0, 0.0, 0.5) is None
True
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_no_refcount
from navkit._shared.types import IntArray
from navkit.mapping._grid_kernels import world_to_cell_entry, world_to_cell_kernel

__all__ = ["new_cells_entry", "world_to_new_cells"]

# navkit._shared.array_objects's intrinsics (it imports numba): bound when numba loads.
float_pairs: Any = None
new_int_pairs: Any = None
is_null: Any = None
discard: Any = None
no_object: Any = None
bind_numba_names(
    globals(), "navkit._shared.array_objects",
    float_pairs="float_pairs", new_int_pairs="new_int_pairs", is_null="is_null",
    discard="discard", no_object="no_object",
)  # fmt: skip

#: The signature of one entry: what new_cells_entry's caller passes.
NewCellsEntry = Callable[[object, float, float, float, float], "IntArray | None"]


@njit_no_refcount
def world_to_new_cells(
    points: Any,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
) -> Any:
    """New int64 cells of C-contiguous (N, 2) float64 points, or None (see the module)."""
    n, pts = float_pairs(points)
    if n < 0:
        return no_object()
    cells, out = new_int_pairs(n)
    if is_null(cells):  # out of memory: the entry raises NumPy's MemoryError
        return cells
    # numba links world_to_cell_kernel's code in here, but caches this kernel keyed on
    # this file alone: edit this file too when that kernel changes (review 50: its
    # clamps became selects).
    if world_to_cell_kernel(pts, origin_x, origin_y, origin_yaw, resolution, out):
        return cells
    return discard(cells)


_FLOAT64 = np.dtype(np.float64)


def _python_new_cells(
    points: object, origin_x: float, origin_y: float, origin_yaw: float, resolution: float
) -> IntArray | None:
    """The entry with the JIT disabled (``NUMBA_DISABLE_JIT=1``): the same tests in Python."""
    if (
        type(points) is np.ndarray
        and points.dtype.num == _FLOAT64.num
        and points.dtype.byteorder == "="
        and points.strides == (16, 8)
        and points.shape[1] == 2
    ):
        cells = np.empty(points.shape, dtype=np.int64)
        if world_to_cell_entry()(points, origin_x, origin_y, origin_yaw, resolution, cells):
            return cells
    return None


def new_cells_entry() -> NewCellsEntry:
    """Compiled entry of :func:`world_to_new_cells`: any object, four floats, cells or None.

    The caller passes four Python floats (origin x, y, yaw, resolution > 0, the
    origin within ±1e9 m); the points may be anything. Returns a new (N, 2)
    int64 array (C order, writable, owning its data, as ``np.empty`` makes) of
    :func:`~navkit.mapping._grid_kernels.world_to_cell_kernel`'s cells when
    the points are an ``ndarray`` (not a subclass) of native float64, shape
    ``(N, 2)``, strides ``(16, 8)``, all finite; else None. Compiled (or loaded
    from the cache) on first call of this function; it also compiles the
    kernel for :func:`~navkit.mapping._grid_kernels.world_to_cell_entry`'s
    signature, which that entry then finds ready. With the JIT disabled, the
    same tests in Python.

    Examples
    --------
    >>> new_cells_entry()(np.array([[0.7, 0.2], [0.1, 0.1]]), 0.0, 0.0, 0.0, 0.5)
    array([[0, 1],
           [0, 0]])
    """
    # The dispatcher first: it loads numba (holding a Ctrl-C back until numba is
    # fully imported) and binds the intrinsics, registering their symbols.
    dispatcher: Any = world_to_new_cells
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return _python_new_cells
    from numba import types  # here: importing this module must not import numba

    from navkit._shared.array_objects import OBJECT

    return cast(NewCellsEntry, dispatcher.compile((OBJECT, *(types.float64,) * 4)))
