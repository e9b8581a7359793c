"""The world's edge index and chessboard distances against plain-Python references."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.sim._edge_grid_kernels import build_cell_lists, chebyshev_distance

PAD = 1e-6


def _span(lo: float, hi: float, n: int) -> range:
    """Indices of the cells from ``floor(lo - PAD)`` to ``floor(hi + PAD)``, clamped to [0, n)."""
    first = min(max(math.floor(lo - PAD), 0), n - 1)
    return range(first, min(max(math.floor(hi + PAD), 0), n - 1) + 1)


def reference_cells(
    segs: np.ndarray, circles: np.ndarray, gx0: float, gy0: float, h: float, nx: int, ny: int
) -> list[list[int]]:
    """Cell by cell, the items filed there, by a loop over primitives, rows and columns."""
    cells: list[list[int]] = [[] for _ in range(nx * ny)]
    inv_h = 1.0 / h
    for i, (x0, y0, x1, y1) in enumerate(segs.tolist()):
        u0, v0 = (x0 - gx0) * inv_h, (y0 - gy0) * inv_h
        u1, v1 = (x1 - gx0) * inv_h, (y1 - gy0) * inv_h
        dv = v1 - v0
        for r in _span(min(v0, v1), max(v0, v1), ny):
            ta, tb = 0.0, 1.0
            if dv != 0.0:
                ta, tb = sorted(((r - PAD - v0) / dv, (r + 1 + PAD - v0) / dv))
                ta, tb = max(ta, 0.0), min(tb, 1.0)
                if ta > tb:
                    continue
            ua, ub = u0 + ta * (u1 - u0), u0 + tb * (u1 - u0)
            for c in _span(min(ua, ub), max(ua, ub), nx):
                cells[r * nx + c].append(i)
    for j, (cx, cy, radius) in enumerate(circles.tolist()):
        # The cells of the circle's (padded) bounding box whose square its boundary may cross.
        for r in _span((cy - radius - gy0) * inv_h, (cy + radius - gy0) * inv_h, ny):
            for c in _span((cx - radius - gx0) * inv_h, (cx + radius - gx0) * inv_h, nx):
                xa, ya = gx0 + c * h, gy0 + r * h
                qx, qy = min(max(cx, xa), xa + h) - cx, min(max(cy, ya), ya + h) - cy
                fx = max(abs(xa - cx), abs(xa + h - cx))
                fy = max(abs(ya - cy), abs(ya + h - cy))
                near, far = math.sqrt(qx * qx + qy * qy), math.sqrt(fx * fx + fy * fy)
                if near <= radius + PAD * h and far >= radius - PAD * h:
                    cells[r * nx + c].append(segs.shape[0] + j)
    return cells


coord = st.floats(-3.0, 3.0, allow_nan=False).map(lambda v: round(v * 4) / 4 if v > 2 else v)


@settings(max_examples=25, deadline=None)
@given(
    segs=st.lists(st.tuples(coord, coord, coord, coord), max_size=12),
    circles=st.lists(st.tuples(coord, coord, st.floats(0.05, 2.0)), max_size=3),
    h=st.sampled_from([0.25, 0.5, 1.0 / 3.0, 1.0]),
    nx=st.integers(1, 14),
    ny=st.integers(1, 14),
)
def test_cell_lists_match_reference(
    segs: list[tuple[float, ...]], circles: list[tuple[float, ...]], h: float, nx: int, ny: int
) -> None:
    s = np.array(segs, dtype=float).reshape(-1, 4)
    c = np.array(circles, dtype=float).reshape(-1, 3)
    start, items = build_cell_lists(s, c, -2.0, -2.5, h, nx, ny, 10**6)
    expected = reference_cells(s, c, -2.0, -2.5, h, nx, ny)
    assert start.dtype == items.dtype == np.int64
    assert start.shape == (nx * ny + 1,) and start[0] == 0
    assert [items[start[k]:start[k + 1]].tolist() for k in range(nx * ny)] == expected
    total = sum(len(cell) for cell in expected)
    if total > 0:
        over_start, over_items = build_cell_lists(s, c, -2.0, -2.5, h, nx, ny, total - 1)
        assert over_items.shape == (0,) and over_start[-1] == total


test_cell_lists_match_reference_thoroughly = slow_twin(
    test_cell_lists_match_reference, max_examples=60
)


@settings(max_examples=40, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 12), st.integers(1, 12)),
    density=st.sampled_from([0.0, 0.05, 0.3]),
    seed=st.integers(0, 1000),
)
def test_chebyshev_distance_is_brute_force(
    shape: tuple[int, int], density: float, seed: int
) -> None:
    occ = (np.random.default_rng(seed).random(shape) < density).astype(np.uint8)
    d = chebyshev_distance(occ)
    assert d.dtype == np.int32 and d.shape == shape
    blocked = np.argwhere(occ != 0)
    rows, cols = np.indices(shape)
    if blocked.shape[0] == 0:
        assert (d == shape[0] + shape[1]).all()
        return
    cheb = np.maximum(
        np.abs(rows[..., None] - blocked[:, 0]), np.abs(cols[..., None] - blocked[:, 1])
    )
    np.testing.assert_array_equal(d, cheb.min(axis=-1))
