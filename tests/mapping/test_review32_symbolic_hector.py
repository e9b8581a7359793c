"""Hector scan matching against its symbolic derivation (review 32, symbolic lens).

Kohlbrecher et al. 2011: ``M`` is the bilinear interpolant of the cell
probabilities ``p`` (cell centres at integer ``(row, col)``); with fractions
``b = row - r0`` and ``a = col - c0``, sympy gives (at authoring time)

    M        = (1 - b)((1 - a) p00 + a p01) + b((1 - a) p10 + a p11)
    ∂M/∂row  = (1 - a)(p10 - p00) + a(p11 - p01)
    ∂M/∂col  = (1 - b)(p01 - p00) + b(p11 - p10)

(Hector's ``interpMapValueWithDerivatives`` weights the differences by the
other fraction, as the kernels' docstring says; the last test shows navkit does
not). With the world point ``S(ξ) = (x, y) + R(θ) p`` and the map frame
``(col, row) = R(yaw₀)ᵀ (S - origin) / res - ½``, the chain rule gives
``J = ∇M ∂(row, col)/∂ξ`` and one Gauss–Newton iteration solves
``(Σ JᵀJ) Δξ = Σ Jᵀ (1 - M)``. All of it is evaluated here in mpmath at 50
digits, from the cell probabilities the kernel itself uses (``exp`` of the
float32 log-odds runs in float32 by design, documented within 2e-8; read at the
cell centres, where the interpolant is ``p00`` exactly), so only the double
arithmetic after it is compared, to rounding.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.mapping._scan_matcher_kernels import (
    STATUS_CONVERGED,
    STATUS_MAX_ITERATIONS,
    accumulate,
    interpolate_batch,
    match_level,
)

mp = pytest.importorskip("mpmath")

EPS = 2.0**-52


pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")


def _cell_probabilities(logodds: np.ndarray) -> np.ndarray:
    """The kernel's own p of every cell (a padded map's value at each centre)."""
    rows, cols = logodds.shape
    centres = np.array([(r, c) for r in range(rows) for c in range(cols)], dtype=np.float64)
    out = np.empty((centres.shape[0], 3))
    interpolate_batch(np.pad(logodds, ((0, 1), (0, 1))), centres, out)
    return out[:, 0].reshape(rows, cols)


def _bilinear(p: np.ndarray, row: Any, col: Any) -> tuple[Any, Any, Any]:
    """M, ∂M/∂row, ∂M/∂col of the module docstring, the map padded with unknown cells.

    Beyond the edge cells' centres the neighbours beyond the edge are unknown
    (p = 1/2): ``p`` padded with two rings of them, and the coordinates moved by
    the padding; past the first ring every neighbour is unknown (zeros there until
    review 50).
    """
    rows, cols = p.shape
    if row < -1 or row > rows or col < -1 or col > cols:
        return mp.mpf(0.5), mp.mpf(0), mp.mpf(0)
    p = np.pad(p, 2, constant_values=0.5)
    row, col = row + 2, col + 2
    r0, c0 = int(mp.floor(row)), int(mp.floor(col))
    b, a = row - r0, col - c0
    p00, p01 = mp.mpf(p[r0, c0]), mp.mpf(p[r0, c0 + 1])
    p10, p11 = mp.mpf(p[r0 + 1, c0]), mp.mpf(p[r0 + 1, c0 + 1])
    m = (1 - b) * ((1 - a) * p00 + a * p01) + b * ((1 - a) * p10 + a * p11)
    return m, (1 - a) * (p10 - p00) + a * (p11 - p01), (1 - b) * (p01 - p00) + b * (p11 - p10)


def _map(rng: np.random.Generator) -> np.ndarray:
    return rng.normal(0.0, 3.0, (9, 11)).astype(np.float32)


def test_interpolated_value_and_gradient_are_the_bilinear_interpolant_s() -> None:
    rng = np.random.default_rng(3211)
    mp.mp.dps = 50
    logodds = _map(rng)
    p = _cell_probabilities(logodds)
    coords = np.column_stack((rng.uniform(-3.0, 11.0, 600), rng.uniform(-3.0, 13.0, 600)))
    coords[:40] = np.round(coords[:40])  # on cell centres and lines
    out = np.empty((coords.shape[0], 3))
    interpolate_batch(logodds, coords, out)
    for (row, col), got in zip(coords.tolist(), out, strict=True):
        exact = _bilinear(p, mp.mpf(row), mp.mpf(col))
        for k in range(3):
            assert abs(exact[k] - got[k]) <= 8 * EPS, (row, col, k)
    # The float32 exp of the log-odds: within the documented 2e-8 of the exact sigmoid.
    sigmoid = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    assert np.abs(p - sigmoid).max() <= 2e-8


def _exact_sums(
    p: np.ndarray,
    frame: tuple[float, float, float, float],
    pts: np.ndarray,
    pose: tuple[float, float, float],
) -> tuple[Any, Any, Any, Any, Any]:
    """Σ JᵀJ, Σ Jᵀ(1 - M), Σ (1 - M)², and the sums of the terms' magnitudes."""
    ox, oy, oyaw, res = (mp.mpf(v) for v in frame)
    x, y, th = (mp.mpf(v) for v in pose)
    co, so, ct, st = mp.cos(oyaw), mp.sin(oyaw), mp.cos(th), mp.sin(th)
    hess, grad, abs_h, abs_g = mp.zeros(3, 3), mp.zeros(3, 1), mp.zeros(3, 3), mp.zeros(3, 1)
    cost = mp.mpf(0)
    for px, py in pts.tolist():
        rx, ry = ct * px - st * py, st * px + ct * py
        dx, dy = x + rx - ox, y + ry - oy
        col = (co * dx + so * dy) / res - mp.mpf(0.5)
        row = (-so * dx + co * dy) / res - mp.mpf(0.5)
        m, d_row, d_col = _bilinear(p, row, col)
        # ∂(col, row)/∂(x, y, θ), ∂S/∂θ = (-ry, rx).
        dcol = (co / res, so / res, (-co * ry + so * rx) / res)
        drow = (-so / res, co / res, (so * ry + co * rx) / res)
        jac = [d_row * drow[k] + d_col * dcol[k] for k in range(3)]
        for i in range(3):
            grad[i] += jac[i] * (1 - m)
            abs_g[i] += abs(jac[i] * (1 - m))
            for j in range(3):
                hess[i, j] += jac[i] * jac[j]
                abs_h[i, j] += abs(jac[i] * jac[j])
        cost += (1 - m) ** 2
    return hess, grad, cost, abs_h, abs_g


