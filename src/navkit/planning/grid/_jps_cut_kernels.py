"""numba kernels for jump point search with corner cutting (private).

The 8-connected graph in which a diagonal move needs only its two end cells
to be traversable (``corner_cutting=True``; pyastar2d's, tcod's and
scikit-image's ``MCP_Geometric`` graph) is the one of the original jump
point search (D. Harabor and A. Grastien, "Online Graph Pruning for
Pathfinding on Grid Maps", AAAI 2011). Its pruning rules, for a node x
reached from its parent by a move d:

* straight move, say east: the natural successor is the cell ahead. A side
  cell, say north, that is blocked *forces* the diagonal cell ahead of it
  (north-east) when that one is free: the parent reaches it in 1 + sqrt(2)
  only through x or the north cell. The cells beside and behind x are
  reached from the parent at least as cheaply without x.
* diagonal move, say north-east: the natural successors are north, east and
  north-east. A blocked west cell forces north-west when that is free (the
  parent, south-west of x, reaches north-west in 2 only through the west
  cell, and in 2 sqrt(2) through x), and a blocked south cell forces
  south-east likewise.

A straight scan stops at a cell with a forced neighbour (or at the goal); a
diagonal scan stops at a cell with a forced neighbour, or from which either
straight scan along its two components reaches a jump point; the start scans
all eight directions. The 2011 paper proves that A* over these jump points
returns optimal paths.

Diagonal jump points of the second kind are not queued. Expanding such a
cell z, reached diagonally, would rescan exactly what the diagonal walk
has just scanned from it: its two straight scans (z has no forced
neighbour) and the diagonal ahead. So the walk records z (cost and parent,
for the path), queues the jump points its straight scans found with z as
their parent and walks on: every queued node gets the cost of a real path
and the search is A* on the jump point graph plus these shortcut edges,
which changes no distance, so it stays exact. z itself stays open, not
closed: reached again at a lower cost it is queued and expanded as usual;
reached at no lower cost (``_reach`` refuses), the walk stops there, since
everything beyond it is (or will be) reached more cheaply from it. On
random maps, where most diagonal steps stop a scan, this saves a fifth to
a third of the queue operations and expansions.

Bit-parallel stop conditions. Scanning east along row q, cell x is a stop
when it is blocked (the scan fails) or, for a side row s (q - 1 or q + 1),
``s[x]`` is blocked while ``s[x + 1]`` is free. With ``b``, ``a`` and ``d`` the
64-bit words of rows q, q - 1 and q + 1 and ``ahead(s)`` the word of s
shifted so that bit i holds cell i + 1 (its top bit borrowed from the next
word)::

    stops = ~b | (ahead(a) & ~a) | (ahead(d) & ~d)

Scanning west, ``ahead`` shifts the other way (bit i holds cell i - 1); the
column scans do the same on the transposed table. (Without corner cutting
the side test looks back instead, ``s[x]`` free and ``s[x - 1]`` blocked;
:func:`navkit.planning.grid._jps_kernels._scan_line` does both.)

The tables, queue, node records and path tracing are those of
:mod:`navkit.planning.grid._jps_kernels`; this module only holds what the
corner-cutting rules change, compiled when first requested. The queue's
order is that module's too: f with its lowest ``F_TIE_BITS`` bits cleared,
then the tie key (review 40; on MovingAI's ``random512-10-0`` 1,807,384
jump points expanded over its problems with f compared exactly, 1,114,374
now). (numba's cache keys :func:`jps_cut_search` on this file alone: a
change to the queue in the other module needs this file changed too, or
the cache deleted; see ``docs/compilation.md``.)
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, njit_released, typed_njit
from navkit._shared.types import KernelInt

# jps_cut_search's machine code holds these helpers, and numba keys its cache on
# this file alone: a change to them is recorded here so that a cache built with
# the old ones is dropped (review 50: the queue's comparison written out).
from navkit.planning.grid._jps_kernels import (
    _DC,
    _DR,
    SQRT2,
    _begin,
    _expand,
    _finish,
    _free,
    _line_end,
    _next_node,
    _offer,
    _reach,
    _scan_line,
)
from navkit.planning.grid._search_heap import FLOAT_TIE_LIMIT, tie_resolution

# The helpers' options, as _jps_kernels' (written here: numba's cache keys a kernel's
# code on its own file, so options imported from another file could change without
# recompiling these). Typed once each; the inlined ones by LLVM into each caller.
_helper_not_inlined = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=False)
_helper_inlined = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=True)


@_helper_not_inlined
def _scan_forward_cut(
    bits: np.ndarray, nw: int, line: KernelInt, p: KernelInt, target: int
) -> KernelInt:
    """:func:`~navkit.planning.grid._jps_kernels._scan_line` towards larger positions, cutting."""
    return _scan_line(bits, nw, line, p, target, np.int64(1), np.bool_(True))


@_helper_not_inlined
def _scan_backward_cut(
    bits: np.ndarray, nw: int, line: KernelInt, p: KernelInt, target: int
) -> KernelInt:
    """:func:`~navkit.planning.grid._jps_kernels._scan_line` towards smaller positions, cutting."""
    return _scan_line(bits, nw, line, p, target, np.int64(-1), np.bool_(True))


@_helper_inlined
def _scan(
    row_bits: np.ndarray,
    hw: int,
    col_bits: np.ndarray,
    vw: int,
    q: KernelInt,
    p: KernelInt,
    k: int,
    gq: int,
    gp: int,
) -> KernelInt:
    """Padded position along its line of the next jump point from (q, p) in straight direction k.

    -1 when a blocked cell comes first. ``(gq, gp)`` is the padded goal.
    """
    if k >= 2:
        on_row = gp if q == gq else -1
        if k == 3:
            return _scan_forward_cut(row_bits, hw, q, p, on_row)
        return _scan_backward_cut(row_bits, hw, q, p, on_row)
    on_col = gq if p == gp else -1
    if k == 1:
        return _scan_forward_cut(col_bits, vw, p, q, on_col)
    return _scan_backward_cut(col_bits, vw, p, q, on_col)


@_helper_not_inlined
def _diagonal_forced(bits: np.ndarray, nw: int, q: int, p: int, dr: int, dc: int) -> bool:
    """Whether padded (q, p), reached by the diagonal move (dr, dc), has a forced neighbour.

    The cell behind it along either component is blocked while the cell
    beside that one, on the side the move goes, is free.
    """
    return (not _free(bits, nw, q, p - dc) and _free(bits, nw, q + dr, p - dc)) or (
        not _free(bits, nw, q - dr, p) and _free(bits, nw, q - dr, p + dc)
    )


@_helper_inlined
def _add_on_line(
    blocks: np.ndarray,
    g: np.ndarray,
    meta: np.ndarray,
    stamp: int,
    heap: np.ndarray,
    n: KernelInt,
    next_f: float,
    next_key: float,
    next_v: KernelInt,
    x: KernelInt,
    k: int,
    r: KernelInt,
    c: KernelInt,
    gu: float,
    u: KernelInt,
    cols: int,
    gr: int,
    gc: int,
    tie_res: float,
) -> tuple[KernelInt, float, float, KernelInt]:
    """Reach the jump point a straight scan k from node ``u`` = (r, c) found, and queue it.

    ``x`` is its padded position along the scanned line, ``gu`` the cost of
    ``u``. Nothing changes when the jump point is closed or open at no
    higher cost. Returns the queue state as
    :func:`~navkit.planning.grid._jps_kernels._offer`.
    """
    vr, vc, run = _line_end(r, c, r + 1, c + 1, k, x)
    v = vr * cols + vc
    if not _reach(blocks, g, meta, stamp, v, gu + run, u, k):
        return n, next_f, next_key, next_v
    return _offer(heap, n, next_f, next_key, next_v, v, vr, vc, gu + run, gr, gc, tie_res)


@_helper_not_inlined
def _successor_directions(
    row_bits: np.ndarray, hw: int, q: KernelInt, p: KernelInt, d: KernelInt
) -> KernelInt:
    """Bit set of the directions (0-7) to scan from padded (q, p) reached by move ``d``.

    ``d`` is -1 at the start (every direction). Directions are those of
    :mod:`navkit.planning.grid._jps_kernels`: 0-3 N, S, W, E; 4-7 NW, NE, SW, SE.
    """
    if d < 0:
        return 0xFF
    dr = _DR[d]
    dc = _DC[d]
    if d >= 4:
        # Natural: both straight components and the diagonal itself; forced:
        # the diagonals that turn back along one component past a blocked cell.
        out = (1 << (0 if dr < 0 else 1)) | (1 << (2 if dc < 0 else 3)) | (1 << d)
        if not _free(row_bits, hw, q, p - dc) and _free(row_bits, hw, q + dr, p - dc):
            out |= 1 << (4 + (dr > 0) * 2 + (dc < 0))
        if not _free(row_bits, hw, q - dr, p) and _free(row_bits, hw, q - dr, p + dc):
            out |= 1 << (4 + (dr < 0) * 2 + (dc > 0))
        return out
    out = 1 << d
    if dr == 0:
        # Horizontal: the side cells above and below.
        ahead = p + dc
        if not _free(row_bits, hw, q - 1, p) and _free(row_bits, hw, q - 1, ahead):
            out |= 1 << (4 + (dc > 0))
        if not _free(row_bits, hw, q + 1, p) and _free(row_bits, hw, q + 1, ahead):
            out |= 1 << (6 + (dc > 0))
    else:
        ahead = q + dr
        if not _free(row_bits, hw, q, p - 1) and _free(row_bits, hw, ahead, p - 1):
            out |= 1 << (4 + (dr > 0) * 2)
        if not _free(row_bits, hw, q, p + 1) and _free(row_bits, hw, ahead, p + 1):
            out |= 1 << (5 + (dr > 0) * 2)
    return out


@njit_released
def jps_cut_search(
    row_bits: np.ndarray,
    col_bits: np.ndarray,
    rows: int,
    cols: int,
    start: int,
    goal: int,
    g: np.ndarray,
    meta: np.ndarray,
    blocks: np.ndarray,
    heap: np.ndarray,
    stamp: int,
) -> tuple[int, int, int, int]:
    """A* over the jump points of the corner-cutting graph from ``start`` to ``goal``.

    Arguments and results are those of
    :func:`navkit.planning.grid._jps_kernels.jps_search` (the same tables,
    node records, stamps and queue); only the graph differs: a diagonal move
    needs its two end cells traversable and nothing else. ``expanded``
    counts queued jump points only (see the module notes).
    """
    hw, vw, gr, gc = _begin(rows, cols, start, goal, g, meta)
    # Ties to 1/16 cell unless rows + cols >= 2**17 (see _search_heap).
    tie_res = tie_resolution(rows, cols, FLOAT_TIE_LIMIT)
    gq = gr + 1
    gp = gc + 1
    n: KernelInt = np.int64(0)
    expanded = 0
    u: KernelInt = start
    next_v: KernelInt
    while u != goal:
        r, c, gu, d = _expand(blocks, stamp, u, cols, g, meta)
        expanded += 1
        q = r + 1
        p = c + 1
        dirs = _successor_directions(row_bits, hw, q, p, d)
        next_f, next_key, next_v = np.inf, np.inf, np.int64(-1)
        for k in range(8):
            if not (dirs >> k) & 1:
                continue
            if k < 4:
                x = _scan(row_bits, hw, col_bits, vw, q, p, k, gq, gp)
                if x >= 0:
                    n, next_f, next_key, next_v = _add_on_line(
                        blocks, g, meta, stamp, heap, n, next_f, next_key, next_v,
                        x, k, r, c, gu, u, cols, gr, gc, tie_res,
                    )  # fmt: skip
                if n < 0:
                    return expanded, -1, 0, 0
                continue
            # The diagonal walk. A cell with a forced neighbour (or the goal)
            # is a jump point, queued. A cell from which a straight scan
            # reaches a jump point is one only for those scans: it is
            # recorded (its parent links the path) but not queued, its
            # straight successors are queued at once and the walk goes on,
            # which is what expanding it would do.
            dr = _DR[k]
            dc = _DC[k]
            kh = 2 if dc < 0 else 3
            kv = 0 if dr < 0 else 1
            parent = u
            zr = r
            zc = c
            steps = 0
            while True:
                zr += dr
                zc += dc
                if not _free(row_bits, hw, zr + 1, zc + 1):
                    break
                z = zr * cols + zc
                steps += 1
                gz = gu + SQRT2 * steps
                if z == goal or _diagonal_forced(row_bits, hw, zr + 1, zc + 1, dr, dc):
                    if _reach(blocks, g, meta, stamp, z, gz, parent, k):
                        n, next_f, next_key, next_v = _offer(
                            heap, n, next_f, next_key, next_v, z, zr, zc, gz, gr, gc, tie_res
                        )
                    break
                xh = _scan(row_bits, hw, col_bits, vw, zr + 1, zc + 1, kh, gq, gp)
                xv = _scan(row_bits, hw, col_bits, vw, zr + 1, zc + 1, kv, gq, gp)
                if xh < 0 and xv < 0:
                    continue
                # Reached before at no higher cost: its successors are
                # (or will be) reached from there.
                if not _reach(blocks, g, meta, stamp, z, gz, parent, k):
                    break
                parent = z
                for kk, x in ((kh, xh), (kv, xv)):
                    if x >= 0:
                        n, next_f, next_key, next_v = _add_on_line(
                            blocks, g, meta, stamp, heap, n, next_f, next_key, next_v,
                            x, kk, zr, zc, gz, z, cols, gr, gc, tie_res,
                        )  # fmt: skip
                        if n < 0:
                            return expanded, -1, 0, 0
            if n < 0:
                return expanded, -1, 0, 0
        u, n = _next_node(heap, n, next_f, next_key, next_v, blocks)
        if u < 0:
            return expanded, 0, 0, 0
    return _finish(expanded + 1, meta, cols, goal, heap)
