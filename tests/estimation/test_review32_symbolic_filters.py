"""Filters against their symbolic derivation (review 32, symbolic lens), in mpmath.

PlanarFusion's motion model, from its docstring: over ``dt`` the robot travels
``s = v dt + a dt²/2`` along ``m = θ + ω dt/2``, then ``θ += ω dt``, ``v += a dt``.
Its Jacobian, derived with sympy at authoring time (``f.jacobian(state)``), is
``I`` plus, in rows x and y and columns θ, v, ω, a::

    x: -s sin m,   dt cos m,   -s sin m · dt/2,   dt²/2 cos m
    y:  s cos m,   dt sin m,    s cos m · dt/2,   dt²/2 sin m

and ``∂θ'/∂ω = ∂v'/∂a = dt``. The measurements select one or two states (yaw θ,
speed v, yaw rate ω, acceleration a, odometry (v, ω)): ``H`` has a single 1 per
row, and with dt = 0 the update must be the exact linear-Gaussian posterior
``x + P Hᵀ S⁻¹ y``, ``P - P Hᵀ S⁻¹ H P`` (``S = H P Hᵀ + R``) and the NIS
``yᵀ S⁻¹ y``, computed here in mpmath at 50 digits. The general
ExtendedKalmanFilter's Joseph update is checked the same way for random ``H``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion, UpdateResult

mp = pytest.importorskip("mpmath")

EPS = 2.0**-52


pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")


def _spd(rng: np.random.Generator, n: int, cond: float, scale: float) -> np.ndarray:
    q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    mat = (q * 10 ** rng.uniform(0.0, math.log10(cond), n)) @ q.T * scale
    out: np.ndarray = 0.5 * (mat + mat.T)
    return out


def _mp(a: np.ndarray) -> Any:
    return mp.matrix(np.atleast_2d(a).tolist())


def _jacobian(x: list[Any], dt: Any) -> Any:
    """The sympy-derived Jacobian of the motion model (see the module docstring)."""
    _, _, th, v, w, a = x
    s = v * dt + a * dt**2 / 2
    m = th + w * dt / 2
    c, sn = mp.cos(m), mp.sin(m)
    jac = mp.eye(6)
    jac[0, 2], jac[0, 3], jac[0, 4], jac[0, 5] = -s * sn, dt * c, -s * sn * dt / 2, dt**2 / 2 * c
    jac[1, 2], jac[1, 3], jac[1, 4], jac[1, 5] = s * c, dt * sn, s * c * dt / 2, dt**2 / 2 * sn
    jac[2, 4] = dt
    jac[3, 5] = dt
    return jac


def _motion(x: list[Any], dt: Any) -> list[Any]:
    px, py, th, v, w, a = x
    s = v * dt + a * dt**2 / 2
    m = th + w * dt / 2
    return [px + s * mp.cos(m), py + s * mp.sin(m), th + w * dt, v + a * dt, w, a]


def _wrapped(a: Any) -> Any:
    r = a - 2 * mp.pi * mp.floor((a + mp.pi) / (2 * mp.pi))
    return mp.pi if r == -mp.pi else r


def test_planar_fusion_prediction_is_the_symbolic_model_and_its_jacobian() -> None:
    rng = np.random.default_rng(3205)
    mp.mp.dps = 50
    for _ in range(60):
        x0 = rng.normal(0.0, 1.0, 6)
        x0[2] = rng.uniform(-3.0, 3.0)
        p0 = _spd(rng, 6, 10 ** rng.uniform(0, 4), 10 ** rng.uniform(-3, 1))
        q = np.diag(10 ** rng.uniform(-4, -1, 6))
        dt = float(rng.uniform(1e-3, 0.5))
        fusion = PlanarFusion(x0, p0, process_noise=q, t0=0.0)
        fusion.predict(dt)
        xs = [mp.mpf(float(u)) for u in x0]
        jac = _jacobian(xs, mp.mpf(dt))
        exact = jac * _mp(p0) * jac.T + _mp(q) * dt
        absj = mp.matrix([[abs(jac[i, j]) for j in range(6)] for i in range(6)])
        bound = absj * mp.matrix(np.abs(p0).tolist()) * absj.T + _mp(q) * dt
        for i in range(6):
            for j in range(6):
                assert abs(exact[i, j] - fusion.P[i, j]) <= 16 * EPS * bound[i, j], (i, j)
        moved = _motion(xs, mp.mpf(dt))
        moved[2] = _wrapped(moved[2])
        size = sum(abs(u) for u in xs) * (1 + dt) ** 2
        for i in range(6):
            assert abs(moved[i] - fusion.x[i]) <= 8 * EPS * size, i


# (method, the states it observes): every measurement PlanarFusion takes.
_UPDATES: list[tuple[str, list[int]]] = [
    ("yaw", [2]),
    ("speed", [3]),
    ("yaw_rate", [4]),
    ("acceleration", [5]),
    ("odometry", [3, 4]),
]


def _apply(fusion: PlanarFusion, kind: str, z: list[float], r: list[float]) -> UpdateResult:
    if kind == "odometry":
        return fusion.update_odometry(0.0, z[0], z[1], v_variance=r[0], omega_variance=r[1])
    method: Callable[..., UpdateResult] = getattr(fusion, "update_" + kind)
    return method(0.0, z[0], variance=r[0])


def test_planar_fusion_updates_are_the_exact_linear_gaussian_posterior() -> None:
    rng = np.random.default_rng(3206)
    mp.mp.dps = 50
    for trial in range(100):
        kind, rows = _UPDATES[trial % len(_UPDATES)]
        x0 = rng.normal(0.0, 1.0, 6)
        x0[2] = rng.uniform(-3.0, 3.0)
        p0 = _spd(rng, 6, 10 ** rng.uniform(0, 3), 10 ** rng.uniform(-3, 1))
        # Measurements from far more to far less precise than the estimate (both of the
        # kernel's branches for the observed rows of the gain).
        r = [float(v) for v in 10 ** rng.uniform(-6, 3, len(rows))]
        z = [float(v) for v in rng.normal(0.0, 2.0, len(rows))]
        fusion = PlanarFusion(x0, p0, t0=0.0)
        res = _apply(fusion, kind, z, r)
        assert res.accepted
        h = mp.zeros(len(rows), 6)
        for k, col in enumerate(rows):
            h[k, col] = 1
        pm, xm = _mp(p0), mp.matrix([mp.mpf(float(u)) for u in x0])
        y = mp.matrix([mp.mpf(z[k]) - xm[col] for k, col in enumerate(rows)])
        if kind == "yaw":
            y[0] = _wrapped(y[0])
        s = h * pm * h.T + mp.diag([mp.mpf(v) for v in r])
        s_inv = mp.inverse(s)
        gain = pm * h.T * s_inv
        post_x = xm + gain * y
        post_p = pm - gain * h * pm
        cond_s = float(mp.norm(s, 1) * mp.norm(s_inv, 1))
        for k in range(len(rows)):
            assert abs(y[k] - res.residual[k]) <= 2 * EPS * (abs(z[k]) + abs(x0[rows[k]]))
        nis = (y.T * s_inv * y)[0]
        assert abs(nis - res.nis) <= 16 * EPS * cond_s * nis
        cond_p = float(np.linalg.cond(p0))
        for i in range(6):
            for j in range(6):
                scale = mp.sqrt(pm[i, i] * pm[j, j])
                assert abs(post_p[i, j] - fusion.P[i, j]) <= 16 * EPS * cond_p * scale, (i, j)
            step = (
                mp.sqrt(pm[i, i])
                * max(abs(u) for u in y)
                / min(mp.sqrt(s[k, k]) for k in range(len(rows)))
            )
            exact_x = _wrapped(post_x[i]) if i == 2 else post_x[i]
            # The start position is kept apart from the motion (documented): its size counts.
            size = abs(xm[i]) + abs(x0[i]) + step
            assert abs(exact_x - fusion.x[i]) <= 16 * EPS * cond_s * size, (kind, i)


def test_ekf_joseph_update_is_the_exact_linear_gaussian_posterior() -> None:
    rng = np.random.default_rng(3207)
    mp.mp.dps = 50
    for _ in range(120):
        n = int(rng.integers(1, 7))
        m = int(rng.integers(1, n + 1))
        x0 = rng.normal(size=n)
        p0 = _spd(rng, n, 10 ** rng.uniform(0, 3), 10 ** rng.uniform(-3, 2))
        hm = rng.normal(size=(m, n))
        r = _spd(rng, m, 10 ** rng.uniform(0, 2), 10 ** rng.uniform(-4, 1))
        z = rng.normal(size=m)
        ekf = ExtendedKalmanFilter(x0, p0)
        res = ekf.update(z, functools.partial(np.matmul, hm), hm, r)
        pm, h, xm = _mp(p0), _mp(hm), mp.matrix([mp.mpf(float(u)) for u in x0])
        s = h * pm * h.T + _mp(r)
        s_inv = mp.inverse(s)
        cond_s = float(mp.norm(s, 1) * mp.norm(s_inv, 1))
        # The NIS of navkit's own residual (z - H x rounded: its cancellation is the
        # input's, not the update's).
        y = mp.matrix([mp.mpf(float(u)) for u in res.residual])
        nis = (y.T * s_inv * y)[0]
        assert abs(nis - res.nis) <= 16 * EPS * cond_s * nis
        y_exact = mp.matrix([mp.mpf(float(u)) for u in z]) - h * xm
        post_x = xm + pm * h.T * s_inv * y_exact
        post_p = pm - pm * h.T * s_inv * h * pm
        cond_p = float(np.linalg.cond(p0)) * cond_s
        nis_exact = abs((y_exact.T * s_inv * y_exact)[0])
        for i in range(n):
            for j in range(n):
                scale = mp.sqrt(pm[i, i] * pm[j, j])
                assert abs(post_p[i, j] - ekf.P[i, j]) <= 16 * EPS * cond_p * scale
            size = (
                abs(xm[i])
                + mp.sqrt(pm[i, i] * nis_exact)
                + sum(abs(hm[k]) @ np.abs(x0) for k in range(m))
                * mp.sqrt(pm[i, i] / min(s[k, k] for k in range(m)))
            )
            assert abs(post_x[i] - ekf.x[i]) <= 16 * EPS * cond_s * size
