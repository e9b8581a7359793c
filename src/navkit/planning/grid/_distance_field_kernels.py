"""numba kernels for whole-grid distance fields: a bucket-queue Dijkstra (private).

Same graph as :mod:`navkit.planning.grid._astar_kernels` (a move between
neighbouring traversable cells u, v costs ``step * (c_u + c_v) / 2``, ``step``
1 or sqrt(2); without corner cutting a diagonal also needs both cells it passes
beside), evaluated with the same floating-point operations, so the fields are
bit-identical to Dijkstra's (see *Exactness* below).

Queue. Every move costs at least ``delta`` = the smallest cell cost (an
orthogonal move between two cheapest cells) and at most ``w_max`` (a diagonal,
or with 4-connectivity an orthogonal move, between two dearest cells). Cells are
kept in buckets of width ``width = delta * (1 - 2**-10)``: bucket ``k`` holds the
cells whose tentative cost ``g`` has ``int(g / width) == k``. A cell of bucket
``k`` can only lower its neighbours to buckets ``> k`` (its moves cost at least
``delta > width``), so the cells of the lowest non-empty bucket are final and are
expanded in any order: Dial's algorithm with buckets one move wide, O(1) per
queue operation instead of a heap's O(log n). Only ``w_max / width + 2``
buckets are ever non-empty at once; they live in a ring of ``B`` (a power of two)
slots, each an array segment of ``cap`` cell ids. A cell lowered within its
bucket is not queued again; one lowered into another bucket is queued again and
its stale entry is skipped when popped (its bucket no longer matches).

The grid is padded with a border of impassable cells, so no move needs a bounds
test and cell ids need no division: neighbours are fixed flat offsets.
Traversability is read from a byte mask; when every traversable cell costs the
same the float costs are not read at all (the two move costs are constants,
computed with the same operations).

Exactness. The result is the least float64 sum, over all paths, of the move
costs added one by one from the goal (rounding is monotone, so this is the least
fixed point of the Bellman equations): Dijkstra computes it, and so does this
kernel. The bucket width's margin (2**-10 of ``delta``) exceeds the relative
rounding of ``g / width`` over 2**41 buckets, so a final cell is never lowered
again; if rounding ever did lower one it would be re-queued (its new bucket
differs), which keeps the result the least fixed point.

Indices stay signed (review 25): indexed with ``np.uint64`` as A* is (see
Indices in :mod:`navkit.planning.grid._astar_kernels`), the expansion loop lost
its wraparound code (26 -> 1 ``sar``/``and`` pairs) but the field took the same time
(÷ the heap Dijkstra of the A* kernel on the 1024² maps and the weighted one,
with and without corner cutting: 0.985-1.003 of before, medians of 10
alternating runs), so the change was dropped.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, njit_released, typed_njit

SQRT2 = math.sqrt(2.0)
_HALF_ORTHO = 0.5
_HALF_DIAG = SQRT2 * 0.5  # the A* kernel's ``step * 0.5`` for a diagonal

WIDTH_MARGIN = 1.0 - 2.0**-10
"""Bucket width as a fraction of the cheapest move."""
MAX_SLOTS = 64
"""Largest bucket ring (dearest move / cheapest move up to about 61)."""
DONE = 0
"""Status of :func:`bucket_field`: every reachable cell is final."""
GROW = 1
"""Status of :func:`bucket_field`: a bucket segment is full; enlarge ``cap`` and call again."""


@njit_released
def pad_grid(
    flat: np.ndarray,
    rows: int,
    cols: int,
    free: np.ndarray,
    padded: np.ndarray,
    uniform: bool,
    dist: np.ndarray,
) -> None:
    """Write the padded grid (``(rows + 2) * (cols + 2)`` cells, border impassable).

    ``free[i]`` is 1 for a traversable cell, 0 else; unless ``uniform``, ``padded``
    receives the costs (border inf). Every entry of ``dist`` (the padded field)
    is set to inf: done here rather than by a kernel of its own, whose Python
    wrapper and machine code cost about 0.04 s of first use (issue 17).
    """
    pc = cols + 2
    for j in range(pc):
        free[j] = 0
        free[(rows + 1) * pc + j] = 0
        if not uniform:
            padded[j] = np.inf
            padded[(rows + 1) * pc + j] = np.inf
    for r in range(rows):
        row = (r + 1) * pc
        free[row] = 0
        free[row + pc - 1] = 0
        if not uniform:
            padded[row] = np.inf
            padded[row + pc - 1] = np.inf
        src = r * cols
        if uniform:
            for c in range(cols):
                free[row + 1 + c] = flat[src + c] < np.inf
        else:
            for c in range(cols):
                v = flat[src + c]
                free[row + 1 + c] = v < np.inf
                padded[row + 1 + c] = v
    for i in range(dist.shape[0]):
        dist[i] = np.inf


# Typed once and inlined by LLVM into its eight call sites (numba's inline="always"
# typed the body again at each of them); no Python wrapper (called from kernels only).
@typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=True)
def _relax(
    free: np.ndarray,
    costs: np.ndarray,
    uniform: bool,
    dist: np.ndarray,
    buckets: np.ndarray,
    counts: np.ndarray,
    cap: int,
    mask: int,
    inv: float,
    v: int,
    half: float,
    gu: float,
    cu: float,
    top: int,
) -> int:
    """Lower a traversable cell ``v`` through a move; return the fullest segment size.

    The move costs ``half * (cu + costs[v])`` (``half``: half its step), or
    ``half`` itself when ``uniform`` (then the caller passes the move cost).
    """
    new = gu + (half if uniform else half * (cu + costs[v]))
    old = dist[v]
    if free[v] and new < old:
        dist[v] = new
        # np.int64 and a select, not the int and max builtins, which numba
        # compiles as overloads of their own on first use (issue 17).
        k = np.int64(new * inv)
        # A float to integer conversion of inf is undefined: test for a first
        # visit before converting.
        if old == np.inf or np.int64(old * inv) != k:
            slot = k & mask
            c: int = counts[slot] + 1
            buckets[slot * cap + c - 1] = v
            counts[slot] = c
            return c if c > top else top
    return top


@njit_released
def bucket_field(
    free: np.ndarray,
    costs: np.ndarray,
    uniform_cost: float,
    rows: int,
    cols: int,
    eight: bool,
    corner_cutting: bool,
    inv: float,
    mask: int,
    dist: np.ndarray,
    buckets: np.ndarray,
    cap: int,
    counts: np.ndarray,
    state: np.ndarray,
) -> int:
    """Run (or resume) the bucket-queue Dijkstra on a padded grid.

    Parameters
    ----------
    free : ((rows + 2) * (cols + 2),) uint8
        Padded traversability (:func:`pad_grid`): 1 traversable, 0 not (border 0).
    costs : ((rows + 2) * (cols + 2),) float64
        Padded cell costs (:func:`pad_grid`); not read (any array) when
        ``uniform_cost > 0``.
    uniform_cost : float
        The cost of every traversable cell if they all cost the same, else 0.
    rows, cols : int
        Shape of the unpadded grid.
    eight, corner_cutting : bool
        8-connected (else 4); diagonal moves beside impassable cells allowed.
    inv : float
        ``1 / width``, the reciprocal of the bucket width (see the module notes).
    mask : int
        ``B - 1`` for a ring of ``B`` bucket slots, ``B`` a power of two with
        ``B >= w_max * inv + 3``.
    dist : ((rows + 2) * (cols + 2),) float64
        Costs from the goal: inf but 0 at the goal on the first call. On return
        with :data:`DONE` the field, cropped: its first ``rows * cols`` entries
        hold the unpadded field in row-major order (every value moved towards
        the front, onto a cell already read; done here rather than by a
        kernel of its own, about 0.08 s of first use, issue 17).
    buckets : (B * cap,) int32
        Bucket segments; slot ``s`` holds ``counts[s]`` cell ids from ``s * cap``.
    cap : int
        Segment length, at least 8.
    counts : (B,) int64
        Entries per slot; on the first call 1 in the goal's slot (0) and 0 elsewhere.
    state : (3,) int64
        ``(bucket, next entry, fullest segment)``; zeros (but ``state[2] = 1``) on
        the first call. Kept between calls.

    Returns
    -------
    int
        :data:`DONE`, or :data:`GROW` when a segment could overflow during the
        next expansion: copy the segments into a larger ``cap`` and call again
        with the same ``dist``, ``counts`` and ``state``.
    """
    uniform = uniform_cost > 0.0
    # Move costs as the A* kernel computes them: step * 0.5 * (c_u + c_v).
    if uniform:
        ortho = _HALF_ORTHO * (uniform_cost + uniform_cost)
        diag = _HALF_DIAG * (uniform_cost + uniform_cost)
    else:
        ortho = _HALF_ORTHO
        diag = _HALF_DIAG
    pc = cols + 2
    n_slots = mask + 1
    k = state[0]
    i = state[1]
    top = state[2]
    while True:
        slot = k & mask
        base = slot * cap
        while i < counts[slot]:
            if top + 8 > cap:
                state[0] = k
                state[1] = i
                state[2] = top
                return GROW
            u = buckets[base + i]
            i += 1
            gu = dist[u]
            if np.int64(gu * inv) != k:
                continue  # stale: lowered into an earlier bucket and expanded there
            cu = uniform_cost if uniform else costs[u]
            top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                         u - pc, ortho, gu, cu, top)
            top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                         u + pc, ortho, gu, cu, top)
            top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                         u - 1, ortho, gu, cu, top)
            top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                         u + 1, ortho, gu, cu, top)
            if eight:
                if corner_cutting:
                    nw = ne = sw = se = True
                else:
                    # A diagonal needs both cells it passes beside (MovingAI rule).
                    n_ok = free[u - pc] != 0
                    s_ok = free[u + pc] != 0
                    w_ok = free[u - 1] != 0
                    e_ok = free[u + 1] != 0
                    nw = n_ok and w_ok
                    ne = n_ok and e_ok
                    sw = s_ok and w_ok
                    se = s_ok and e_ok
                if nw:
                    top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                                 u - pc - 1, diag, gu, cu, top)
                if ne:
                    top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                                 u - pc + 1, diag, gu, cu, top)
                if sw:
                    top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                                 u + pc - 1, diag, gu, cu, top)
                if se:
                    top = _relax(free, costs, uniform, dist, buckets, counts, cap, mask, inv,
                                 u + pc + 1, diag, gu, cu, top)
        counts[slot] = 0
        i = 0
        # Next non-empty bucket; a whole empty ring means the queue is empty.
        empty = 0
        k += 1
        while counts[k & mask] == 0:
            empty += 1
            if empty >= n_slots:
                state[0] = k
                state[1] = 0
                state[2] = top
                for r in range(rows):
                    src = (r + 1) * pc + 1
                    dst = r * cols
                    for c in range(cols):
                        dist[dst + c] = dist[src + c]
                return DONE
            k += 1
