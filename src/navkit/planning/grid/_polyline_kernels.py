"""numba kernels for exact costs of straight segments and polylines on a cost grid (private).

Points are in node coordinates (cell ``(r, c)`` covers ``[r, r+1] × [c, c+1]``;
see :mod:`navkit.planning.grid._dstar_lite_kernels`) and cell costs come from the
same ``+inf``-padded flat array ``pad`` of row width ``width = cols + 2``. A
segment pays, per unit length, the cost of the cell it crosses, or the cheaper
of the two cells beside a grid line it runs along. Used by Field D* for the
true cost of its paths and by its shortcut (smoothing) pass.

Compilation: one kernel called from Python, :func:`_polyline`, does both jobs
(:func:`shortcut` and :func:`polyline_cost` are plain Python functions calling
it), and :func:`segment_cost` is its one helper: every compiled function costs a
fixed tenth of a second or so on first use, and a helper linked into several
kernels is optimised again in each of them. Cell costs are read inline
(``pad[(r + 1) * width + c + 1]``) rather than through an IR-inlined function.
The caller passes the shortcut's output buffer, so :func:`_polyline` allocates
nothing and runs without reference counting: allocating in it compiled numba's
``np.empty`` implementation and its allocator with it (about 0.2 s of first
use). ``min()`` is written out (numba compiles it as a function of its own per
argument type set), and ``math.floor`` already returns an int: the grid line
and cell indices are kept as ints, so no ``int()`` (a compiled function of its
own) is needed. Counters start from a variable 0 and constants are frozen
globals (see :mod:`navkit.planning.grid._field_path_kernels`). The points
reach :func:`_polyline` flat (review 49): a 2-D element access lowered to
about twice the instructions of a flat one (1,911 -> 1,358 for the kernel,
numba 0.68.1).
"""

from __future__ import annotations

from math import ceil, floor, hypot
from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, RELEASES_GIL, typed_njit
from navkit.planning.grid._dstar_lite_kernels import INF

# This module's compile options, written in this file as in each Field D* kernel
# module (the heap's, the search's, the path's, the polyline's): numba's cache keys
# a kernel's machine code on its own source file only, so options imported from
# another file could change there while these kernels kept loading code compiled
# with the old ones (tests/planning/grid/test_review23_fd_kernel_options.py checks
# it, and that the four modules agree). See ``KERNEL_OPTIONS`` in
# :mod:`navkit.planning.grid._dstar_heap` for what the options are for.
KERNEL_OPTIONS: dict[str, Any] = {**NO_REFCOUNT, "error_model": "numpy"}
HELPER_OPTIONS: dict[str, Any] = {**KERNEL_OPTIONS, "no_cpython_wrapper": True}
_kernel = typed_njit(**KERNEL_OPTIONS, **RELEASES_GIL)
_helper = typed_njit(**HELPER_OPTIONS)


@_helper
def segment_cost(pad: np.ndarray, width: int, r0: float, c0: float, r1: float, c1: float) -> float:
    """Exact cost of the straight segment p0 -> p1: sum of length × cell cost.

    The segment is split where it crosses grid lines; each piece pays the cell
    it lies in, or, when the whole segment lies on a grid line (both ends on it
    exactly), the cheaper of the two cells beside it. Pieces shorter than
    1e-12 (passing through a corner) are free. Cell ``(r, c)`` costs
    ``pad[(r + 1) * width + c + 1]``.
    """
    dr = r1 - r0
    dc = c1 - c0
    length = hypot(dr, dc)
    if length == 0.0:
        return 0.0
    # Exact tests, not a tolerance: a segment a hair beside a grid line lies in
    # the cell on its side (the walk's points on a line are exactly on it), and
    # pricing it at the cheaper neighbour undercounted its cost by up to the
    # cost difference times its length.
    # Integers (floor() and ceil() return ints), so that cell indices need no int().
    fr0 = floor(r0)
    fc0 = floor(c0)
    on_row = dr == 0.0 and r0 == fr0
    on_col = dc == 0.0 and c0 == fc0
    total = 0.0
    t = 0.0
    # Index of the next integer line in each axis, stepped by counters to avoid drift.
    if dr > 0:
        nr_line = fr0 + 1
    elif dr < 0:
        nr_line = ceil(r0) - 1
    else:
        nr_line = fr0
    if dc > 0:
        nc_line = fc0 + 1
    elif dc < 0:
        nc_line = ceil(c0) - 1
    else:
        nc_line = fc0
    step_r = 1 if dr > 0 else -1
    step_c = 1 if dc > 0 else -1
    while t < 1.0:
        tr = (nr_line - r0) / dr if dr != 0.0 else INF
        tc = (nc_line - c0) / dc if dc != 0.0 else INF
        # min(tr, tc, 1.0) written out: numba compiles min() as a function of its own.
        t1 = tc if tc < tr else tr
        if t1 > 1.0:
            t1 = 1.0
        # The piece's cell from the next lines to cross, not from its midpoint: a
        # piece a hair from a grid line has a midpoint that may round onto the
        # line, whose floor is the cell beyond it (an impassable one made a
        # path's cost inf).
        cell_r = nr_line - 1 if dr > 0 else (nr_line if dr < 0 else fr0)
        cell_c = nc_line - 1 if dc > 0 else (nc_line if dc < 0 else fc0)
        if tr <= t1:
            nr_line += step_r
        if tc <= t1:
            nc_line += step_c
        piece = (t1 - t) * length
        if piece > 1e-12:
            if on_row:
                # Along row line r0: cells (r0 - 1, col) and (r0, col).
                at = fr0 * width + cell_c + 1
                cost = pad[at]
                if pad[at + width] < cost:
                    cost = pad[at + width]
            elif on_col:
                # Along column line c0: cells (row, c0 - 1) and (row, c0).
                at = (cell_r + 1) * width + fc0
                cost = pad[at]
                if pad[at + 1] < cost:
                    cost = pad[at + 1]
            else:
                cost = pad[(cell_r + 1) * width + cell_c + 1]
            if cost == INF:
                return INF
            total += cost * piece
        t = t1
    return total


