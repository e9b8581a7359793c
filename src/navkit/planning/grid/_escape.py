"""The start escape of ``start_tolerance`` (private): from the inflated band to a passable cell.

:meth:`navkit.planning.MapPlanner.plan` and the world methods of
:class:`navkit.planning.FieldDStar` share it. A start whose cell is impassable
only through the inflation (not a *hard* cell: an obstacle, or unknown space
that may not be crossed) may go straight to the nearest passable cell centre
within the tolerance whose segment from the start touches no hard cell's
square (a corner included) nor passes within ``_GRAZE`` (1e-9 cells) of one:
a segment that misses a corner by a rounding error is refused (as the public
docs say); ties, equal distances in the grid's float64
continuous coordinates, go to the lowest ``(row, col)``. The callers word the
refusals: only they know why a cell is impassable.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.types import BoolArray, FloatArray, IntArray

__all__ = ["BAND_COST", "nearest_escape"]

# Cost per cell of length that an escape segment pays in cells impassable only
# through the inflation: the finite limit of the band's cost next to the
# inscribed zone, ``1 + cost_weight`` with the cost_weight (4) MapPlanner builds
# its costs with (navkit.mapping.traversal_costs).
BAND_COST = 5.0
# An escape segment passing within this many cells of a blocked cell's square
# counts as crossing it: a segment grazing a wall's corner is refused, never let
# through by a rounding error.
_GRAZE = 1e-9


def nearest_escape(
    costs: FloatArray,
    hard_map: BoolArray,
    start: tuple[int, int],
    q: tuple[float, float],
    tolerance: float,
    resolution: float,
) -> tuple[tuple[int, int], float] | None:
    """The escape cell from the impassable, not hard, cell ``start`` and its segment's cost.

    ``costs``: (rows, cols) cell costs, ``inf`` impassable; ``hard_map``: the
    cells no escape segment may touch; ``q``: the start point in continuous
    grid coordinates ``(row, col)`` (integers at cell centres), inside
    ``start``; ``tolerance`` in m, ``resolution`` m per cell. Returns the
    escape cell and the integral of the cost along the segment (cost units ×
    cells; an impassable cell counts :data:`BAND_COST`), or None when no cell
    qualifies.

    Candidates: the passable cells whose centre lies within ``tolerance`` of
    the start point, in the start's 4-connected component of cells that are
    not hard in a window around the disc: a segment crossing no hard square
    crosses a 4-connected chain of such cells, so the labelling only drops
    cells no segment could reach (a start in a sealed pocket is refused
    without testing every cell beyond its walls). They are tried nearest
    first.
    """
    total = tolerance / resolution
    # A disc this large holds the whole map.
    whole = math.hypot(*costs.shape) + 2.0
    # Growing discs: the first escape is usually within a few cells, and a
    # disc of radius ``reach`` holds every candidate nearer than one found
    # in it, and the cells of their segments.
    reach = 8.0
    while True:
        reach = total if reach >= min(total, whole) else reach
        found = _escape_within(costs, hard_map, start, q, reach, tolerance, resolution)
        if found is not None:
            return found
        if reach == total:
            return None
        reach *= 4.0


def _escape_within(
    costs: FloatArray,
    hard_map: BoolArray,
    start: tuple[int, int],
    q: tuple[float, float],
    reach: float,
    tolerance: float,
    resolution: float,
) -> tuple[tuple[int, int], float] | None:
    """The escape among the candidates within ``reach`` cells of ``q``, if any.

    Of ``hard_map`` a window around the disc is used.
    """
    rows, cols = costs.shape
    q_row, q_col = q
    r_lo = max(0, math.floor(q_row - reach) - 1)
    r_hi = min(rows, math.ceil(q_row + reach) + 2)
    c_lo = max(0, math.floor(q_col - reach) - 1)
    c_hi = min(cols, math.ceil(q_col + reach) + 2)
    window = (slice(r_lo, r_hi), slice(c_lo, c_hi))
    hard = hard_map[window]
    row0, col0 = start[0] - r_lo, start[1] - c_lo
    from scipy import ndimage  # only here: an escape is rare, the import is not free

    labels, _ = ndimage.label(~hard)
    rr, cc = np.nonzero(
        (labels == labels[row0, col0]) & np.isfinite(costs[window])
    )
    rr += r_lo
    cc += c_lo
    d2 = (rr - q_row) ** 2 + (cc - q_col) ** 2
    near = (np.sqrt(d2) * resolution <= tolerance) & (d2 <= reach * reach)
    rr, cc, d2 = rr[near], cc[near], d2[near]
    origin = np.array([q_row, q_col])
    theta = np.arctan2(cc - q_col, rr - q_row)
    # Candidates neither tried nor hidden behind a hard cell that blocked an
    # earlier one, in index order (ties go to the lowest (row, col)). Without the
    # shadows a start whose candidates are all hidden (deep in a bent, band-only
    # corridor, a large tolerance) tested every segment: minutes on a big map.
    alive = np.arange(rr.shape[0])
    while alive.size:
        near_d2 = d2[alive]
        first = int(np.argmin(near_d2))  # the first of the least: lowest index
        k = int(alive[first])
        cell = (int(rr[k]), int(cc[k]))
        direction = np.array([cell[0] - q_row, cell[1] - q_col])
        box_r, box_c, _, _ = _segment_cells(origin, direction, _GRAZE)
        # Beyond the map's edge only a segment along that edge touches them.
        inside = (box_r >= 0) & (box_r < rows) & (box_c >= 0) & (box_c < cols)
        box_r, box_c = box_r[inside], box_c[inside]
        blocked = hard[box_r - r_lo, box_c - c_lo]
        if not blocked.any():
            box_r, box_c, enter, leave = _segment_cells(origin, direction, 0.0)
            inside = (box_r >= 0) & (box_r < rows) & (box_c >= 0) & (box_c < cols)
            box_r, box_c = box_r[inside], box_c[inside]
            enter, leave = enter[inside], leave[inside]
            cell_costs = costs[box_r, box_c]
            cell_costs = np.where(np.isfinite(cell_costs), cell_costs, BAND_COST)
            cost = float(np.sum((leave - enter) * cell_costs)) * math.hypot(*direction)
            return cell, cost
        # The blocking cell nearest the start hides the widest wedge behind it.
        dist2 = np.where(blocked, (box_r - q_row) ** 2 + (box_c - q_col) ** 2, np.inf)
        blocker = int(np.argmin(dist2))
        drop = _shadow(q, (int(box_r[blocker]), int(box_c[blocker])), theta[alive], near_d2)
        drop[first] = True
        alive = alive[~drop]
    return None


def _shadow(
    q: tuple[float, float], blocker: tuple[int, int], theta: FloatArray, d2: FloatArray
) -> BoolArray:
    """Which candidates (directions ``theta``, squared distances ``d2`` from ``q``) are hidden.

    A sufficient test, not an exact one: a centre whose direction from ``q``
    lies strictly inside (by ``1e-9`` rad) the angle that the blocker's square
    subtends and that lies farther than the square's farthest corner is
    hidden, as its segment meets the square on the way. ``q`` touching the
    square (within the graze) hides everything.
    """
    q_row, q_col = q
    b_row, b_col = blocker
    reach = 0.5 + _GRAZE
    if abs(b_row - q_row) <= reach and abs(b_col - q_col) <= reach:
        return np.ones(theta.shape[0], dtype=bool)
    corner_r = b_row + np.array([-0.5, -0.5, 0.5, 0.5]) - q_row
    corner_c = b_col + np.array([-0.5, 0.5, -0.5, 0.5]) - q_col
    base = math.atan2(b_col - q_col, b_row - q_row)
    # Offsets from the direction of the square's centre, wrapped to [-pi, pi):
    # seen from outside, the square spans less than a half turn around it.
    spread = (np.arctan2(corner_c, corner_r) - base + math.pi) % (2 * math.pi) - math.pi
    offset = (theta - base + math.pi) % (2 * math.pi) - math.pi
    far = float(np.hypot(corner_r, corner_c).max())
    margin = 1e-9
    hidden: BoolArray = (
        (offset > spread.min() + margin)
        & (offset < spread.max() - margin)
        & (d2 > (far + margin) ** 2)
    )
    return hidden


def _segment_cells(
    start: FloatArray, direction: FloatArray, graze: float
) -> tuple[IntArray, IntArray, FloatArray, FloatArray]:
    """Cells whose closed square, grown by ``graze``, the segment ``start + t·direction`` meets.

    Continuous grid coordinates ``(row, col)``, cell ``(r, c)`` the square
    ``[r-½, r+½] × [c-½, c+½]``, ``t`` in ``[0, 1]``. Returns the rows and
    columns of those cells and the ``t`` at which the segment enters and
    leaves each (slab clipping, exact up to rounding; with ``graze = 0`` the
    intervals partition ``[0, 1]`` but for touching points of zero length).
    """
    end = start + direction
    lo = np.floor(np.minimum(start, end) + 0.5 - graze).astype(np.int64)
    hi = np.floor(np.maximum(start, end) + 0.5 + graze).astype(np.int64)
    rows = np.arange(lo[0], hi[0] + 1)
    cols = np.arange(lo[1], hi[1] + 1)
    enter = np.zeros((rows.size, cols.size))
    leave = np.ones((rows.size, cols.size))
    for axis, centres in ((0, rows), (1, cols)):
        low = centres - 0.5 - graze - start[axis]
        high = centres + 0.5 + graze - start[axis]
        d = direction[axis]
        if d == 0.0:
            inside = (low <= 0.0) & (high >= 0.0)
            t_in = np.where(inside, 0.0, np.inf)
            t_out = np.where(inside, 1.0, -np.inf)
        else:
            t_in = np.minimum(low / d, high / d)
            t_out = np.maximum(low / d, high / d)
        shape = (-1, 1) if axis == 0 else (1, -1)
        enter = np.maximum(enter, t_in.reshape(shape))
        leave = np.minimum(leave, t_out.reshape(shape))
    hit_r, hit_c = np.nonzero(enter <= leave)
    return rows[hit_r], cols[hit_c], enter[hit_r, hit_c], leave[hit_r, hit_c]
