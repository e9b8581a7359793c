"""Exact rational linear algebra for reference results (``fractions.Fraction``).

Tests of numerically delicate updates (the EKF's and the fusion filter's
covariance updates) compare with exact arithmetic on the float inputs, rounded
once at the end.
"""

from __future__ import annotations

from collections.abc import Iterator
from fractions import Fraction

import numpy as np

Matrix = list[list[Fraction]]
#: A pinned update (x0, P0, H, R, z) as nested lists of floats.
Case = tuple[list[float], list[list[float]], list[list[float]], list[list[float]], list[float]]


def inverse(matrix: Matrix) -> Matrix:
    """Exact inverse (Gauss-Jordan) of a small non-singular rational matrix."""
    n = len(matrix)
    rows = [row[:] + [Fraction(int(i == j)) for j in range(n)] for i, row in enumerate(matrix)]
    for col in range(n):
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        head = rows[col][col]
        rows[col] = [v / head for v in rows[col]]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                factor = rows[r][col]
                rows[r] = [a - factor * b for a, b in zip(rows[r], rows[col], strict=True)]
    return [row[n:] for row in rows]


def positive_definite(matrix: Matrix) -> bool:
    """Whether a symmetric rational matrix is positive definite: every pivot of its
    exact Gaussian elimination (no pivoting) is above zero."""
    rows = [row[:] for row in matrix]
    for i in range(len(rows)):
        if rows[i][i] <= 0:
            return False
        for j in range(i + 1, len(rows)):
            factor = rows[j][i] / rows[i][i]
            rows[j] = [x - factor * y for x, y in zip(rows[j], rows[i], strict=True)]
    return True


def fractions(a: np.ndarray) -> Matrix:
    """The exact values of a float array (a vector becomes one row)."""
    return [[Fraction(v) for v in row] for row in np.atleast_2d(a).tolist()]


def exact_innovation(p: np.ndarray, h: np.ndarray, r: np.ndarray) -> tuple[Matrix, Matrix]:
    """``(H P, S⁻¹)`` exactly, S = H P Hᵀ + R."""
    n, m = p.shape[0], h.shape[0]
    pf, hf, rf = fractions(p), fractions(h), fractions(r)
    hp = [[sum(hf[a][k] * pf[k][j] for k in range(n)) for j in range(n)] for a in range(m)]
    s = [
        [sum(hp[a][k] * hf[b][k] for k in range(n)) + rf[a][b] for b in range(m)] for a in range(m)
    ]
    return hp, inverse(s)


def exact_nis(p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray) -> Fraction:
    """``yᵀ S⁻¹ y`` exactly, S = H P Hᵀ + R: one solve (Gaussian elimination), no inverse.

    m times cheaper than :func:`exact_update`'s NIS for m components (28: 0.1 s, not 1 s).
    """
    n, m = p.shape[0], h.shape[0]
    pf, hf, rf = fractions(p), fractions(h), fractions(r)
    yf = [Fraction(v) for v in np.asarray(y).tolist()]
    hp = [[sum(hf[a][k] * pf[k][j] for k in range(n)) for j in range(n)] for a in range(m)]
    rows = [
        [sum(hp[a][k] * hf[b][k] for k in range(n)) + rf[a][b] for b in range(m)] + [yf[a]]
        for a in range(m)
    ]
    for col in range(m):  # S is positive definite: no pivot is zero, no rows exchanged
        head = rows[col]
        for below in rows[col + 1 :]:
            factor = below[col] / head[col]
            if factor:
                for j in range(col, m + 1):
                    below[j] -= factor * head[j]
    solution = [Fraction(0)] * m
    for k in range(m - 1, -1, -1):
        rest = sum((rows[k][j] * solution[j] for j in range(k + 1, m)), Fraction(0))
        solution[k] = (rows[k][m] - rest) / rows[k][k]
    return sum((yf[a] * solution[a] for a in range(m)), Fraction(0))


def exact_gain(p: np.ndarray, h: np.ndarray, r: np.ndarray) -> tuple[Matrix, Matrix, Matrix]:
    """``(H P, S⁻¹, K)`` exactly: S = H P Hᵀ + R and the Kalman gain K = P Hᵀ S⁻¹ (n x m)."""
    n, m = p.shape[0], h.shape[0]
    hp, s_inv = exact_innovation(p, h, r)
    gain = [[sum(hp[b][i] * s_inv[b][a] for b in range(m)) for a in range(m)] for i in range(n)]
    return hp, s_inv, gain


