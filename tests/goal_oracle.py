"""The goal test in rational arithmetic, and offsets on its boundary (reviews 48-49).

:func:`exact_at_goal` is what ``navkit._shared.goal.at_goal`` must answer: the
offset ``goal - robot`` (as floats) at most the tolerance long, or the goal's
resolution if larger, in ``fractions.Fraction`` arithmetic (no rounding).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from navkit._shared.goal import resolution

#: (px, py, gx, gy, tolerance)
Case = tuple[float, float, float, float, float]


def radius(gx: float, gy: float, tolerance: float) -> Fraction:
    """The radius the goal test compares with: the tolerance or the goal's resolution."""
    return Fraction(max(tolerance, resolution(gx, gy)))


def exact_at_goal(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """The controllers' test in rational arithmetic: within the tolerance, or the
    goal's float resolution if larger; a NaN offset is not at the goal."""
    dx, dy = gx - px, gy - py
    if math.isnan(dx) or math.isnan(dy):
        return False
    t = radius(gx, gy, tolerance)
    return Fraction(dx) ** 2 + Fraction(dy) ** 2 <= t * t


def boundary_cases(seed: int, n: int) -> list[Case]:
    """Offsets on (and a few ulps around) the tolerance's circle, tolerances from
    1e-12 m to 1e6 m, goals near the origin and in UTM coordinates (where the
    goal's resolution may exceed the tolerance), and the edge cases."""
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        t = float(10.0 ** rng.uniform(-12.0, 6.0))
        angle = float(rng.uniform(-math.pi, math.pi))
        dx, dy = t * math.cos(angle), t * math.sin(angle)
        kind = int(rng.integers(4))
        if kind == 1:
            dx += int(rng.integers(-3, 4)) * math.ulp(dx)
        elif kind == 2:
            dx, dy = t, float(rng.choice([0.0, 5e-324, 1e-300, 1e-30, 1e-17 * t]))
        elif kind == 3:
            dx = t * float(rng.uniform(-1.0, 1.0))
            dy = math.sqrt(max(t * t - dx * dx, 0.0))
        gx, gy = (float(v) for v in rng.uniform(-10.0, 10.0, 2))
        if rng.random() < 0.1:
            gx, gy, t = 4.6e6, -4.6e6, float(rng.choice([1e-12, t]))
        cases.append((gx - dx, gy - dy, gx, gy, t))
    cases += [
        (0.0, 0.0, 0.3, 0.4, 0.5),  # hypot rounds 0.5000000000000000277 to 0.5
        (0.0, 0.0, 5e-324, 0.0, 5e-324),
        (0.0, 0.0, 1e-320, 1e-321, 1e-320),
        (1.0, 1.0, 1.0, 1.0, 1e-300),
        (0.0, 0.0, math.nan, 0.0, 1.0),
        (0.0, 0.0, 1e300, 1e300, 1e6),
    ]
    return cases