def test_gauss_newton_sums_are_the_chain_rule_s() -> None:
    rng = np.random.default_rng(3212)
    mp.mp.dps = 50
    logodds = _map(rng)
    p = _cell_probabilities(logodds)
    for _ in range(40):
        res = float(rng.uniform(0.05, 0.5))
        yaw = float(rng.uniform(-3.0, 3.0))
        ox, oy = (float(v) for v in rng.normal(0.0, 1.0, 2))
        # A pose over the middle of the map, points within a few cells of it.
        cx = ox + math.cos(yaw) * 5.5 * res - math.sin(yaw) * 4.5 * res
        cy = oy + math.sin(yaw) * 5.5 * res + math.cos(yaw) * 4.5 * res
        pose = (
            cx + float(rng.normal(0, res)),
            cy + float(rng.normal(0, res)),
            float(rng.uniform(-3, 3)),
        )
        pts = np.ascontiguousarray(rng.normal(0.0, 2.0 * res, (int(rng.integers(3, 40)), 2)))
        hess, grad = np.empty((3, 3)), np.empty(3)
        cost, _ = accumulate(logodds, ox, oy, yaw, res, pts, *pose, 0.0, hess, grad)
        e_h, e_g, e_cost, abs_h, abs_g = _exact_sums(p, (ox, oy, yaw, res), pts, pose)
        # Each term: the world point, map coordinates and J a few roundings each.
        cond = 64 * (1 + (abs(ox) + abs(oy) + abs(pose[0]) + abs(pose[1])) / res)
        for i in range(3):
            assert abs(e_g[i] - grad[i]) <= EPS * cond * abs_g[i] + 1e-300
            for j in range(3):
                assert abs(e_h[i, j] - hess[i, j]) <= EPS * cond * abs_h[i, j] + 1e-300
        assert abs(e_cost - cost) <= EPS * cond * pts.shape[0]


