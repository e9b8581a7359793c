"""Bresenham line kernels shared by the mapping and planning layers (private).

``line_is_free(occupied, r0, c0, r1, c1) -> bool``
    True when no cell of the Bresenham line between the two cells (both ends
    included) is occupied or outside the grid.
``line_cells(r0, c0, r1, c1) -> int64 (n, 2)``
    The cells of that same line, in order from ``(r0, c0)`` to ``(r1, c1)``.
``bresenham_step``
    One step of the integer walk, for kernels that walk lines themselves.

The line is the classic 8-connected Bresenham line, made symmetric: it is always
traced from the lexicographically smaller end, so ``a -> b`` and ``b -> a`` visit
the same cells. Being 8-connected, it can pass diagonally between two occupied
cells that touch only at a corner. Grid cells are ``(row, col)``.
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import njit_cached, njit_inline
from navkit._shared.types import BoolArray, IntArray


@njit_inline
def _ordered(r0: int, c0: int, r1: int, c1: int) -> tuple[int, int, int, int]:
    """Endpoints swapped so the trace starts at the lexicographically smaller cell."""
    if r1 < r0 or (r1 == r0 and c1 < c0):
        return r1, c1, r0, c0
    return r0, c0, r1, c1


@njit_inline
def bresenham_step(
    r: int, c: int, err: int, dr: int, dc: int, sr: int, sc: int
) -> tuple[int, int, int]:
    """One step of the integer Bresenham walk (``dr``, ``dc`` >= 0, ``sr``, ``sc`` = ±1).

    Start with ``err = dc - dr``; each call moves to the next cell of the line.
    """
    e2 = 2 * err
    if e2 > -dr:
        err -= dr
        c += sc
    if e2 < dc:
        err += dc
        r += sr
    return r, c, err


@njit_cached
def line_is_free(occupied: BoolArray, r0: int, c0: int, r1: int, c1: int) -> bool:
    """Whether the Bresenham line between two cells crosses only free cells.

    Parameters
    ----------
    occupied : bool ndarray, shape (rows, cols)
        True where a cell blocks the line.
    r0, c0, r1, c1 : int
        End cells ``(row, col)``; both ends are tested.

    Returns
    -------
    bool
        False as soon as a cell of the line is occupied or lies outside the grid.
    """
    rows = occupied.shape[0]
    cols = occupied.shape[1]
    ra, ca, rb, cb = _ordered(r0, c0, r1, c1)
    dr = abs(rb - ra)
    dc = abs(cb - ca)
    sr = 1 if rb > ra else -1
    sc = 1 if cb > ca else -1
    err = dc - dr
    r = ra
    c = ca
    while True:
        if r < 0 or r >= rows or c < 0 or c >= cols or occupied[r, c]:
            return False
        if r == rb and c == cb:
            return True
        r, c, err = bresenham_step(r, c, err, dr, dc, sr, sc)


@njit_cached
def line_cells(r0: int, c0: int, r1: int, c1: int) -> IntArray:
    """Cells ``(row, col)`` of the Bresenham line from ``(r0, c0)`` to ``(r1, c1)``.

    Returns a new int64 array of shape ``(max(|dr|, |dc|) + 1, 2)`` ordered from
    the first cell to the second; the set of cells is the one :func:`line_is_free`
    tests.
    """
    ra, ca, rb, cb = _ordered(r0, c0, r1, c1)
    dr = abs(rb - ra)
    dc = abs(cb - ca)
    n = max(dr, dc) + 1
    out = np.empty((n, 2), dtype=np.int64)
    sr = 1 if rb > ra else -1
    sc = 1 if cb > ca else -1
    err = dc - dr
    r = ra
    c = ca
    reverse = ra != r0 or ca != c0
    for k in range(n):
        slot = n - 1 - k if reverse else k
        out[slot, 0] = r
        out[slot, 1] = c
        r, c, err = bresenham_step(r, c, err, dr, dc, sr, sc)
    return out

