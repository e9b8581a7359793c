"""The soccer paper's Table 6 recomputed: minima of the linear, blended and paraboloid potentials.

The paper samples its attractive potentials on a 1200 × 1200 map for blending
widths ω of 1, 10, 50 and 100 (map units) and lists their minima. Here a map
unit is 1 cm: the map is 12 × 12 m at 0.01 m per cell, the goal at a cell
centre in its middle, and the field parameters are navkit's defaults
(``K_att = c = a = b = m = U_trans = 1``, ``rad_thr = 0.5 m``). For each width
the blended potential's global minimum (value and distance from the goal), its
strict local minima on the grid away from the goal (a cell below its 8
neighbours) and, from a fine radial profile, the ring of false minima and the
depth of its trap are measured; the linear (cone) and paraboloid limits do not depend on ω.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from navkit._shared.types import FloatArray
from navkit.planning import (
    AttractiveField,
    BlendedAttraction,
    ConicAttraction,
    ParaboloidAttraction,
)

__all__ = [
    "FULL_TABLE_CELLS",
    "RESOLUTION",
    "THRESHOLD_RADIUS",
    "WIDTHS_PX",
    "grid_axis",
    "radial_minima",
    "strict_local_minima",
    "table6_values",
]

#: The paper's blending widths, in map cells.
WIDTHS_PX = (1, 10, 50, 100)
#: Size of one map cell, m (so the paper's 1200 cells are 12 m).
RESOLUTION = 0.01
#: Smallest map side (cells) holding the whole ring of false minima of the
#: narrow widths (out to 0.55 m from the goal): from it on every figure equals
#: the 1200-cell map's (113 cells already do; a margin of a few cells).
FULL_TABLE_CELLS = 120
#: ``rad_thr`` (m): navkit's default.
THRESHOLD_RADIUS = 0.5
#: Radial profile: step (m) and reach (m) of the 1-D search for false minima.
_PROFILE_STEP = 1e-4
_PROFILE_REACH = 3.0


def grid_axis(cells: int) -> FloatArray:
    """Cell-centre coordinates (m) of a ``cells``-wide axis whose cell ``cells // 2`` is at 0."""
    out: FloatArray = (np.arange(cells, dtype=np.float64) - cells // 2) * RESOLUTION
    return out


def strict_local_minima(u: FloatArray) -> FloatArray:
    """``(row, col)`` of the interior cells strictly below all 8 neighbours, shape (K, 2)."""
    core = u[1:-1, 1:-1]
    mask = np.ones(core.shape, dtype=bool)
    h, w = u.shape
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            if dr or dc:
                mask &= core < u[1 + dr : h - 1 + dr, 1 + dc : w - 1 + dc]
    out: FloatArray = np.argwhere(mask).astype(np.float64) + 1.0
    return out


def radial_minima(field: AttractiveField) -> tuple[FloatArray, FloatArray]:
    """Distances (m) of the radial profile's local minima and maxima along +x from the goal.

    The profile is sampled every 0.1 mm out to 3 m; the goal is ``field.goal_xy``.
    """
    r: FloatArray = np.arange(0.0, _PROFILE_REACH, _PROFILE_STEP, dtype=np.float64)
    pts = field.goal_xy + np.column_stack((r, np.zeros_like(r)))
    u = field.potential(pts)
    inner = u[1:-1]
    lows = np.flatnonzero((inner < u[:-2]) & (inner <= u[2:])) + 1
    highs = np.flatnonzero((inner > u[:-2]) & (inner >= u[2:])) + 1
    if u[0] < u[1]:
        lows = np.concatenate(([0], lows))
    return r[lows], r[highs]


def _blended(width: float) -> BlendedAttraction:
    return BlendedAttraction(np.zeros(2), threshold_radius=THRESHOLD_RADIUS, width=width)


@functools.lru_cache(maxsize=4)
def table6_values(cells: int) -> dict[str, float]:
    """Every figure of the recomputed Table 6 on a ``cells × cells`` map (cached).

    Keys (``w`` the width in cells): ``linear_min`` and ``paraboloid_min``;
    ``w{w}_blended_min``, ``w{w}_argmin_distance`` (m, the grid's lowest
    cell from the goal), ``w{w}_min_radius`` (m, the radial profile's first
    minimum: 0 at the goal, else a circle of minima around it),
    ``w{w}_false_minima`` (strict grid minima farther than ``rad_thr / 2``
    from the goal), ``w{w}_ring_radius`` (m, the radial profile's minimum
    beyond ``rad_thr / 2``; NaN without one) and ``w{w}_trap_depth`` (the
    potential climb from that ring back over the crest inside it; NaN without
    a ring).
    """
    axis = grid_axis(cells)
    xx, yy = np.meshgrid(axis, axis)
    pts = np.column_stack((xx.ravel(), yy.ravel()))
    goal = np.zeros(2)
    out: dict[str, float] = {}
    linear = ConicAttraction(goal, threshold_radius=THRESHOLD_RADIUS)
    out["linear_min"] = float(linear.potential(pts).min())
    out["paraboloid_min"] = float(ParaboloidAttraction(goal).potential(pts).min())
    near = 0.5 * THRESHOLD_RADIUS
    for px in WIDTHS_PX:
        field = _blended(px * RESOLUTION)
        u = field.potential(pts).reshape(cells, cells)
        row, col = divmod(int(np.argmin(u)), cells)
        out[f"w{px}_blended_min"] = float(u[row, col])
        out[f"w{px}_argmin_distance"] = float(math.hypot(axis[col], axis[row]))
        cells_rc = strict_local_minima(u).astype(np.int64)
        dist = np.hypot(axis[cells_rc[:, 1]], axis[cells_rc[:, 0]])
        out[f"w{px}_false_minima"] = float(np.count_nonzero(dist > near))
        lows, highs = radial_minima(field)
        out[f"w{px}_min_radius"] = float(lows[0])
        ring = lows[lows > near]
        if ring.size:
            radius = float(ring[0])
            crest = highs[highs < radius]
            top = float(crest[-1]) if crest.size else 0.0
            pot = field.potential([[radius, 0.0], [top, 0.0]])
            out[f"w{px}_ring_radius"] = radius
            out[f"w{px}_trap_depth"] = float(pot[1] - pot[0])
        else:
            out[f"w{px}_ring_radius"] = math.nan
            out[f"w{px}_trap_depth"] = math.nan
    return out
