"""numba kernel of the diff-astar localiser: Gauss-Newton scan-to-map matching (private).

It wraps angles with :func:`navkit._shared.se2.wrap_scalar`: numba's cache keys
the kernel on this file alone, so a change of that helper comes with a note here
(review 51: compiled once and inlined by LLVM, no longer copied by numba).

Examples
--------
>>> import numpy as np
>>> values = np.tile((20.0 - np.arange(40)) * 0.1, (40, 1))  # signed distance to x = 2.05 m
>>> out = np.zeros(3)
>>> match_scan(np.array([1.0, 1.0]), np.array([0.0, 0.5]), np.full(2, 1e-4), values,
...            0.0, 0.0, 1.0, 0.0, 0.1, 1.0, 0.9, 2.0, 0.0, 1e-2, 1e-2, 10, out)
>>> round(float(out[0]), 6)
1.05
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_no_refcount
from navkit._shared.se2 import wrap_scalar

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

__all__ = ["match_scan"]


@njit_no_refcount
def match_scan(
    px: np.ndarray,
    py: np.ndarray,
    variance: np.ndarray,
    values: np.ndarray,
    ox: float,
    oy: float,
    cos_o: float,
    sin_o: float,
    resolution: float,
    clip: float,
    x0: float,
    y0: float,
    th0: float,
    info_xy: float,
    info_th: float,
    iterations: int,
    out: np.ndarray,
) -> None:
    """Pose maximising the fit of scan points to a distance field, near a prior pose.

    Minimises ``sum_i d(T p_i)^2 / variance_i + (T - T0)' diag(info_xy, info_xy, info_th) (T - T0)``
    over the pose ``T = (x, y, th)`` by Gauss-Newton from the prior ``T0 =
    (x0, y0, th0)``; ``d`` is ``values`` (distances at cell centres of a grid
    with origin ``(ox, oy)``, rotation ``(cos_o, sin_o)`` and ``resolution``)
    interpolated bilinearly (signed: negative inside obstacles). Points where
    ``|d| >= clip`` or off the map are left out: the map covers
    ``-0.5 <= row < rows - 0.5`` and ``-0.5 <= col < cols - 0.5`` in cell
    coordinates (cell centres at whole numbers); in its outer half cell, between
    the edge cells' centres and the edge, the edge cells' bilinear patch is
    extended (linearly in each direction: exact for a distance linear there, e.g.
    to a straight wall), and a map one cell wide is constant across it.
    Writes ``(x, y, th)`` into ``out``.
    """
    rows = values.shape[0]
    cols = values.shape[1]
    x = x0
    y = y0
    th = th0
    inv_res = 1.0 / resolution
    for _ in range(iterations):
        c = math.cos(th)
        s = math.sin(th)
        h00 = info_xy
        h01 = 0.0
        h02 = 0.0
        h11 = info_xy
        h12 = 0.0
        h22 = info_th
        g0 = info_xy * (x - x0)
        g1 = info_xy * (y - y0)
        g2 = info_th * wrap_scalar(th - th0)
        for i in range(px.shape[0]):
            wx = x + c * px[i] - s * py[i]
            wy = y + s * px[i] + c * py[i]
            dx = wx - ox
            dy = wy - oy
            col = (cos_o * dx + sin_o * dy) * inv_res - 0.5
            row = (-sin_o * dx + cos_o * dy) * inv_res - 0.5
            # Off the map (also NaN, and huge coordinates before any int conversion).
            if not (-0.5 <= row < rows - 0.5 and -0.5 <= col < cols - 0.5):
                continue
            # The outer half cell (between the edge cells' centres and the edge) was
            # left out once: a wall drawn in the edge cells was invisible, a map one
            # cell wide matched nothing. The edge cells' patch extends over it.
            r0 = min2(max2(math.floor(row), 0), rows - 2) if rows > 1 else 0
            c0 = min2(max2(math.floor(col), 0), cols - 2) if cols > 1 else 0
            r1 = r0 + 1 if rows > 1 else 0
            c1 = c0 + 1 if cols > 1 else 0
            fr = row - r0
            fc = col - c0
            v00 = values[r0, c0]
            v01 = values[r0, c1]
            v10 = values[r1, c0]
            v11 = values[r1, c1]
            d = (1.0 - fr) * ((1.0 - fc) * v00 + fc * v01) + fr * ((1.0 - fc) * v10 + fc * v11)
            if abs(d) >= clip:
                continue
            d_dr = ((1.0 - fc) * (v10 - v00) + fc * (v11 - v01)) * inv_res
            d_dc = ((1.0 - fr) * (v01 - v00) + fr * (v11 - v10)) * inv_res
            jx = d_dc * cos_o - d_dr * sin_o
            jy = d_dc * sin_o + d_dr * cos_o
            jt = jx * (-s * px[i] - c * py[i]) + jy * (c * px[i] - s * py[i])
            w = 1.0 / variance[i]
            h00 += w * jx * jx
            h01 += w * jx * jy
            h02 += w * jx * jt
            h11 += w * jy * jy
            h12 += w * jy * jt
            h22 += w * jt * jt
            g0 += w * jx * d
            g1 += w * jy * d
            g2 += w * jt * d
        # Solve H step = -g (H symmetric positive definite) by Cramer's rule.
        a00 = h11 * h22 - h12 * h12
        a01 = h02 * h12 - h01 * h22
        a02 = h01 * h12 - h02 * h11
        det = h00 * a00 + h01 * a01 + h02 * a02
        if not det > 0.0:
            break
        a11 = h00 * h22 - h02 * h02
        a12 = h01 * h02 - h00 * h12
        a22 = h00 * h11 - h01 * h01
        sx = -(a00 * g0 + a01 * g1 + a02 * g2) / det
        sy = -(a01 * g0 + a11 * g1 + a12 * g2) / det
        st = -(a02 * g0 + a12 * g1 + a22 * g2) / det
        x += sx
        y += sy
        th = wrap_scalar(th + st)
        if abs(sx) + abs(sy) < 1e-5 and abs(st) < 1e-5:
            break
    out[0] = x
    out[1] = y
    out[2] = th
