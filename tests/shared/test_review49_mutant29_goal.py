"""Review 49 mutation review (MUTANT29): the exact goal test at the ends of the float range.

``at_goal`` decides ``dx² + dy² <= t²`` exactly; the review-48 oracle tests
draw tolerances from 1e-12 m to 1e6 m only, near the origin or at UTM
coordinates. Mutants that survived them:

* the scaling of lengths into [2**-200, 2**200] done once instead of until
  the tolerance is there (``while`` -> ``if``): a tolerance of 1e-320 m or
  1e300 m, one pass short, squared to zero or overflowed in the exact tail;
* the offset's short side taken as negligible from 2**-20 of the tolerance
  instead of 2**-60: an offset an ulp beyond the circle, with a short side
  near 2**-24 of the tolerance (where ``hypot`` leaves the answer to the exact
  tail), was "at the goal";
* an offset whose long side equals the tolerance decided by ``hypot`` (``a
  > t`` for ``a >= t``): (t, 1e-30 t) rounds to t and was "at the goal";
* the goal's resolution taken from its coarser coordinate (``max`` for
  ``min``): a goal at (4.6e6, 0.5) m was reached from 5e-10 m away with a
  tolerance of 1e-12 m (the ulp of 4.6e6 is 9.3e-10 m, of 0.5 1.1e-16 m);
* (review 49's ``goal_verdict``) the radius bound of ``hypot``'s verdict
  from the coarser coordinate: those offsets, far beyond the radius, were
  left undecided to Python by the run kernels instead of OUTSIDE;
* the goal's resolution found without scaling for goals up to 2**980 m
  instead of 2**200 m (Rump's product overflows beyond 2**971 m): one ulp off
  such a goal, with a tolerance below its ulp, was not at the goal.

Each is checked against rational arithmetic (``fractions.Fraction``) on the
floats themselves.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from navkit._shared.goal import INSIDE, OUTSIDE, at_goal, goal_verdict, resolution


def _exact(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """The goal test in rational arithmetic (the tolerance or the goal's resolution)."""
    dx, dy = gx - px, gy - py
    t = Fraction(max(tolerance, resolution(gx, gy)))
    return Fraction(dx) ** 2 + Fraction(dy) ** 2 <= t * t


def _around_circle(t: float, dx: float, dy: float) -> list[tuple[float, float]]:
    """(dx, dy) and the offsets one and two ulps of dx either side of it."""
    out = []
    for k in (-2, -1, 0, 1, 2):
        x = dx
        for _ in range(abs(k)):
            x = math.nextafter(x, math.inf if k > 0 else -math.inf)
        out.append((x, dy))
    return out


def test_offsets_on_the_circle_at_every_scale_of_tolerance() -> None:
    # Tolerances from 1e-320 m to 1e307 m: an offset computed onto the circle
    # and its neighbours a few ulps inside and out, goal at the origin (whose
    # resolution, 5e-324 m, is below every tolerance here).
    rng = np.random.default_rng(49029)
    checked = inside = 0
    for exponent in range(-1062, 1020, 7):
        t = math.ldexp(float(rng.uniform(1.0, 2.0)), exponent)
        angle = float(rng.uniform(0.0, math.pi / 2))
        for dx, dy in _around_circle(t, t * math.cos(angle), t * math.sin(angle)):
            want = _exact(-dx, -dy, 0.0, 0.0, t)
            assert at_goal(-dx, -dy, 0.0, 0.0, t) == want, (dx, dy, t)
            assert at_goal(0.0, 0.0, dx, dy, t) == want, (dx, dy, t)
            checked += 1
            inside += want
    # Both answers occur: the offsets straddle the circle.
    assert 0 < inside < checked


def test_a_short_side_is_not_negligible_where_hypot_cannot_decide() -> None:
    # Short sides b from 2**-40 to 2**-21 of the tolerance, the long side the
    # floats nearest sqrt(t² - b²): the offsets are within an ulp or two of the
    # circle, where the exact tail decides; about half are outside.
    checked = outside = 0
    for t in (1.0, 0.75, 3.0e-5, 7.0e8):
        for e in range(-40, -20):
            b = math.ldexp(1.3 * t, e)
            a0 = float(Fraction(t) - Fraction(b) ** 2 / (2 * Fraction(t)))
            for dx, dy in _around_circle(t, a0, b):
                want = _exact(0.0, 0.0, dx, dy, t)
                assert at_goal(0.0, 0.0, dx, dy, t) == want, (dx, dy, t)
                assert at_goal(0.0, 0.0, dy, dx, t) == want, (dy, dx, t)
                checked += 1
                outside += not want
    assert 0 < outside < checked


def test_the_resolution_of_the_largest_goals() -> None:
    # Goals between 2**960 m and the largest float: a tolerance below the goal's
    # ulp is lifted to it, so one ulp off is at the goal and two are not.
    for g in (2.0**960, 2.0**971, 1.5 * 2.0**972, 2.0**975, 1.25 * 2.0**979, 2.0**985):
        res = math.ulp(g)
        assert resolution(g, g) == res
        one = math.nextafter(g, math.inf)
        two = math.nextafter(one, math.inf)
        assert at_goal(one, g, g, g, 0.75 * res)
        assert at_goal(g, one, g, g, 0.75 * res)
        assert not at_goal(two, g, g, g, 0.75 * res)
        assert not at_goal(one, one, g, g, 0.75 * res)  # sqrt(2) ulps off


def test_the_resolution_is_the_finer_coordinates() -> None:
    # A goal with one coordinate coarse (4.6e6 m: ulp 9.3e-10 m) and one fine
    # (0.5 m): nearer poses exist, so the tolerance, 1e-12 m, is the radius.
    for gx, gy in ((4.6e6, 0.5), (0.5, -4.6e6), (-1e300, 3.0)):
        assert resolution(gx, gy) < 1e-12
        coarse = max(abs(gx), abs(gy))
        for px, py in (
            (math.nextafter(gx, 0.0), gy),  # one coarse ulp off
            (gx, math.nextafter(gy, 0.0)),
            (gx, gy - 0.5 * math.ulp(coarse) if abs(gy) < 1e3 else gy),
            (gx - 0.5 * math.ulp(coarse) if abs(gx) < 1e3 else gx, gy),
        ):
            want = _exact(px, py, gx, gy, 1e-12)
            assert want == (max(abs(px - gx), abs(py - gy)) <= 1e-12)
            assert at_goal(px, py, gx, gy, 1e-12) == want, (px, py, gx, gy)
            # Decided by hypot alone (review 49's verdict of the run kernels): the
            # radius bound is the finer coordinate's, so none is left to Python
            # (a mutant bounding by the coarser one left the far ones undecided).
            verdict = goal_verdict(px, py, gx, gy, 1e-12)
            assert verdict == (INSIDE if want else OUTSIDE), (px, py, gx, gy)


def test_a_long_side_equal_to_the_tolerance_with_any_short_side_is_beyond_it() -> None:
    # (t, b) with b > 0 is longer than t however small b is; hypot rounds it to t.
    for t in (5e-324, 1e-300, 1e-12, 0.05, 1.0, 3.0e8, 1e300):
        assert at_goal(0.0, 0.0, t, 0.0, t)
        assert at_goal(0.0, 0.0, 0.0, -t, t)
        for b in (5e-324, 1e-300, 1e-30 * t, math.ulp(t)):
            if b == 0.0 or b >= t:
                continue
            assert math.hypot(t, b) == t or b > 1e-20 * t
            assert not _exact(0.0, 0.0, t, b, t)
            assert not at_goal(0.0, 0.0, t, b, t), (t, b)
            assert not at_goal(0.0, 0.0, -b, t, t), (t, b)
