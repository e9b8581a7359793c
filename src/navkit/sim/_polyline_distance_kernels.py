"""numba kernels: distance from many points to a polyline (private).

Used for the cross-track error of a run against its reference path.

* :func:`point_polyline_distances`: every point against every segment,
  O(points x segments); the fastest for short paths.
* :func:`point_polyline_distances_chunked`: the same distances, bit for bit, in
  sub-quadratic time for long paths. The segments are grouped in chunks of
  :data:`CHUNK` consecutive segments and the chunks in groups of :data:`GROUP`,
  each with its bounding box (``boxes``, made by :func:`chunk_boxes` in NumPy:
  a loop in the kernel would cost first-use compile time). Each point starts
  from the chunk that held the previous point's nearest segment (a run follows
  its path), then skips every group and chunk whose box is farther than the
  best distance so far. A box is skipped only when it is farther by more than
  the rounding of any of its segments' computed distances can reach (``SLACK``
  times its width plus height, far above that rounding), so a skipped segment
  could not have given a smaller value: the result is the minimum over the same computed values as
  :func:`point_polyline_distances`, the same floats.

Examples
--------
>>> import numpy as np
>>> out = np.empty(2)
>>> point_polyline_distances(np.array([[0.5, 1.0], [3.0, 0.0]]),
...                          np.array([[0.0, 0.0], [2.0, 0.0]]), out)
>>> out.tolist()
[1.0, 1.0]
>>> s = np.linspace(0.0, 100.0, 1001)
>>> path = np.column_stack([s, np.sin(s)])
>>> pts = np.array([[10.0, 3.0], [50.0, -2.0], [120.0, 0.0]])
>>> chunked = np.empty(3)
>>> point_polyline_distances_chunked(pts, path, chunk_boxes(path), chunked)
>>> plain = np.empty(3)
>>> point_polyline_distances(pts, path, plain)
>>> bool(np.array_equal(chunked, plain))
True
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_force_inline, njit_released
from navkit._shared.types import KernelInt

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

__all__ = [
    "CHUNK",
    "GROUP",
    "SIMPLE_MAX_SEGMENTS",
    "chunk_boxes",
    "point_polyline_distances",
    "point_polyline_distances_chunked",
]

#: Consecutive segments per chunk (one bounding box each).
CHUNK = 32
#: Chunks per group (one bounding box around their boxes).
GROUP = 32
#: Paths of at most this many segments go to :func:`point_polyline_distances`
#: (one chunk: nothing to skip; 30,001 points: 21 ms plain, 24 ms chunked at 32
#: segments, 37 against 26 ms at 64).
SIMPLE_MAX_SEGMENTS = 32
#: A box is skipped when its distance exceeds the best distance so far by more
#: than this times its width plus height (and by a relative 1e-12). The computed
#: distance to a segment errs by at most a few units in the last place of the
#: point's offset from the segment and of the segment's length, both bounded by
#: the box's distance plus twice its width plus height: about 1e-15 of them.
SLACK = 1e-12


def chunk_boxes(path: np.ndarray) -> np.ndarray:
    """The boxes :func:`point_polyline_distances_chunked` prunes ``path``'s segments with.

    Parameters
    ----------
    path : numpy.ndarray
        The polyline's vertices, shape (K, 2), K >= 1.

    Returns
    -------
    numpy.ndarray
        One row per chunk of :data:`CHUNK` segments, then one per group of
        :data:`GROUP` chunks: ``x0, y0, x1, y1`` (the bounding box of their
        vertices) and the slack ``SLACK * ((x1 - x0) + (y1 - y0))``. A NaN
        coordinate makes its box NaN, which the kernel never skips.

    Examples
    --------
    >>> boxes = chunk_boxes(np.array([[0.0, 0.0], [2.0, 1.0], [1.0, -1.0]]))
    >>> boxes[:, :4].tolist()
    [[0.0, -1.0, 2.0, 1.0], [0.0, -1.0, 2.0, 1.0]]
    """
    nseg = path.shape[0] - 1
    if nseg <= 0:
        return np.empty((0, 5))
    # Chunk c holds segments c*CHUNK .. : vertices c*CHUNK to its last segment's end.
    starts = np.arange(0, nseg, CHUNK)
    ends = np.minimum(starts + CHUNK, nseg)
    body = path[:nseg]
    lo = np.minimum(np.minimum.reduceat(body, starts, axis=0), path[ends])
    hi = np.maximum(np.maximum.reduceat(body, starts, axis=0), path[ends])
    groups = np.arange(0, starts.shape[0], GROUP)
    lo = np.concatenate([lo, np.minimum.reduceat(lo, groups, axis=0)])
    hi = np.concatenate([hi, np.maximum.reduceat(hi, groups, axis=0)])
    boxes = np.empty((lo.shape[0], 5))
    boxes[:, :2] = lo
    boxes[:, 2:4] = hi
    boxes[:, 4] = SLACK * ((hi[:, 0] - lo[:, 0]) + (hi[:, 1] - lo[:, 1]))
    return boxes


@njit_force_inline
def _nearer(
    px: float, py: float, path: np.ndarray, j0: KernelInt, j1: KernelInt, best: float
) -> float:
    """The least of ``best`` and the distances from ``(px, py)`` to segments ``j0 .. j1 - 1``.

    The one segment loop of both kernels: the chunked kernel's distances are the
    plain one's, bit for bit, because they are computed here alike.
    """
    for j in range(j0, j1):
        ax = path[j, 0]
        ay = path[j, 1]
        ex = path[j + 1, 0] - ax
        ey = path[j + 1, 1] - ay
        wx = px - ax
        wy = py - ay
        ee = ex * ex + ey * ey
        t = 0.0
        if ee > 0.0:
            t = min2(max2((wx * ex + wy * ey) / ee, 0.0), 1.0)
        d = math.hypot(wx - t * ex, wy - t * ey)
        if d < best:
            best = d
    return best


@njit_released
def point_polyline_distances(points: np.ndarray, path: np.ndarray, out: np.ndarray) -> None:
    """``out[i]``: distance from ``points[i]`` to the polyline ``path`` (K >= 1 vertices)."""
    nseg = path.shape[0] - 1
    # Typed int64, not the literal 0: a literal argument compiles _nearer once more.
    first = np.int64(0)
    for i in range(points.shape[0]):
        px = points[i, 0]
        py = points[i, 1]
        best = math.hypot(px - path[0, 0], py - path[0, 1])
        out[i] = _nearer(px, py, path, first, nseg, best)


@njit_released
def point_polyline_distances_chunked(
    points: np.ndarray, path: np.ndarray, boxes: np.ndarray, out: np.ndarray
) -> None:
    """:func:`point_polyline_distances`, pruned by :func:`chunk_boxes` ``boxes``."""
    nseg = path.shape[0] - 1
    nchunk = (nseg + CHUNK - 1) // CHUNK
    hint = 0
    for i in range(points.shape[0]):
        px = points[i, 0]
        py = points[i, 1]
        best = math.hypot(px - path[0, 0], py - path[0, 1])
        found = hint
        # The previous point's chunk first, unboxed (c = -1); then, in order,
        # each group's box and, if it is near, its chunks' boxes.
        c = -1
        grouped = False
        while c < nchunk:
            if c < 0:
                r = hint
                far = nchunk == 0
                c = 0
            else:
                r = c
                if c % GROUP == 0 and not grouped:
                    r = nchunk + c // GROUP
                far = r == hint
                if not far:
                    dx = 0.0
                    if px < boxes[r, 0]:
                        dx = boxes[r, 0] - px
                    elif px > boxes[r, 2]:
                        dx = px - boxes[r, 2]
                    dy = 0.0
                    if py < boxes[r, 1]:
                        dy = boxes[r, 1] - py
                    elif py > boxes[r, 3]:
                        dy = py - boxes[r, 3]
                    reach = best + boxes[r, 4]
                    # Far beyond rounding; a NaN best compares False: nothing skipped.
                    far = dx * dx + dy * dy > reach * reach * (1.0 + 1e-12)
                if r >= nchunk:
                    if far:
                        c += GROUP
                    else:
                        grouped = True
                    continue
                grouped = False
                c += 1
            if far:
                continue
            j1 = r * CHUNK + CHUNK
            if j1 > nseg:
                j1 = nseg
            lower = _nearer(px, py, path, r * CHUNK, j1, best)
            if lower < best:
                best = lower
                found = r
        hint = found
        out[i] = best