def test_one_gauss_newton_iteration_takes_the_step_h_inverse_g() -> None:
    """match_level's first step is Δξ = H⁻¹ g up to its documented ridge (1e-9 of H's
    largest diagonal entry): relative 1e-9 times H's condition number."""
    rng = np.random.default_rng(3213)
    mp.mp.dps = 50
    # A smooth bump of occupancy: a well-conditioned H in x, y and θ.
    rr, cc = np.mgrid[0:24, 0:24]
    logodds = (6.0 - 0.08 * ((rr - 11.3) ** 2 + 0.6 * (cc - 12.1) ** 2)).astype(np.float32)
    p = _cell_probabilities(logodds)
    frame = (0.0, 0.0, 0.0, 0.1)
    checked = 0
    for _ in range(30):
        pts = np.ascontiguousarray(rng.normal(0.0, 0.3, (12, 2)))
        start = np.array(
            [1.2 + rng.normal(0, 0.05), 1.15 + rng.normal(0, 0.05), rng.normal(0, 0.05)]
        )
        pose = start.copy()
        scratch = (np.empty((3, 3)), np.empty(3), np.empty(3), np.empty((0, 0)))
        _, status = match_level(
            logodds,
            *frame,
            pts,
            pose,
            1,
            10.0,
            10.0,
            0.0,
            0.0,
            np.zeros(3),
            0.0,
            0.0,
            0.0,
            *scratch,
        )
        assert status in (STATUS_CONVERGED, STATUS_MAX_ITERATIONS)
        e_h, e_g, _, _, _ = _exact_sums(p, frame, pts, tuple(start.tolist()))
        n = pts.shape[0]
        step = mp.inverse(e_h / n) * (e_g / n)
        cond = float(mp.norm(e_h, 1) * mp.norm(mp.inverse(e_h), 1))
        taken = [mp.mpf(float(pose[k])) - float(start[k]) for k in range(3)]
        if all(t == 0 for t in taken):
            continue  # no halving lowered the cost: nothing taken to compare
        # The step taken is Δξ halved 0-4 times (the line search).
        scale = 2.0 ** round(math.log2(float(taken[0] / step[0])))
        assert 1 / 16 <= scale <= 1
        for k in range(3):
            # The ridge shifts the solution by up to 1e-9 cond(H) relative (the H of a
            # small scan is ill-conditioned: cond 5e5 here, a step 5e-4 off).
            bound = (2e-9 + 64 * EPS) * cond * float(mp.norm(step)) * scale + 4 * EPS * (
                abs(start[k]) + 1
            )
            assert abs(taken[k] - scale * step[k]) <= bound, (k, cond)
        checked += 1
    assert checked >= 20


def test_the_gradient_is_not_hector_s_swapped_one() -> None:
    logodds = np.array([[0.0, 2.0], [-1.0, 3.0]], dtype=np.float32)
    p = _cell_probabilities(logodds)
    row, col = 0.2, 0.7  # b = 0.2, a = 0.7: the two weightings differ
    out = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    swapped_row = (1 - row) * (p[1, 0] - p[0, 0]) + row * (p[1, 1] - p[0, 1])
    swapped_col = (1 - col) * (p[0, 1] - p[0, 0]) + col * (p[1, 1] - p[1, 0])
    exact = _bilinear(p, mp.mpf(row), mp.mpf(col))
    assert abs(out[0, 1] - float(exact[1])) < 1e-15 and abs(out[0, 2] - float(exact[2])) < 1e-15
    assert abs(out[0, 1] - swapped_row) > 0.05 and abs(out[0, 2] - swapped_col) > 0.05
