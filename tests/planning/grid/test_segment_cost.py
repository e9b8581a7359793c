"""Field D*'s exact segment integrator against a rational-arithmetic reference.

The reference shares no code with the numba kernel: it finds the grid lines a
segment crosses with :class:`fractions.Fraction` (no rounding at all) and prices
each piece by the cell holding its exact midpoint. Points are in node
coordinates (cell ``(r, c)`` covers ``[r, r+1] × [c, c+1]``).
"""

from __future__ import annotations

import math
from fractions import Fraction
from itertools import pairwise

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from hypothesis_twins import slow_twin
from navkit.planning import FieldDStar
from navkit.planning.grid._polyline_kernels import polyline_cost

FloatArray = NDArray[np.float64]
# Pieces at most this long are free in the kernel (a segment through a corner).
_TINY = 1e-12


def _crossings(a: Fraction, b: Fraction) -> list[Fraction]:
    """Parameters t in (0, 1) where a + t (b - a) is an integer."""
    if a == b:
        return []
    lo, hi = min(a, b), max(a, b)
    first = math.floor(lo) + 1
    return [(k - a) / (b - a) for k in range(first, math.ceil(hi)) if lo < k < hi]


def reference_cost(costs: FloatArray, p0: tuple[float, float], p1: tuple[float, float]) -> tuple[
    float, list[float]
]:
    """Exact-arithmetic segment cost and the lengths of its pieces."""
    r0, c0, r1, c1 = (Fraction(v) for v in (*p0, *p1))
    length = math.hypot(p1[0] - p0[0], p1[1] - p0[1])
    if length == 0.0:
        return 0.0, []
    rows, cols = costs.shape

    def cell(r: int, c: int) -> float:
        return float(costs[r, c]) if 0 <= r < rows and 0 <= c < cols else math.inf

    ts = sorted({Fraction(0), Fraction(1), *_crossings(r0, r1), *_crossings(c0, c1)})
    total = 0.0
    pieces = []
    for t0, t1 in pairwise(ts):
        piece = float(t1 - t0) * length
        pieces.append(piece)
        if piece <= _TINY:
            continue
        tm = (t0 + t1) / 2
        mr = r0 + tm * (r1 - r0)
        mc = c0 + tm * (c1 - c0)
        if r0 == r1 and r0.denominator == 1:
            value = min(cell(int(r0) - 1, math.floor(mc)), cell(int(r0), math.floor(mc)))
        elif c0 == c1 and c0.denominator == 1:
            value = min(cell(math.floor(mr), int(c0) - 1), cell(math.floor(mr), int(c0)))
        else:
            value = cell(math.floor(mr), math.floor(mc))
        if value == math.inf:
            return math.inf, pieces
        total += value * piece
    return total, pieces


def _kernel_cost(costs: FloatArray, p0: tuple[float, float], p1: tuple[float, float]) -> float:
    planner = FieldDStar(costs)
    pts = np.array([p0, p1], dtype=np.float64)
    cost, _ = polyline_cost(planner._pad, planner._width, pts, 2)
    return float(cost)


def _near_line(limit: int) -> st.SearchStrategy[float]:
    """A coordinate in [0, limit]: anywhere, or an integer nudged by a few ulps."""
    nudged = st.builds(
        lambda k, ulps: float(np.clip(k + ulps * math.ulp(max(k, 1)), 0.0, limit)),
        st.integers(0, limit),
        st.integers(-3, 3),
    )
    return st.one_of(st.floats(0.0, float(limit)), nudged, st.integers(0, limit).map(float))


@settings(max_examples=50, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    r0=_near_line(3),
    c0=_near_line(3),
    r1=_near_line(3),
    c1=_near_line(3),
)
def test_segment_cost_matches_exact_rational_reference(
    seed: int, r0: float, c0: float, r1: float, c1: float
) -> None:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((3, 3)) < 0.3, np.inf, rng.uniform(1.0, 9.0, (3, 3)))
    expected, pieces = reference_cost(costs, (r0, c0), (r1, c1))
    # Rounding of t may move a piece across the free-piece threshold: skip those.
    assume(all(not (_TINY / 8 < p < 8 * _TINY) for p in pieces))
    got = _kernel_cost(costs, (r0, c0), (r1, c1))
    if math.isinf(expected):
        assert got == math.inf
    else:
        assert got == pytest.approx(expected, rel=1e-9, abs=1e-12)


test_segment_cost_matches_exact_rational_reference_thoroughly = slow_twin(
    test_segment_cost_matches_exact_rational_reference, max_examples=400
)


def test_segment_one_ulp_beside_a_line_pays_its_own_cell() -> None:
    # The piece's cell came from its midpoint, which for a segment ending on a
    # grid line and starting one ulp before it rounds onto the line: its floor
    # is the impassable cell beyond.
    costs = np.array([[1.0, np.inf]])
    start = (0.3, math.nextafter(1.0, 0.0))
    assert _kernel_cost(costs, start, (0.0, 1.0)) == pytest.approx(math.hypot(0.3, 2**-53))
    assert _kernel_cost(costs, (0.0, 1.0), start) == pytest.approx(math.hypot(0.3, 2**-53))


@pytest.mark.parametrize("smooth", [True, False])
def test_world_plan_from_a_hair_before_an_impassable_cell_has_a_finite_cost(
    smooth: bool,
) -> None:
    # plan_world raised "ValueError: cost must be finite, got inf" (from Path2D):
    # the start lies in the passable cell, one ulp from the impassable one, and
    # the link to its nearest node was priced at the impassable cell.
    planner = FieldDStar(np.array([[1.0, np.inf]]), smooth=smooth)
    start = (math.nextafter(1.0, 0.0), 0.3)
    path = planner.plan_world(start, (0.2, 0.5))
    assert math.isfinite(path.cost)
    assert path.points[0].tolist() == list(start)
    assert path.points[-1].tolist() == [0.2, 0.5]
    assert path.cost == pytest.approx(path.length, rel=1e-12)  # every cell costs 1
