"""OmniDrive returns a result within the float range even when a partial sum overflows.

``jacobian @ twist`` and ``forward_matrix @ wheel_speeds`` add terms that can each
exceed the float range (or whose running sum does) while their sum fits: the terms
cancel. Such inputs were refused as overflowing. The references are exact
(rational arithmetic) products of the documented matrices.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.kinematics import OmniDrive

_HUGE = st.tuples(st.floats(1.0, 17.9), st.integers(295, 307), st.booleans()).map(
    lambda t: (-t[0] if t[2] else t[0]) * 10.0 ** t[1]
)
_LENGTH = st.floats(1e-6, 1e6)
_LIMIT = Fraction(np.finfo(np.float64).max)


@st.composite
def _drives(draw: st.DrawFn) -> OmniDrive:
    n = draw(st.integers(3, 5))
    angles = draw(st.lists(st.floats(-3.14, 3.14), min_size=n, max_size=n))
    try:
        return OmniDrive(angles, wheel_radius=draw(_LENGTH), base_radius=draw(_LENGTH))
    except ValueError:  # a singular layout
        assume(False)
        raise


def _exact(matrix: np.ndarray, vector: np.ndarray) -> tuple[list[Fraction], list[Fraction]]:
    """Each row's exact product with ``vector`` and the sum of its terms' magnitudes."""
    terms = [[Fraction(float(m)) * Fraction(float(v)) for m, v in zip(row, vector, strict=True)]
             for row in matrix]
    return [sum(t, Fraction(0)) for t in terms], [sum(map(abs, t), Fraction(0)) for t in terms]


def _verdict(exact: list[Fraction]) -> bool | None:
    """True: every entry fits; False: one is beyond the float range; None: too close to tell."""
    peak = max(abs(e) for e in exact)
    if peak < _LIMIT * (1 - Fraction(1, 2**40)):
        return True
    if peak > _LIMIT * (1 + Fraction(1, 2**40)):
        return False
    return None


def _check(got: np.ndarray, exact: list[Fraction], size: list[Fraction]) -> None:
    for value, want, scale in zip(got, exact, size, strict=True):
        assert abs(Fraction(float(value)) - want) <= scale * Fraction(1, 2**49)


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(_drives(), st.tuples(_HUGE, _HUGE, _HUGE))
@example(OmniDrive.three_wheel(wheel_radius=0.5, base_radius=0.1), (-1e308, 0.0, 1.7e308))
def test_inverse_of_huge_twists(drive: OmniDrive, twist: tuple[float, float, float]) -> None:
    tw = np.array(twist)
    exact, size = _exact(drive.jacobian, tw)
    verdict = _verdict(exact)
    if verdict is False:
        with pytest.raises(ValueError, match="twist: the wheel speeds would overflow"):
            drive.inverse(tw)
    if not verdict:
        return
    speeds = drive.inverse(tw)
    _check(speeds, exact, size)
    batch = drive.inverse_batch(np.array([tw, [0.5, -0.25, 0.125]]))
    _check(batch[0], exact, size)
    _check(batch[1], *_exact(drive.jacobian, np.array([0.5, -0.25, 0.125])))


test_inverse_of_huge_twists_thoroughly = slow_twin(test_inverse_of_huge_twists, max_examples=300)


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(_drives(), st.lists(_HUGE, min_size=5, max_size=5))
@example(
    OmniDrive.three_wheel(wheel_radius=1.0, base_radius=1.0),
    [1.7e308, 1.7e308, -1.7e308, 0.0, 0.0],
)
def test_forward_of_huge_speeds(drive: OmniDrive, values: list[float]) -> None:
    w = np.array(values[: drive.n_wheels])
    exact, size = _exact(drive.forward_matrix, w)
    verdict = _verdict(exact)
    if verdict is False:
        with pytest.raises(ValueError, match="wheel_speeds: the twist would overflow"):
            drive.forward(w)
    if not verdict:
        return
    twist = drive.forward(w)
    _check(twist.as_array(), exact, size)
    small = np.linspace(-1.0, 2.0, drive.n_wheels)
    batch = drive.forward_batch([w, small])
    _check(batch[0], exact, size)
    _check(batch[1], *_exact(drive.forward_matrix, small))


test_forward_of_huge_speeds_thoroughly = slow_twin(test_forward_of_huge_speeds, max_examples=300)


def test_results_beyond_the_float_range_are_still_refused() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=1.0, base_radius=1.0)
    with pytest.raises(ValueError, match="twist: the wheel speeds would overflow"):
        drive.inverse([1.5e308, 0.0, -1.5e308])
    with pytest.raises(ValueError, match="twists: the wheel speeds would overflow"):
        drive.inverse_batch([[0.0, 0.0, 0.0], [1.5e308, 0.0, -1.5e308]])
    with pytest.raises(ValueError, match="wheel_speeds: the twist would overflow"):
        drive.forward([1.7e308, -1.7e308, 0.0])
    with pytest.raises(ValueError, match="wheel_speeds: the twists would overflow"):
        drive.forward_batch([[1.7e308, -1.7e308, 0.0]])
