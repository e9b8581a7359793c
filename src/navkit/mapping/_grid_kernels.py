"""numba kernels for world-to-cell conversion of many points (private).

Plain functions on C-contiguous arrays and scalars compiled with ``cache=True``;
:class:`navkit.mapping.OccupancyGrid` validates input before calling them. They
allocate nothing and are compiled without numba's reference counting
(``njit_no_refcount``): with it, every call wrapped each array argument in a
MemInfo (a malloc, atomic reference counts, a free), about 0.1 µs per array,
a third of a ten-point call. Grid
cells are ``(row, col)``; continuous grid coordinates put integers at cell
centres (cell ``(r, c)`` covers ``[r - ½, r + ½) × [c - ½, c + ½)``).

:func:`world_to_cell_kernel` is called through :func:`world_to_cell_entry`,
its one compiled version (for unaligned points): calling the dispatcher with
aligned points compiles a second one.

Examples
--------
>>> import numpy as np
>>> out = np.empty((1, 2), dtype=np.int64)
>>> world_to_cell_entry()(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, out)
True
>>> out
array([[0, 1]])
>>> cont = np.empty((1, 2))
>>> world_to_continuous_kernel(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, cont)
>>> cont.round(12)
array([[-0.1,  0.9]])
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_no_refcount

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

__all__ = [
    "cell_to_world_entry",
    "cell_to_world_kernel",
    "world_to_cell_entry",
    "world_to_cell_kernel",
    "world_to_continuous_kernel",
]

#: Grid coordinates are clamped to ±2**62: far outside any grid, and no int64
#: conversion can overflow (a point at 1e300 m would otherwise wrap around).
_LIMIT = float(2**62)


@njit_no_refcount
def world_to_cell_kernel(
    points: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> bool:
    """Fill ``out`` (N, 2) int64 with the ``(row, col)`` cell of each ``(x, y)`` point.

    The cell is ``floor`` of the point's coordinates in the grid frame divided by
    the resolution, so indices outside the grid are returned as they are, up to
    ±2**62. The origin must lie within ±1e9 m (then nothing here is NaN).
    Returns whether every point was finite (if not, ``out`` is meaningless), so
    that callers need no separate finiteness pass.
    """
    inv_res = 1.0 / resolution
    c = math.cos(origin_yaw)
    s = math.sin(origin_yaw)
    # Flat views of the C-contiguous arrays: LLVM vectorises this form (about
    # twice as fast as indexing [i, 0], clamps included).
    xy = points.reshape(-1)
    flat = out.reshape(-1)
    finite = True
    for i in range(points.shape[0]):
        x = xy[2 * i]
        y = xy[2 * i + 1]
        # x - x is 0 for a finite x and NaN otherwise; & keeps the loop branch-free.
        finite &= (x - x == 0.0) & (y - y == 0.0)
        dx = x - origin_x
        dy = y - origin_y
        flat[2 * i] = math.floor(min2(max2((-s * dx + c * dy) * inv_res, -_LIMIT), _LIMIT))
        flat[2 * i + 1] = math.floor(min2(max2((c * dx + s * dy) * inv_res, -_LIMIT), _LIMIT))
    return finite


@njit_no_refcount
def world_to_continuous_kernel(
    points: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> None:
    """Fill ``out`` (N, 2) float64 with continuous ``(row, col)`` coordinates of points.

    Integers are cell centres: a point at the lower-left corner of cell (0, 0) is
    at ``(-0.5, -0.5)``. Clamped to ±2**62, as :func:`world_to_cell_kernel`.
    """
    inv_res = 1.0 / resolution
    c = math.cos(origin_yaw)
    s = math.sin(origin_yaw)
    xy = points.reshape(-1)
    flat = out.reshape(-1)
    for i in range(points.shape[0]):
        dx = xy[2 * i] - origin_x
        dy = xy[2 * i + 1] - origin_y
        flat[2 * i] = min2(max2((-s * dx + c * dy) * inv_res - 0.5, -_LIMIT), _LIMIT)
        flat[2 * i + 1] = min2(max2((c * dx + s * dy) * inv_res - 0.5, -_LIMIT), _LIMIT)


def world_to_cell_entry() -> Callable[..., bool]:
    """Compiled entry of :func:`world_to_cell_kernel` for float64 points, skipping dispatch.

    Calling a numba dispatcher first types every argument to pick the compiled
    version (about 0.1 µs, a third of the kernel's time on ten points); the entry
    returned here is that version itself, compiled (or loaded from the cache)
    now. It checks nothing: the caller guarantees C-contiguous (N, 2) float64
    points (read-only and unaligned ones are fine: the kernel only reads them,
    and it is compiled for unaligned data, whose loads on x86-64 and AArch64
    cost the same as aligned ones and give the same values), four
    floats and a writable C-contiguous (N, 2) int64 ``out``; anything else reads
    or writes the wrong memory.

    Examples
    --------
    >>> out = np.empty((1, 2), dtype=np.int64)
    >>> world_to_cell_entry()(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, out), out
    (True, array([[0, 1]]))
    """
    # The dispatcher first: it loads numba (holding a Ctrl-C back until numba is
    # fully imported), which the import below would do unguarded.
    dispatcher: Any = world_to_cell_kernel
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return _python_cells_entry
    from numba import types  # here: importing this module must not import numba

    signature = (
        types.Array(types.float64, 2, "C", aligned=False),
        *(types.float64,) * 4,  # origin x, y, yaw, resolution
        types.Array(types.int64, 2, "C"),
    )
    return cast(Callable[..., bool], dispatcher.compile(signature))


def _python_cells_entry(
    points: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> bool:
    """:func:`world_to_cell_kernel` run as Python (``NUMBA_DISABLE_JIT=1``), as compiled.

    Compiled, a NaN or infinite point gives False (the caller's general way then
    names the argument). As Python the kernel reads NumPy scalars: ``inf - inf``
    obeys the caller's :func:`numpy.seterr` (a ``FloatingPointError`` under
    ``all="raise"``, a ``RuntimeWarning`` by default) and ``math.floor`` of a
    NaN raises ``ValueError``; both are the same False here.
    """
    with np.errstate(all="ignore"):
        try:
            return bool(
                world_to_cell_kernel(points, origin_x, origin_y, origin_yaw, resolution, out)
            )
        except (ValueError, OverflowError):
            return False


@njit_no_refcount
def cell_to_world_kernel(
    cells: np.ndarray,
    origin_x: float,
    origin_y: float,
    cos_yaw: float,
    sin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> bool:
    """Fill ``out`` (N, 2) float64 with the world points ``(x, y)`` of ``(row, col)`` cells.

    ``OccupancyGrid.cell_to_world``'s general arithmetic, operation for
    operation (its results bit for bit): the point ``((col + ½) res,
    (row + ½) res)`` in the grid frame, rotated by ``(cos_yaw, sin_yaw)`` and
    shifted by the origin. Returns whether every cell lay within ±2**62 and
    every point is finite; if not, ``out`` is meaningless (the caller's
    general way then raises or rescales).
    """
    rc = cells.reshape(-1)
    flat = out.reshape(-1)
    ok = True
    for i in range(cells.shape[0]):
        row = float(rc[2 * i])
        col = float(rc[2 * i + 1])
        # NaN fails both comparisons; & keeps the loop branch-free.
        ok &= (abs(row) <= _LIMIT) & (abs(col) <= _LIMIT)
        px = (col + 0.5) * resolution
        py = (row + 0.5) * resolution
        wx = px * cos_yaw - py * sin_yaw + origin_x
        wy = px * sin_yaw + py * cos_yaw + origin_y
        flat[2 * i] = wx
        flat[2 * i + 1] = wy
        ok &= (wx - wx == 0.0) & (wy - wy == 0.0)
    return ok


def cell_to_world_entry(dtype: np.dtype[Any]) -> Callable[..., bool]:
    """The compiled entry of :func:`cell_to_world_kernel` for cells of ``dtype``.

    ``dtype`` is float64 or int64. As :func:`world_to_cell_entry`: no dispatch,
    no checks; the caller guarantees C-contiguous (N, 2) cells of that dtype
    (read-only or unaligned are fine), five floats and a writable C-contiguous
    (N, 2) float64 ``out``. One entry per dtype, compiled when first asked for
    (0.3 s each in a cold cache: a map planner needs float64 only, the greedy
    step int64 only).

    Examples
    --------
    >>> out = np.empty((1, 2))
    >>> entry = cell_to_world_entry(np.dtype(np.int64))
    >>> entry(np.array([[0, 1]]), 0.0, 0.0, 1.0, 0.0, 0.5, out), out
    (True, array([[0.75, 0.25]]))
    """
    dispatcher: Any = cell_to_world_kernel
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return cast(Callable[..., bool], dispatcher)
    from numba import types  # here: importing this module must not import numba

    kind = types.float64 if dtype == np.float64 else types.int64
    signature = (
        types.Array(kind, 2, "C", aligned=False),
        *(types.float64,) * 5,  # origin x, y, cos and sin of its yaw, resolution
        types.Array(types.float64, 2, "C"),
    )
    return cast(Callable[..., bool], dispatcher.compile(signature))
