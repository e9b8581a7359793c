"""Review 48 (SIMGOAL): the simulator's "goal reached" is the controllers' goal test.

The controllers decide "within ``goal_tolerance``" exactly (``dx² + dy² <= t²``
in real arithmetic, review 47); the simulator's run kernel decided "reached" by
``math.hypot(dx, dy) <= goal_tolerance`` (libm's hypot, as ``np.hypot``), which
rounds offsets a hair beyond the tolerance onto it and ones a hair inside
beyond it. A robot standing on such an offset was "goal reached" for the run
while its controller was not done, or the reverse. Both now call one exact
test, ``navkit._shared.goal.at_goal`` (compiled for the kernels as
``at_goal_kernel``), checked here against rational arithmetic in Python and
compiled (whole runs: ``test_review48_simgoal_runs.py``).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numba
import numpy as np

from navkit._shared.goal import at_goal, at_goal_kernel, resolution


def _exact(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """The controllers' test in rational arithmetic: within the tolerance, or the
    goal's float resolution if larger."""
    dx, dy = gx - px, gy - py
    if math.isnan(dx) or math.isnan(dy):
        return False
    t = Fraction(max(tolerance, resolution(gx, gy)))
    return Fraction(dx) ** 2 + Fraction(dy) ** 2 <= t * t


def _boundary_cases(seed: int, n: int) -> list[tuple[float, float, float, float, float]]:
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


@numba.njit(cache=False)
def _kernel_at_goal(cases: np.ndarray, out: np.ndarray) -> None:
    for i in range(cases.shape[0]):
        out[i] = at_goal_kernel(cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3], cases[i, 4])


def test_the_goal_test_is_exact_in_python_and_compiled() -> None:
    cases = _boundary_cases(48, 3000)
    array = np.array(cases)
    compiled = np.zeros(len(cases), dtype=np.bool_)
    _kernel_at_goal(array, compiled)
    rounded = 0
    for case, kernel in zip(cases, compiled, strict=True):
        want = _exact(*case)
        assert at_goal(*case) == want, case
        assert bool(kernel) == want, case
        dx, dy = case[2] - case[0], case[3] - case[1]
        rounded += (float(np.hypot(dx, dy)) <= max(case[4], resolution(case[2], case[3]))) != want
    # The cases do reach the boundary: hypot's rounding decides many of them wrongly.
    assert rounded > 150


def test_the_inlined_resolution_is_math_ulp() -> None:
    # at_goal lifts a tolerance below the goal's resolution to it, computing it with
    # Rump's leading power of two (numba has no math.ulp): one ulp off the goal is at
    # it, two are not.
    for g in (1e-310, 1e-300, 0.3, 3.0, 4.6e6 + 0.5, 1e15 + 1.0, 1e300):
        res = math.ulp(g)
        assert resolution(g, -2.0 * g) == res
        one = math.nextafter(g, 0.0)
        two = math.nextafter(one, 0.0)
        assert (g - one, g - two) == (res, 2.0 * res)
        tolerance = 0.75 * res
        assert at_goal(one, g, g, g, tolerance)
        assert at_goal(g, one, g, g, tolerance)
        assert not at_goal(two, g, g, g, tolerance)
        assert not at_goal(one, one, g, g, tolerance)  # sqrt(2) resolutions off
    # Powers of two (the resolution steps there) and goals up to 1e308, upward.
    for g in (2.0**-1022, 0.5, 4.0, 2.0**52, 2.0**900, 1e300, 2.0**1023):
        res = math.ulp(g)
        one = math.nextafter(g, math.inf)
        two = math.nextafter(one, math.inf)
        assert (one - g, two - g) == (res, 2.0 * res)
        assert at_goal(one, g, g, g, 0.75 * res)
        assert not at_goal(two, g, g, g, 0.75 * res)
