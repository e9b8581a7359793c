"""Random draws with the same bits on every x86-64 CPU (review 35).

A test that pins counts over thousands of random draws must draw the same
numbers on every machine. NumPy's array loops for ``power`` (``10.0 ** array``),
``exp``, ``log``, ``arctan2`` ... are vectorised for the CPU and differ in the
last bit with and without AVX-512; OpenBLAS's matrix products (``@``) and
LAPACK (``np.linalg``) differ by kernel (fused multiply-adds, the order of
sums). The draws here take the generator's raw outputs (``random``,
``integers``, ``choice``: integer arithmetic and ``(bits >> 11) * 2**-53``) and
combine them with operations IEEE 754 rounds once, the same on every CPU, SIMD
or not: ``+ - * /`` and ``sqrt``; ``floor`` and ``ldexp`` are exact. Sums are
added in the order written (one ufunc per operation: NumPy fuses none into a
multiply-add).
"""

from __future__ import annotations

import numpy as np

#: The float nearest log2(10) (a literal: Python parses decimals correctly rounded).
LOG2_10 = 3.321928094887362


def normals(rng: np.random.Generator, size: int | tuple[int, ...]) -> np.ndarray:
    """Nearly standard normal draws: 12 uniforms on [0, 1) added in order, less 6.

    Irwin and Hall's sum: mean 0, variance 1, within ±6 (``rng.normal``'s
    ziggurat calls the C library's ``exp`` and ``log1p`` in its tails).
    """
    shape = (size,) if isinstance(size, int) else size
    u = rng.random((12, *shape))
    total: np.ndarray = u[0]
    for k in range(1, 12):
        total = total + u[k]
    return total - 6.0


def log_uniform(
    rng: np.random.Generator, low: float, high: float, size: int | tuple[int, ...] | None = None
) -> np.ndarray | float:
    """About ``10.0 ** rng.uniform(low, high, size)``: magnitudes spread evenly in log.

    The exponent ``t = u log2(10)`` split into its floor ``e`` and fraction
    ``f``: ``(1 + f) 2**e``, exact (a mantissa linear between powers of two, the
    chord above ``2**f``: up to 6.15 % above ``10**u``, so from ``10**low`` to
    below ``1.0615 * 10**high``).
    """
    u = rng.random(size)
    t = (low + (high - low) * np.asarray(u)) * LOG2_10
    e = np.floor(t)
    value = np.ldexp(1.0 + (t - e), e.astype(np.int64))
    return float(value) if size is None else value


def matvec(a: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``a @ v`` for a matrix (m, n) and a vector (n,), the products added in order."""
    out: np.ndarray = a[:, 0] * v[0]
    for k in range(1, a.shape[1]):
        out = out + a[:, k] * v[k]
    return out


def gram(a: np.ndarray) -> np.ndarray:
    """``a @ a.T`` (n, n), the products added in order: symmetric exactly."""
    out: np.ndarray = a[:, None, 0] * a[None, :, 0]
    for k in range(1, a.shape[1]):
        out = out + a[:, None, k] * a[None, :, k]
    return out


def quadratic(v: np.ndarray, p: np.ndarray) -> float:
    """``v @ p @ v`` for a vector (n,) and a matrix (n, n), in order."""
    total = 0.0
    for i in range(len(v)):
        for j in range(len(v)):
            total += float(v[i]) * float(p[i, j]) * float(v[j])
    return total
