"""PlanarFusion's prediction covariance is F P Fᵀ + Q dt with the motion model's Jacobian.

Review 35 (mutation testing, MUTANT4). The prediction kernel builds F - I entry
by entry (``_fusion_kernels._planar_step``); scaling the entry ∂x/∂ω by four
(``-sn * s * 0.5 * dt`` made ``-sn * s / 0.5 * dt``) passed every test, which
checked the predicted mean, or covariances where the yaw rate's cross terms
did not matter. Oracle: the constant-acceleration unicycle written out here
(s = v dt + a dt²/2 along θ + ω dt/2), its Jacobian written out by hand and
checked against central finite differences of that model, and F P Fᵀ + Q dt
formed in NumPy from a dense, random P and Q (every cross term counts).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import PlanarFusion


def _motion(x: np.ndarray, dt: float) -> np.ndarray:
    px, py, th, v, w, a = x
    s = v * dt + 0.5 * a * dt * dt
    mid = th + 0.5 * w * dt
    return np.array([px + math.cos(mid) * s, py + math.sin(mid) * s, th + w * dt, v + a * dt, w, a])


def _jacobian(x: np.ndarray, dt: float) -> np.ndarray:
    _, _, th, v, w, a = x
    s = v * dt + 0.5 * a * dt * dt
    mid = th + 0.5 * w * dt
    c, sn = math.cos(mid), math.sin(mid)
    f = np.eye(6)
    f[0, 2:] = [-sn * s, c * dt, -sn * s * dt / 2, c * dt * dt / 2]
    f[1, 2:] = [c * s, sn * dt, c * s * dt / 2, sn * dt * dt / 2]
    f[2, 4] = dt
    f[3, 5] = dt
    return f


def _spd(rng: np.random.Generator, scale: float) -> np.ndarray:
    a = rng.standard_normal((6, 6))
    return scale * (a @ a.T + 0.5 * np.eye(6))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_jacobian_written_here_is_the_model_s(seed: int) -> None:
    # The oracle's own check: the hand-written F against central differences.
    rng = np.random.default_rng(seed)
    x = rng.uniform(-1.5, 1.5, 6)
    dt = 0.37
    h = 1e-6
    fd = np.empty((6, 6))
    for j in range(6):
        e = np.zeros(6)
        e[j] = h
        fd[:, j] = (_motion(x + e, dt) - _motion(x - e, dt)) / (2 * h)
    np.testing.assert_allclose(_jacobian(x, dt), fd, atol=1e-8)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_predicted_covariance_is_f_p_ft_plus_q_dt(seed: int) -> None:
    rng = np.random.default_rng(seed)
    x0 = rng.uniform(-1.5, 1.5, 6)
    p0 = _spd(rng, 0.3)
    q = _spd(rng, 0.05)
    dt = 0.37
    f = PlanarFusion(x0, p0, process_noise=q, t0=2.0)
    f.predict(2.0 + dt)
    jac = _jacobian(x0, dt)
    expected = jac @ p0 @ jac.T + q * dt
    np.testing.assert_allclose(f.P, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())
    expected_x = _motion(x0, dt)
    expected_x[2] = math.remainder(expected_x[2], 2 * math.pi)
    np.testing.assert_allclose(f.x, expected_x, rtol=1e-13, atol=1e-14)


def test_the_yaw_rate_s_cross_terms_reach_the_position() -> None:
    # Only ω uncertain (and the heading 1 rad): the position's covariance is that of
    # ∂(x, y)/∂ω = s dt / 2 (-sin, cos)(mid), nothing else (Q zero).
    x0 = np.array([0.0, 0.0, 1.0, 2.0, 0.4, 0.0])
    p0 = np.diag([1e-30, 1e-30, 1e-30, 1e-30, 0.25, 1e-30])
    dt = 0.5
    f = PlanarFusion(x0, p0, process_noise=np.zeros(6), t0=0.0)
    f.predict(dt)
    s = 2.0 * dt
    mid = 1.0 + 0.5 * 0.4 * dt
    gx = -math.sin(mid) * s * dt / 2
    gy = math.cos(mid) * s * dt / 2
    assert f.P[0, 0] == pytest.approx(0.25 * gx * gx, rel=1e-9)
    assert f.P[0, 1] == pytest.approx(0.25 * gx * gy, rel=1e-9)
    assert f.P[0, 4] == pytest.approx(0.25 * gx, rel=1e-9)
    assert f.P[1, 4] == pytest.approx(0.25 * gy, rel=1e-9)
    assert f.P[2, 4] == pytest.approx(0.25 * dt, rel=1e-9)


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4, 5])
def test_the_predicted_covariance_is_exactly_symmetric(seed: int) -> None:
    # F P Fᵀ + Q dt is symmetric in exact arithmetic, not in rounding: the kernel
    # averages each pair of mirrored entries (a mutant skipping the pairs next to the
    # diagonal, range(i + 2, 6), passed the suite).
    rng = np.random.default_rng(seed)
    x0, p0, q = rng.uniform(-1.5, 1.5, 6), _spd(rng, 0.3), _spd(rng, 0.05)
    f = PlanarFusion(x0, p0, process_noise=q, t0=0.0)
    for k in range(1, 4):
        f.predict(0.29 * k)
        p = f.P
        assert np.array_equal(p, p.T)
