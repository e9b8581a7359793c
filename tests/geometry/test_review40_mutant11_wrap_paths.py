"""Every way into ``wrap_angle`` gives the same bits: the exact reduction into (-π, π].

Review 40 (mutation testing, MUTANT11). ``wrap_angle`` has a float fast path
(``_shared.angles.wrap_float``), a path for 0-d input (a NumPy scalar, a 0-d
array) and one for arrays; only the first and the last were pinned at the seam.
The 0-d path's fold read as ``r >= math.pi`` passed every test, though it turns
``wrap_angle(np.float64(math.pi))`` into -π, outside (-π, π]. Oracle: exact rational
arithmetic on the float inputs (the docstring's reduction by multiples of the
float ``2 * math.pi`` into (-math.pi, math.pi], which is unique: that interval is
exactly one multiple long).
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction

import numpy as np
import pytest

from navkit.geometry import Pose2D, angle_diff, wrap_angle

PI_F = Fraction(math.pi)
TWO_PI_F = Fraction(2 * math.pi)


def _reduced(a: float) -> float:
    """``a - k * (2 * math.pi)`` in (-math.pi, math.pi], exactly (then it is a float)."""
    x = Fraction(a)
    k = math.ceil((x - PI_F) / TWO_PI_F)
    r = x - k * TWO_PI_F
    assert -PI_F < r <= PI_F
    assert Fraction(float(r)) == r  # the documented reduction is exact
    return float(r)


def _bits(value: float) -> str:
    return float(value).hex()


_SEAM = [
    math.pi,
    -math.pi,
    math.nextafter(math.pi, math.inf),
    math.nextafter(math.pi, 0.0),
    math.nextafter(-math.pi, -math.inf),
    math.nextafter(-math.pi, 0.0),
    2 * math.pi,
    -2 * math.pi,
    3 * math.pi,
    -3 * math.pi,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1e300,
    -1e300,
    sys.float_info.max,
    -sys.float_info.max,
    # Exactly math.pi plus whole multiples of the float 2π: fmod leaves math.pi.
    float(PI_F + 3 * TWO_PI_F),
    float(-PI_F - 5 * TWO_PI_F),
]


def _values() -> list[float]:
    rng = np.random.default_rng(40)
    extra = [float(v) for v in rng.uniform(-100.0, 100.0, 20)]
    extra += [float(v) for v in 10.0 ** rng.uniform(3.0, 300.0, 20) * rng.choice([-1.0, 1.0], 20)]
    return _SEAM + extra


@pytest.mark.parametrize("a", _values())
def test_each_path_is_the_exact_reduction(a: float) -> None:
    expected = _reduced(a)
    results = {
        "float": wrap_angle(a),
        "np.float64": wrap_angle(np.float64(a)),
        "0-d array": wrap_angle(np.array(a)),
        "1-d array": wrap_angle(np.array([a]))[0],
        "2-d array": wrap_angle(np.array([[a, 0.0]]))[0, 0],
        "list": wrap_angle([a])[0],
        "Pose2D": Pose2D(0.0, 0.0, a).theta,
    }
    if math.isfinite(a - 0.0):
        results["angle_diff float"] = angle_diff(a, 0.0)
        results["angle_diff 0-d"] = angle_diff(np.float64(a), np.float64(0.0))
        results["angle_diff array"] = angle_diff(np.array([a]), 0.0)[0]
    assert {name: float(value) for name, value in results.items()} == dict.fromkeys(
        results, expected
    )
    # The same bits on every path, the sign of a zero included (-2π reduces to -0.0).
    assert len({_bits(value) for value in results.values()}) == 1


def test_a_half_turn_stays_plus_pi_on_every_path() -> None:
    for value in (np.float64(math.pi), np.array(math.pi), np.float64(-math.pi), np.array(-math.pi)):
        result = wrap_angle(value)
        assert isinstance(result, float)
        assert result == math.pi
