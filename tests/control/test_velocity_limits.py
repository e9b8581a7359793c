"""limit_velocity_change: the acceleration/deceleration rule (hypothesis) and examples."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.control import limit_velocity_change
from velocity_change_rule import TOL, check_change, period, rate

vec = st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0))


@settings(max_examples=50)
@given(vec, vec, rate, rate, period)
def test_limit_velocity_change_respects_both_limits(
    prev: tuple[float, float], want: tuple[float, float], accel: float, decel: float, dt: float
) -> None:
    p, w = np.array(prev), np.array(want)
    new = limit_velocity_change(p, w, max_accel=accel, max_decel=decel, dt=dt)
    check_change(p, new, accel, decel, dt)
    # On the segment from prev to want, and as far as the limits allow.
    d = w - p
    if np.linalg.norm(d) > 0:
        t = float(np.dot(new - p, d) / np.dot(d, d))
        assert -TOL <= t <= 1 + TOL
        np.testing.assert_allclose(new, p + t * d, atol=1e-9)
    if np.linalg.norm(w - p) <= min(accel, decel) * dt:
        np.testing.assert_allclose(new, w, atol=1e-12)
    else:
        assert np.linalg.norm(new - p) >= min(accel, decel) * dt * (1 - 1e-9)
    assert np.linalg.norm(new) <= max(np.linalg.norm(p), np.linalg.norm(w)) + TOL


test_limit_velocity_change_respects_both_limits_thoroughly = slow_twin(
    test_limit_velocity_change_respects_both_limits, max_examples=300
)


def test_limit_velocity_change_examples() -> None:
    # Reversing at speed 1 with decel 2: braking to zero and beyond is a deceleration
    # until the speed would exceed 1 again.
    out = limit_velocity_change([1.0, 0.0], [-1.0, 0.0], max_accel=0.5, max_decel=2.0, dt=0.1)
    np.testing.assert_allclose(out, [0.8, 0.0])
    out = limit_velocity_change([0.1, 0.0], [-1.0, 0.0], max_accel=0.5, max_decel=2.0, dt=0.1)
    # Braking 0.1 -> -0.1 (t = 0.2 <= decel·dt) keeps |v| <= 0.1; further would speed up.
    np.testing.assert_allclose(out, [-0.1, 0.0], atol=1e-15)
    # Turning at constant speed: the change that keeps |v| is a deceleration (decel limit).
    out = limit_velocity_change([1.0, 0.0], [0.0, 1.0], max_accel=0.1, max_decel=1.0, dt=0.1)
    assert np.linalg.norm(out - [1.0, 0.0]) == pytest.approx(0.1)
    same = limit_velocity_change([0.5], [0.5], max_accel=1.0, max_decel=1.0, dt=0.1)
    np.testing.assert_allclose(same, [0.5])


def test_limit_velocity_change_checks_its_arguments() -> None:
    with pytest.raises(ValueError, match="desired"):
        limit_velocity_change([0.0, 0.0], [1.0], max_accel=1.0, max_decel=1.0, dt=0.1)
    with pytest.raises(ValueError, match="previous"):
        limit_velocity_change([math.nan, 0.0], [1.0, 0.0], max_accel=1.0, max_decel=1.0, dt=0.1)
    with pytest.raises(ValueError, match="max_decel"):
        limit_velocity_change([0.0, 0.0], [1.0, 0.0], max_accel=1.0, max_decel=0.0, dt=0.1)
    with pytest.raises(ValueError, match="dt"):
        limit_velocity_change([0.0, 0.0], [1.0, 0.0], max_accel=1.0, max_decel=1.0, dt=-0.1)
    prev = np.array([0.3, 0.4])
    out = limit_velocity_change(prev, prev, max_accel=1.0, max_decel=1.0, dt=0.1)
    out[0] = 9.0
    np.testing.assert_array_equal(prev, [0.3, 0.4])


def test_limits_are_keyword_only() -> None:
    # Five positionals were easy to swap: the limits and dt must be named.
    with pytest.raises(TypeError, match="positional"):
        limit_velocity_change([0.0], [1.0], 1.0, 2.0, 0.1)  # type: ignore[misc]
    with pytest.raises(TypeError, match="max_decel"):
        limit_velocity_change([0.0], [1.0], max_accel=1.0, dt=0.1)  # type: ignore[call-arg]