def exact_update(
    x: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray
) -> tuple[list[Fraction], Matrix, Fraction]:
    """A linear Kalman update exactly: ``(x⁺, P⁺, NIS)`` for the residual ``y`` (m,).

    x⁺ = x + K y, P⁺ = P - K H P and NIS = yᵀ S⁻¹ y, as Fractions.
    """
    n, m = p.shape[0], h.shape[0]
    hp, s_inv, gain = exact_gain(p, h, r)
    yf = [Fraction(v) for v in np.asarray(y).tolist()]
    nis = sum((yf[a] * s_inv[a][b] * yf[b] for a in range(m) for b in range(m)), Fraction(0))
    pf = fractions(p)
    post = [
        [pf[i][j] - sum(gain[i][a] * hp[a][j] for a in range(m)) for j in range(n)]
        for i in range(n)
    ]
    x_new = [Fraction(x[i]) + sum(gain[i][a] * yf[a] for a in range(m)) for i in range(n)]
    return x_new, post, nis


def information_update(
    x: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray
) -> tuple[list[Fraction], Matrix]:
    """A linear Kalman update with a diagonal ``r`` exactly, in information form: ``(x⁺, P⁺)``.

    P⁺ = (P⁻¹ + Hᵀ R⁻¹ H)⁻¹ and x⁺ = x + P⁺ Hᵀ R⁻¹ y, as Fractions: cheap for
    many beams (one n × n inverse), where :func:`exact_update` inverts S (m × m).
    """
    n = p.shape[0]
    info = inverse(fractions(p))
    g = [Fraction(0)] * n
    for row, variance, residual in zip(fractions(h), np.diag(r).tolist(), y.tolist(), strict=True):
        weight = 1 / Fraction(variance)
        for i in range(n):
            g[i] += row[i] * weight * Fraction(residual)
            for k in range(n):
                info[i][k] += row[i] * row[k] * weight
    post = inverse(info)
    return [Fraction(x[i]) + sum(post[i][k] * g[k] for k in range(n)) for i in range(n)], post


def random_problem(
    seed: int, n: int, m: int, log_p: float, log_r: float
) -> tuple[np.random.Generator, np.ndarray, np.ndarray, np.ndarray]:
    """A random measurement update: the generator (for more draws), P, H and R.

    P (n, n) and R (m, m) symmetric positive definite at scales ``10**log_p`` and
    ``10**log_r``; H (m, n) dense with about 30 % zeros.
    """
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    p = (a @ a.T + 0.1 * np.eye(n)) * 10.0**log_p
    p = 0.5 * (p + p.T)
    h = rng.normal(size=(m, n)) * (rng.random((m, n)) < 0.7)
    root = rng.normal(size=(m, m))
    r = (root @ root.T + m * np.eye(m)) * 10.0**log_r
    r = 0.5 * (r + r.T)
    return rng, p, h, r


def precise_planar_updates(
    seed: int, count: int
) -> Iterator[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """``count`` realistic updates of a 6-state planar filter: (x0, P0, H, R, z).

    Position (x, y), position and heading, or speed measured, R/P from 1e-14 to
    1e-2 for every other one (precise: some variance shrinks more than 4096-fold,
    the EKF's fallback path) and 1e6 times more for the rest (ordinary).
    """
    rng = np.random.default_rng(seed)
    n = 6
    for trial in range(count):
        scale = 10.0 ** rng.uniform(0.0, 6.0)
        x0 = rng.normal(size=n) * np.array([scale, scale, 1.0, 5.0, 0.5, 1.0])
        x0[2] = rng.uniform(-3.0, 3.0)
        sd = 10.0 ** rng.uniform(0.0, 4.0, n)
        a = rng.normal(size=(n, n)) * 0.3 + np.eye(n)
        p0 = (a @ a.T) * np.outer(sd, sd)
        p0 = 0.5 * (p0 + p0.T)
        rows = [[0, 1], [0, 1, 2], [3]][trial % 3]
        h = np.zeros((len(rows), n))
        h[np.arange(len(rows)), rows] = 1.0
        r = np.eye(len(rows)) * 10.0 ** rng.uniform(-6.0, -2.0)
        if trial % 2:
            r = r * 1e6  # ordinary: no variance shrinks 4096-fold
        z = h @ (x0 + np.linalg.cholesky(p0) @ rng.normal(size=n))
        yield x0, p0, h, r, z


def case_arrays(case: Case) -> tuple[np.ndarray, ...]:
    """A pinned update's ``(x0, P0, H, R, z)`` as float64 arrays."""
    return tuple(np.array(a, dtype=np.float64) for a in case)


def exact_case(case: Case) -> tuple[np.ndarray, np.ndarray]:
    """A pinned update's exact posterior ``(x⁺, P⁺)``, each entry rounded once."""
    x0, p0, h, r, z = case_arrays(case)
    x_exact, p_exact, _ = exact_update(x0, p0, h, r, z - h @ x0)
    return (
        np.array([float(v) for v in x_exact]),
        np.array([[float(v) for v in row] for row in p_exact]),
    )


def posterior_relative(got: np.ndarray, exact: np.ndarray) -> float:
    """Largest ``|got - exact|`` entry over ``sqrt(exact_ii exact_jj)``."""
    unit = np.sqrt(np.diag(exact))
    return float(np.max(np.abs(got - exact) / np.outer(unit, unit)))
