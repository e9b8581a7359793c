"""Field D*'s interpolated edge cost against an exact minimisation (review 32, symbolic lens).

Ferguson & Stentz 2006: from node s, a path through cell c (cost c) reaches the
edge s1-s2 at distance y from s1, where the cost-to-goal is interpolated,
``g(y) = (1 - y) g1 + y g2``; it may first run a distance x along the edge s-s1
(between c and the cell b beside it, at cost min(b, c)). Its cost,

    F(x, y) = min(b, c) x + c sqrt((1 - x)² + y²) + g1 + y (g2 - g1),

is convex on the unit square, so its minimum is found by nested golden-section
searches (each inner minimum is a convex function of x): 40 steps pin the
minimiser to 1e-8 and the value to a few ulps (quadratically closer), in float64
(mpmath's 30 digits took 2 s for what this checks). With sympy (at authoring
time) the stationary points on the square's sides are ``y* = f / sqrt(c² - f²)``
(f = g1 - g2; value ``g1 + sqrt(c² - f²)``) and ``1 - x* = b / sqrt(c² - b²)``
(value ``g2 + b + sqrt(c² - b²)``): the options
``corner_cost`` takes the least of. It must equal the exact minimum to rounding,
including the corner cases (an impassable cell, an infinite neighbour value,
equal costs, a stationary point on the square's corner).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from navkit.planning.grid._dstar_lite_kernels import corner_cost

EPS = 2.0**-52
_GOLD = (math.sqrt(5.0) - 1.0) / 2.0


def _golden(f: Callable[[float], float], iterations: int = 40) -> float:
    """Minimum of a convex function on [0, 1] (the ends included)."""
    lo, hi = 0.0, 1.0
    x1, x2 = hi - _GOLD * (hi - lo), lo + _GOLD * (hi - lo)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - _GOLD * (hi - lo)
            f1 = f(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + _GOLD * (hi - lo)
            f2 = f(x2)
    return min(f1, f2, f(0.0), f(1.0))


def _exact(g1: float, g2: float, c: float, b: float) -> float:
    """min over the unit square of F (the module docstring), infinities as limits."""
    edge = min(b, c)
    if math.isinf(c):
        return edge + g1  # only along the edge s-s1, at cost b
    if math.isinf(g1) and math.isinf(g2):
        return math.inf
    if math.isinf(g2):  # only y = 0 is finite: along the side y = 0, linear in x
        return min(c, edge) + g1
    if math.isinf(g1):  # only y = 1: the convex side of x
        return _golden(lambda x: edge * x + c * math.hypot(1.0 - x, 1.0) + g2)

    def inner(x: float) -> float:
        return _golden(lambda y: edge * x + c * math.hypot(1.0 - x, y) + g1 + y * (g2 - g1))

    return _golden(inner)


def _check(g1: float, g2: float, c: float, b: float) -> None:
    got = corner_cost(g1, g2, c, b, True)
    want = _exact(g1, g2, c, b)
    if math.isinf(want):
        assert got == want
    else:
        assert abs(got - want) <= 16 * EPS * (abs(want) + c if math.isfinite(c) else 1.0), (
            g1,
            g2,
            c,
            b,
            got,
            want,
        )


def test_corner_cost_is_the_exact_minimum_over_the_cell() -> None:
    rng = np.random.default_rng(3214)
    for i in range(36):
        c = float(rng.uniform(1.0, 5.0))
        b = [float(rng.uniform(1.0, 5.0)), c * float(rng.uniform(0.3, 0.7)), math.inf][i % 3]
        g2 = float(rng.uniform(0.0, 10.0))
        g1 = g2 + c * float(rng.uniform(-1.5, 1.2))
        _check(max(g1, 0.0), g2, c, b)


def test_corner_cost_corner_cases_are_the_exact_minimum() -> None:
    root_half = math.sqrt(0.5)
    cases = [
        (3.0, 2.0, math.inf, 1.5),  # the crossed cell impassable: along the edge only
        (3.0, 2.0, 2.0, math.inf),  # the edge cell impassable: through c
        (math.inf, 2.0, 2.0, 1.2),  # g1 unknown: to s2, straight or along then cut
        (2.0, math.inf, 2.0, 1.2),  # g2 unknown: along the edge (or across c) to s1
        (math.inf, math.inf, 2.0, 1.2),
        (3.0, 3.0, 2.0, 2.0),  # f = 0, b = c
        (3.0 + 2.0 * root_half, 3.0, 2.0, 3.0),  # 2 f² = c²: y* at the corner y = 1
        (3.0, 1.0, 2.0, 2.0 * root_half),  # 2 b² = c²: x* at the corner x = 0
        (5.0, 1.0, 2.0, 1.0),  # f > c: the cell's far corner
        (1.0, 5.0, 2.0, 3.0),  # g2 far above g1
    ]
    for g1, g2, c, b in cases:
        _check(g1, g2, c, b)


def test_the_exact_minimum_tells_the_interpolated_cost_from_the_grid_moves() -> None:
    """The oracle is not loose: here the minimum (option D, along the edge then a cut to
    s2) is 0.046 below the best 8-connected move (A: along the whole edge), which
    corner_cost without interpolation returns."""
    g1, g2, c, b = 5.4, 2.0, 3.5, 1.0  # 2 f² > c² (no C), 2 b² < c² (D inside the side)
    option_d = g2 + b + math.sqrt(c * c - b * b)
    grid_moves = min(b + g1, c * math.sqrt(2.0) + g2)
    want = _exact(g1, g2, c, b)
    assert abs(want - option_d) < 1e-12 and grid_moves - want > 0.04
    assert abs(corner_cost(g1, g2, c, b, True) - want) < 1e-12
    assert corner_cost(g1, g2, c, b, False) == grid_moves
