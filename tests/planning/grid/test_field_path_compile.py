"""Field D*'s polyline kernels: one compiled kernel for both jobs, checked against a reference."""

from __future__ import annotations

import itertools
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.planning.grid._polyline_kernels import polyline_cost, shortcut

ROWS, COLS = 5, 6


def _pad(costs: np.ndarray) -> tuple[np.ndarray, int]:
    """The ``+inf``-bordered flat cost array of the kernels and its row width."""
    return np.pad(costs, 1, constant_values=np.inf).ravel(), costs.shape[1] + 2


def _reference_segment_cost(costs: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> float:
    """Exact segment cost from the sorted crossings of the grid lines (plain Python)."""
    rows, cols = costs.shape

    def cell(r: int, c: int) -> float:
        return float(costs[r, c]) if 0 <= r < rows and 0 <= c < cols else math.inf

    (r0, c0), (r1, c1) = (float(v) for v in p0), (float(v) for v in p1)
    dr, dc = r1 - r0, c1 - c0
    length = math.hypot(dr, dc)
    if length == 0.0:
        return 0.0
    ts = {0.0, 1.0}
    for start, delta in ((r0, dr), (c0, dc)):
        if delta != 0.0:
            for line in range(-2, max(rows, cols) + 3):
                t = (line - start) / delta
                if 0.0 < t < 1.0:
                    ts.add(t)
    bounds = sorted(ts)
    total = 0.0
    for a, b in itertools.pairwise(bounds):
        if (b - a) * length <= 1e-12:
            continue
        mr = r0 + 0.5 * (a + b) * dr
        mc = c0 + 0.5 * (a + b) * dc
        if dr == 0.0 and mr == round(mr):
            cost = min(cell(round(mr) - 1, math.floor(mc)), cell(round(mr), math.floor(mc)))
        elif dc == 0.0 and mc == round(mc):
            cost = min(cell(math.floor(mr), round(mc) - 1), cell(math.floor(mr), round(mc)))
        else:
            cost = cell(math.floor(mr), math.floor(mc))
        if cost == math.inf:
            return math.inf
        total += cost * (b - a) * length
    return total


_COSTS = st.lists(
    st.sampled_from([1.0, 1.5, 2.0, 4.0, 9.0]), min_size=ROWS * COLS, max_size=ROWS * COLS
).map(lambda v: np.array(v).reshape(ROWS, COLS))
# Quarter-node coordinates: segments along grid lines and through corners occur.
_POINTS = st.lists(
    st.tuples(st.integers(0, 4 * ROWS), st.integers(0, 4 * COLS)), min_size=2, max_size=7
).map(lambda v: np.array(v, dtype=np.float64) / 4.0)


@settings(max_examples=60, deadline=None)
@given(costs=_COSTS, pts=_POINTS)
def test_polyline_cost_matches_the_crossings_reference(costs: np.ndarray, pts: np.ndarray) -> None:
    pad, width = _pad(costs)
    cost, length = polyline_cost(pad, width, pts, pts.shape[0])
    expected = sum(
        _reference_segment_cost(costs, pts[a], pts[a + 1]) for a in range(pts.shape[0] - 1)
    )
    assert math.isclose(cost, expected, rel_tol=1e-9, abs_tol=1e-9)
    steps = np.diff(pts, axis=0)
    assert math.isclose(length, float(np.hypot(steps[:, 0], steps[:, 1]).sum()), rel_tol=1e-12)


@settings(max_examples=60, deadline=None)
@given(costs=_COSTS, pts=_POINTS)
def test_shortcut_keeps_the_ends_and_never_raises_the_cost(
    costs: np.ndarray, pts: np.ndarray
) -> None:
    pad, width = _pad(costs)
    before = pts.copy()
    smooth = shortcut(pad, width, pts, pts.shape[0], 3)
    np.testing.assert_array_equal(pts, before)  # input untouched
    np.testing.assert_array_equal(smooth[0], pts[0])
    np.testing.assert_array_equal(smooth[-1], pts[-1])
    # The kept points are input points, in order.
    index = [int(np.flatnonzero((pts == p).all(axis=1))[0]) for p in smooth]
    assert index == sorted(index)
    smooth_cost = polyline_cost(pad, width, smooth, smooth.shape[0])[0]
    assert smooth_cost <= polyline_cost(pad, width, pts, pts.shape[0])[0] * (1.0 + 1e-9)


def test_a_segment_along_a_grid_line_pays_the_cheaper_cell_and_a_wall_is_infinite() -> None:
    costs = np.array([[1.0, 3.0], [2.0, np.inf]])
    pad, width = _pad(costs)
    # Row line 1 from column 0 to 2: beside (0, 0)|(1, 0) then (0, 1)|(1, 1).
    along = np.array([[1.0, 0.0], [1.0, 2.0]])
    assert polyline_cost(pad, width, along, 2) == (1.0 + 3.0, 2.0)
    # Through the interior of the impassable cell (1, 1).
    through = np.array([[1.0, 1.0], [2.0, 2.0]])
    assert polyline_cost(pad, width, through, 2)[0] == math.inf


_BOTH_JOBS = """
import numpy as np
from navkit.planning.grid._polyline_kernels import polyline_cost, shortcut
pad = np.pad(np.ones((3, 3)), 1, constant_values=np.inf).ravel()
pts = np.array([[0.0, 0.0], [0.0, 3.0], [3.0, 3.0]])
polyline_cost(pad, 5, shortcut(pad, 5, pts, 3, 2), 3)
"""


def test_shortcut_and_polyline_cost_share_one_compiled_kernel() -> None:
    costs = np.ones((3, 3))
    costs[1, 1] = 5.0
    pad, width = _pad(costs)
    pts = np.array([[0.0, 0.0], [0.0, 3.0], [3.0, 3.0]])
    smooth = shortcut(pad, width, pts, 3, 2)
    # The diagonal crosses the costly centre cell: the corner route is kept.
    np.testing.assert_array_equal(smooth, pts)
    assert polyline_cost(pad, width, smooth, 3) == (6.0, 6.0)
    # The two public entry points are plain Python functions, not numba dispatchers.
    assert not hasattr(shortcut, "signatures") and not hasattr(polyline_cost, "signatures")
    if jit_disabled():  # plain functions: no signatures to count
        return
    # Both calls again in a fresh process: this one's kernel keeps the signatures of
    # every earlier test's direct calls (a read-only cost array passed to
    # polyline_cost, say), which ran before this test under another order or split
    # of the suite (xdist).
    compiled = compiled_signatures(_BOTH_JOBS, ["navkit.planning.grid._polyline_kernels"])
    assert len(compiled.get("_polyline_kernels._polyline", [])) == 1, compiled
