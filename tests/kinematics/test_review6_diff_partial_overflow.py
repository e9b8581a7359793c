"""DiffDrive returns a result within the float range even when a partial one overflows.

``wr - wl`` (or ``dr - dl``, ``omega * track``, ``vx - half``) can exceed the
float range while the twist, the heading change or the wheel speeds do not: a
wide track divides, large wheels divide. Such inputs were refused as
overflowing. The references below are exact (rational arithmetic).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import wrap_angle
from navkit.kinematics import DiffDrive

_HUGE = st.tuples(st.floats(1.0, 17.0), st.integers(290, 307), st.booleans()).map(
    lambda t: (-t[0] if t[2] else t[0]) * 10.0 ** t[1]
)
_LENGTH = st.floats(1e-6, 1e6)


def _close(got: float, exact: Fraction, scale: Fraction) -> bool:
    """Within a few roundings of the terms (of magnitude ``scale``) that make ``exact``."""
    return abs(Fraction(got) - exact) <= scale * Fraction(1, 2**50)


def _fits(exact: Fraction) -> bool:
    return abs(exact) < Fraction(1.7e308)


@settings(max_examples=50, deadline=None)
@given(_HUGE, _HUGE, _LENGTH, _LENGTH, _LENGTH)
@example(-1e308, 1e308, 10.0, 1.0, 1.0)
@example(1e308, 1e308, 1e6, 1e6, 1e-6)
def test_forward_of_huge_speeds(
    left: float, right: float, track: float, rl: float, rr: float
) -> None:
    drive = DiffDrive(track=track, left_radius=rl, right_radius=rr)
    wl, wr = Fraction(left) * Fraction(rl), Fraction(right) * Fraction(rr)
    vx, omega = (wl + wr) / 2, (wr - wl) / Fraction(track)
    if not (_fits(vx) and _fits(omega)):
        return  # (the error path is covered by the contract tests)
    twist = drive.forward([left, right])
    size = abs(wl) + abs(wr)
    assert _close(twist.vx, vx, size) and _close(twist.omega, omega, size / Fraction(track))
    batch = drive.forward_batch([[left, right], [1.0, 2.0]])
    np.testing.assert_array_equal(batch[0], twist.as_array())
    np.testing.assert_array_equal(batch[1], drive.forward([1.0, 2.0]).as_array())


test_forward_of_huge_speeds_thoroughly = slow_twin(test_forward_of_huge_speeds, max_examples=300)


@settings(max_examples=50, deadline=None)
@given(_HUGE, _HUGE, _LENGTH, _LENGTH, _LENGTH)
@example(1e308, -1e308, 10.0, 100.0, 100.0)
@example(1.7e308, 1.7e308, 1e6, 1e6, 1e6)
def test_inverse_of_huge_twists(
    vx: float, omega: float, track: float, rl: float, rr: float
) -> None:
    drive = DiffDrive(track=track, left_radius=rl, right_radius=rr)
    half = Fraction(omega) * Fraction(track) / 2
    left, right = (Fraction(vx) - half) / Fraction(rl), (Fraction(vx) + half) / Fraction(rr)
    if not (_fits(left) and _fits(right)):
        return
    speeds = drive.inverse([vx, 0.0, omega])
    size = abs(Fraction(vx)) + abs(half)
    assert _close(float(speeds[0]), left, size / Fraction(rl))
    assert _close(float(speeds[1]), right, size / Fraction(rr))
    batch = drive.inverse_batch([[vx, 0.0, omega], [0.5, 0.0, 0.25]])
    np.testing.assert_array_equal(batch[0], speeds)
    np.testing.assert_array_equal(batch[1], drive.inverse([0.5, 0.0, 0.25]))


test_inverse_of_huge_twists_thoroughly = slow_twin(test_inverse_of_huge_twists, max_examples=300)


@pytest.mark.parametrize("method", ["arc", "midpoint", "first_order"])
def test_odometry_with_a_heading_change_within_the_float_range(method: str) -> None:
    drive = DiffDrive(track=10.0, wheel_radius=0.1)
    exact = (Fraction(1e308) - Fraction(-1e308)) / 10
    step = drive.odometry_step(-1e308, 1e308, method=method)  # type: ignore[arg-type]
    assert step.theta == wrap_angle(float(exact))
    assert math.isfinite(step.x) and math.isfinite(step.y)
    rows = drive.odometry_step_batch([-1e308, 1e-300], [1e308, 3e-300], method=method)  # type: ignore[arg-type]
    np.testing.assert_array_equal(rows[0], step.as_array())
    tiny = drive.odometry_step(1e-300, 3e-300, method=method)  # type: ignore[arg-type]
    np.testing.assert_array_equal(rows[1], tiny.as_array())


def test_results_beyond_the_float_range_are_still_refused() -> None:
    drive = DiffDrive(track=1e-6, wheel_radius=1.0)
    with pytest.raises(ValueError, match="wheel_speeds"):
        drive.forward([-1e308, 1e308])
    with pytest.raises(ValueError, match="d_left, d_right"):
        drive.odometry_step(-1e308, 1e308)
    with pytest.raises(ValueError, match="twist"):
        DiffDrive(track=1e6, wheel_radius=1e-6).inverse([0.0, 0.0, 1e308])
