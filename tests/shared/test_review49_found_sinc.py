"""``navkit._shared.se2.sinc`` against mpmath on both sides of its series switch (review 49).

Before review 49 the series ``1 - x²/6 + x⁴/120`` (summed left to right: two
roundings) ran below ``|x| = 1e-4`` and ``sin(x) / x`` (two roundings, 1 ulp
off for about a third of arguments) at and above it: at exactly 1e-4 the result
was 1 ulp off the correctly rounded value. The series now runs, in Horner form
(one final rounding), below 2**-10, where its truncation x⁶/5040 is below 1e-5
ulp: correctly rounded there; above, ``sin(x) / x`` stays within 1 ulp.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit._shared.se2 import sinc

mp = pytest.importorskip("mpmath")

pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")

#: The switch (``navkit._shared.se2.SINC_SERIES_LIMIT``), written out: the test
#: states the contract, not whatever the module holds.
SINC_SERIES_LIMIT = 2.0**-10


def _rounded(x: float) -> float:
    """sin(x)/x correctly rounded to float64 (40 digits, then one rounding)."""
    with mp.workdps(40):
        v = mp.mpf(x)
        return float(mp.sin(v) / v)


def _ulps(got: float, want: float) -> float:
    return abs(got - want) / math.ulp(want)


def test_old_switch_point_is_correctly_rounded() -> None:
    # sin(1e-4) / 1e-4 was 1 ulp off; the series is exact to the rounding there.
    for x in (1e-4, -1e-4, math.nextafter(1e-4, 0.0), math.nextafter(1e-4, 1.0)):
        assert sinc(x) == _rounded(x), x


def test_series_side_correctly_rounded() -> None:
    rng = np.random.default_rng(49)
    # Log-uniform from 1e-9 up to the switch, both signs, and the last floats below it.
    xs = np.exp(rng.uniform(math.log(1e-9), math.log(SINC_SERIES_LIMIT), 1500))
    below = [SINC_SERIES_LIMIT]
    for _ in range(20):
        below.append(math.nextafter(below[-1], 0.0))
    points = [*xs.tolist(), *below[1:]]
    wrong = [x for x in points for s in (1.0, -1.0) if sinc(s * x) != _rounded(s * x)]
    assert wrong == []
    assert sinc(0.0) == 1.0


def test_direct_side_within_one_ulp() -> None:
    rng = np.random.default_rng(50)
    xs = np.exp(rng.uniform(math.log(SINC_SERIES_LIMIT), math.log(3.0), 1500)).tolist()
    xs += [SINC_SERIES_LIMIT, math.nextafter(SINC_SERIES_LIMIT, 1.0), 1.0, math.pi / 2]
    worst = max(_ulps(sinc(s * x), _rounded(s * x)) for x in xs for s in (1.0, -1.0))
    assert worst <= 1.0


def test_module_constant_is_the_contract() -> None:
    from navkit._shared import se2

    assert se2.SINC_SERIES_LIMIT == SINC_SERIES_LIMIT


def test_no_step_at_the_switch() -> None:
    # The two branches meet: neighbours across 2**-10 differ by what sinc's slope
    # (-x/3) makes of one float step, within one rounding.
    lo = math.nextafter(SINC_SERIES_LIMIT, 0.0)
    hi = SINC_SERIES_LIMIT
    assert abs(sinc(hi) - _rounded(hi)) <= math.ulp(1.0) / 2
    assert abs(sinc(lo) - _rounded(lo)) == 0.0
    assert sinc(lo) >= sinc(hi)