@_kernel
def _polyline(
    pad: np.ndarray, width: int, pts: np.ndarray, k: int, patience: int, out: np.ndarray
) -> tuple[int, float, float]:
    """Both jobs of this module in one compiled kernel.

    ``pts`` holds the points flat (point a at ``2 a``, ``2 a + 1``), as does
    ``out``. With ``patience >= 0`` the :func:`shortcut` of the first ``k``
    points, written to the first m points of ``out`` (room for k, filled by
    the caller): (m, 0, 0); with ``patience < 0`` their :func:`polyline_cost`:
    (0, cost, length), ``out`` unused.
    """
    if patience < 0:
        cost = 0.0
        length = 0.0
        for a in range(k - 1):
            cost += segment_cost(
                pad, width, pts[2 * a], pts[2 * a + 1], pts[2 * a + 2], pts[2 * a + 3]
            )
            length += hypot(pts[2 * a + 2] - pts[2 * a], pts[2 * a + 3] - pts[2 * a + 1])
        return 0, cost, length
    # Element copies only: whole-row and slice assignments compile far more code.
    out[0] = pts[0]
    out[1] = pts[1]
    # Counters start from a variable, not a literal (one more pass of type inference).
    zero = k - k
    m = zero + 1
    i = zero
    while i < k - 1:
        best = i + 1
        acc = 0.0
        misses = zero
        j = i + 1
        while j < k:
            acc += segment_cost(
                pad, width, pts[2 * j - 2], pts[2 * j - 1], pts[2 * j], pts[2 * j + 1]
            )
            if j > i + 1:
                direct = segment_cost(
                    pad, width, pts[2 * i], pts[2 * i + 1], pts[2 * j], pts[2 * j + 1]
                )
                if direct <= acc * (1.0 + 1e-12):
                    best = j
                    misses = zero
                else:
                    misses += 1
                    if misses > patience:
                        break
            j += 1
        out[2 * m] = pts[2 * best]
        out[2 * m + 1] = pts[2 * best + 1]
        m += 1
        i = best
    return m, 0.0, 0.0


def polyline_cost(pad: np.ndarray, width: int, pts: np.ndarray, k: int) -> tuple[float, float]:
    """(cost, length) of the polyline through the first ``k`` points (node coordinates)."""
    flat = pts.reshape(-1)  # (x0, y0, x1, ...): see the module notes
    _, cost, length = _polyline(pad, width, flat, k, -1, flat)
    return cost, length


def shortcut(pad: np.ndarray, width: int, pts: np.ndarray, k: int, patience: int) -> np.ndarray:
    """Replace runs of the polyline by straight segments that cost no more (to rounding).

    From each kept point, the farthest later point whose straight segment costs
    at most the polyline between them, times ``1 + 1e-12``, is kept next (the
    allowance keeps rounding in the sums from blocking the straight segment of
    a run along a grid line); the scan gives up after ``patience`` (>= 0)
    consecutive refusals. The result's cost exceeds the input's by at most
    that relative ``1e-12`` (and rounding), and a segment through an
    impassable cell interior costs inf, so it is never taken.
    """
    out = np.empty(2 * max(k, 1))
    m: int = _polyline(pad, width, pts.reshape(-1), k, patience, out)[0]
    smooth: np.ndarray = out[: 2 * m].reshape(m, 2).copy()  # not a view of the larger buffer
    return smooth
