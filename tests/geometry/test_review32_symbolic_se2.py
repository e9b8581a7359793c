"""SE(2) against its symbolic derivation (review 32, symbolic lens), evaluated in mpmath.

The closed forms below were derived with sympy at authoring time (sympy is not a
test dependency): the exponential of the constant body twist over ``dt``,
``T(x, y, θ) · expm(dt [[0, -ω, vx], [ω, 0, vy], [0, 0, 0]])``, simplifies to

    x' = x + (vx (sin(θ + ω dt) - sin θ) + vy (cos(θ + ω dt) - cos θ)) / ω
    y' = y + (vx (cos θ - cos(θ + ω dt)) + vy (sin(θ + ω dt) - sin θ)) / ω
    θ' = θ + ω dt

with the limit ``(x + dt (vx cos θ - vy sin θ), y + dt (vx sin θ + vy cos θ))`` at
ω = 0. They are evaluated here in mpmath with enough digits for the cancellation
of the differences as ω -> 0 (50 digits plus the ones the difference loses), so
they are the exact values at navkit's float inputs; navkit must agree to a few
ulps of the size of the terms.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D, angle_diff, integrate, wrap_angle

mp = pytest.importorskip("mpmath")

EPS = 2.0**-52


pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")


def _pose(rng: np.random.Generator, spread: float) -> Pose2D:
    x, y = rng.normal(0.0, spread, 2).tolist()
    return Pose2D(x, y, float(rng.uniform(-4.0, 4.0)))


def _wrapped(a: Any) -> Any:
    """``a`` reduced to (-π, π] exactly (by the true 2π)."""
    r = a - 2 * mp.pi * mp.floor((a + mp.pi) / (2 * mp.pi))
    return mp.pi if r == -mp.pi else r


def _exp_pose(
    x: float, y: float, th: float, vx: float, vy: float, w: float, dt: float
) -> tuple[Any, Any]:
    """The symbolic exponential's position at these float inputs, exactly."""
    turn = mp.mpf(w) * mp.mpf(dt)
    if w == 0.0:
        c, s = mp.cos(th), mp.sin(th)
        return mp.mpf(x) + dt * (vx * c - vy * s), mp.mpf(y) + dt * (vx * s + vy * c)
    # The differences lose about -log10|ω dt| digits: keep 50 beyond them.
    lost = max(0, -int(mp.floor(mp.log10(abs(turn))))) if turn != 0 else 0
    with mp.workdps(50 + lost):
        t0, t1 = mp.mpf(th), mp.mpf(th) + turn
        inv = 1 / mp.mpf(w)
        ex = mp.mpf(x) + (vx * (mp.sin(t1) - mp.sin(t0)) + vy * (mp.cos(t1) - mp.cos(t0))) * inv
        ey = mp.mpf(y) + (vx * (mp.cos(t0) - mp.cos(t1)) + vy * (mp.sin(t1) - mp.sin(t0))) * inv
        return +ex, +ey


def test_integrate_is_the_symbolic_exponential_to_a_few_ulps() -> None:
    rng = np.random.default_rng(3201)
    mp.mp.dps = 50
    # Yaw rates from ordinary down to the series branch of sinc (|ω dt| < 2**-10) and to 0.
    scales = [1.0, 1e-3, 1e-5, 1e-9, 1e-15, 1e-200, 0.0]
    for i in range(700):
        start = _pose(rng, 3.0)
        vx, vy = (float(v) for v in rng.normal(0.0, 2.0, 2))
        w = float(rng.normal(0.0, 3.0)) * scales[i % len(scales)]
        dt = float(rng.uniform(0.0, 2.0))
        got = integrate(start, Twist2D(vx, vy, w), dt)
        ex, ey = _exp_pose(start.x, start.y, start.theta, vx, vy, w, dt)
        size = abs(start.x) + abs(start.y) + (abs(vx) + abs(vy)) * dt
        assert abs(float(ex) - got.x) <= 4 * EPS * size, (i, start, vx, vy, w, dt)
        assert abs(float(ey) - got.y) <= 4 * EPS * size, (i, start, vx, vy, w, dt)
        turn = mp.mpf(w) * dt
        eth = _wrapped(mp.mpf(start.theta) + turn)
        # θ + ω dt is one rounded sum (and ω dt one rounded product), then reduced by
        # the float 2π (documented: 2.4e-16 rad a turn removed).
        bound = 2 * EPS * (abs(start.theta) + 2 * abs(float(turn))) + 2.5e-16
        assert abs(float(eth) - got.theta) <= bound, (i, start, w, dt)


