"""Conditioning review: the SE(2) exponential near omega·dt -> 0 and across its series switch.

``integrate`` uses ``sinc`` with a Taylor series below |x| = 2**-10 (``_shared/se2.py``;
1e-4 before review 49).
Against an independent 50-digit evaluation (mpmath; skipped when absent) the
displacement is accurate to a few units of float64 rounding relative to its length for
heading changes from 1e-16 rad to 1 rad, and relative to the distance travelled up to
10 rad (near a whole turn the displacement vanishes, while the rounding of
``omega * dt`` itself still moves the end by about ε v dt), with no step at the switch
(measured worst 1.3e-15 over 2000 draws, at turns of several radians, where that
rounding dominates; 1e-16 to 1e-4 rad stay below 5e-16).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D, Twist2D, integrate

mp = pytest.importorskip("mpmath")

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def _exact(vx: float, vy: float, omega: float, dt: float) -> tuple[float, float]:
    with mp.workdps(50):
        vx_, vy_, dt_ = mp.mpf(vx), mp.mpf(vy), mp.mpf(dt)
        turn = mp.mpf(omega) * dt_
        if turn == 0:
            return float(vx_ * dt_), float(vy_ * dt_)
        a = mp.sin(turn) / turn
        b = (1 - mp.cos(turn)) / turn
        return float(dt_ * (a * vx_ - b * vy_)), float(dt_ * (b * vx_ + a * vy_))


def _relative_error(
    vx: float, vy: float, omega: float, dt: float, *, to_travel: bool = False
) -> float:
    """The end's error relative to the displacement's length (or to the distance travelled)."""
    end = integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(vx, vy, omega), dt)
    ex, ey = _exact(vx, vy, omega, dt)
    scale = math.hypot(vx, vy) * dt if to_travel else math.hypot(ex, ey)
    return math.hypot(end.x - ex, end.y - ey) / scale


@pytest.mark.parametrize(
    "turn",
    [1e-16, 1e-12, 1e-8, 9.999999e-5, 1e-4, 1.000001e-4, 2e-4, 9.765624e-4, 2.0**-10, 1e-2, 3.0],
)
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_the_series_switch_over_is_seamless(turn: float, sign: float) -> None:
    assert _relative_error(1.3, 0.7, sign * turn, 1.0) < 2e-15


@settings(max_examples=200, deadline=None)
@given(
    log_turn=st.floats(-16.0, 1.0),
    sign=st.sampled_from([1.0, -1.0]),
    angle=st.floats(-math.pi, math.pi),
    log_dt=st.floats(-6.0, 3.0),
)
def test_small_turns_keep_full_precision(
    log_turn: float, sign: float, angle: float, log_dt: float
) -> None:
    dt = 10.0**log_dt
    omega = sign * 10.0**log_turn / dt
    vx, vy = math.cos(angle), math.sin(angle)
    # Near a whole turn (2π: log_turn 0.798) the displacement vanishes while the
    # rounding of omega * dt itself (ε |turn| rad) still moves the end by about ε v dt:
    # from a radian on, the error is measured against the distance travelled (a
    # hypothesis draw at turn 6.264 rad, displacement 0.003 of the travel, was
    # 1.2e-14 of the displacement, 3.6e-17 of the travel).
    large = 10.0**log_turn >= 1.0
    assert _relative_error(vx, vy, omega, dt, to_travel=large) < 4e-15


def test_a_million_radian_heading_is_wrapped_as_documented() -> None:
    # wrap_angle reduces by the float 2π (2.4e-16 short of 2π) exactly: the result is
    # k * 2.4e-16 rad from the exact reduction, k the number of turns (159155 here).
    end = integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(0.0, 0.0, 1e6), 1.0)
    with mp.workdps(50):
        exact = mp.mpf(1e6) - 2 * mp.pi * mp.nint(mp.mpf(1e6) / (2 * mp.pi))
        turns = int(mp.nint(mp.mpf(1e6) / (2 * mp.pi)))
        shortfall = float(2 * mp.pi - mp.mpf(2 * math.pi))
    assert abs(end.theta - float(exact)) <= turns * shortfall * 1.01 + 1e-15
    assert np.isfinite(end.theta)