def test_integrate_differs_from_a_first_order_step() -> None:
    """The oracle tells the exponential from the Euler step ``(vx dt, vy dt)`` rotated by θ
    (what a first-order implementation would return): a quarter turn at 1 m/s."""
    got = integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(1.0, 0.0, math.pi / 2), 1.0)
    ex, ey = _exp_pose(0.0, 0.0, 0.0, 1.0, 0.0, math.pi / 2, 1.0)
    assert abs(got.x - float(ex)) < 1e-15 and abs(got.y - float(ey)) < 1e-15
    # 2/π each way, where the Euler step gives (1, 0).
    assert abs(got.x - 2 / math.pi) < 1e-15 and abs(got.y - 2 / math.pi) < 1e-15


def test_relative_pose_compose_and_inverse_are_the_group_operations() -> None:
    """``b.relative_to(a) = a⁻¹ ∘ b``: Rᵀ(θa)(pb - pa), wrap(θb - θa); accurate to the
    rounding of the distance between the poses (documented), also for poses 1 µm apart."""
    rng = np.random.default_rng(3202)
    mp.mp.dps = 50
    for i in range(600):
        a = _pose(rng, 10.0)
        if i % 2:
            b = Pose2D(a.x + 1e-6 * rng.normal(), a.y + 1e-6 * rng.normal(), rng.uniform(-4, 4))
        else:
            b = _pose(rng, 10.0)
        c, s = mp.cos(a.theta), mp.sin(a.theta)
        dx, dy = mp.mpf(b.x) - a.x, mp.mpf(b.y) - a.y
        rel = b.relative_to(a)
        size = float(abs(dx) + abs(dy))
        assert abs(float(c * dx + s * dy) - rel.x) <= 3 * EPS * size
        assert abs(float(c * dy - s * dx) - rel.y) <= 3 * EPS * size
        dth = mp.mpf(b.theta) - a.theta
        assert abs(float(_wrapped(dth)) - rel.theta) <= EPS * abs(float(dth)) + 2.5e-16
        assert abs(float(_wrapped(dth)) - angle_diff(b.theta, a.theta)) <= (
            EPS * abs(float(dth)) + 2.5e-16
        )
        comp = a.compose(b)
        size = abs(a.x) + abs(a.y) + abs(b.x) + abs(b.y)
        assert abs(float(a.x + c * b.x - s * b.y) - comp.x) <= 3 * EPS * size
        assert abs(float(a.y + s * b.x + c * b.y) - comp.y) <= 3 * EPS * size
        inv = a.inverse()
        size = abs(a.x) + abs(a.y)
        assert abs(float(-(c * a.x + s * a.y)) - inv.x) <= 3 * EPS * size
        assert abs(float(s * a.x - c * a.y) - inv.y) <= 3 * EPS * size
        assert float(_wrapped(-mp.mpf(a.theta))) == inv.theta or abs(inv.theta) == math.pi


def test_wrapping_at_plus_minus_pi_is_the_documented_reduction() -> None:
    """(-π, π] half-open, and angles beyond it off the exact reduction by k·2.4e-16 rad at
    most (k turns removed by the float 2π), as wrap_angle documents (as angles: at the
    seam the exact value may be just above -π where navkit gives π)."""
    mp.mp.dps = 50
    float_two_pi_gap = float(2 * mp.pi - 2 * math.pi)  # 2.449e-16
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(math.pi) == math.pi
    for a in (
        math.nextafter(math.pi, 4.0),
        math.nextafter(-math.pi, -4.0),
        3 * math.pi,
        -3 * math.pi,
        7.0,
        -7.0,
        100.0,
        -100.0,
        1e6,
        2 * math.pi,
    ):
        got = wrap_angle(a)
        assert -math.pi < got <= math.pi
        turns = abs(round(float((mp.mpf(a) - got) / (2 * mp.pi))))
        # Circular distance: at the ±π seam the two reductions may land on either side
        # (-3π: exactly -π + 4e-16, by the float 2π +π).
        off = _wrapped(_wrapped(mp.mpf(a)) - got)
        assert float(abs(off)) <= turns * float_two_pi_gap * 1.0001, a
