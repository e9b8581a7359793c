"""Random precise Kalman updates whose Joseph form cancels (the EKF's reviews 38 and 39).

Shared by the tests of the EKF's exact and information-form fallbacks: the
same draws by seed in every file that uses them.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

import numpy as np


def spd(rng: np.random.Generator, n: int, log_kappa: float, log_scale: float) -> np.ndarray:
    """A symmetric positive definite matrix of condition about 10**log_kappa, badly scaled."""
    q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    a = (q * 10.0 ** np.linspace(0.0, log_kappa, n)) @ q.T
    s = 10.0 ** rng.uniform(-log_scale, log_scale, n)
    a = a * s * s[:, None]
    return 0.5 * (a + a.T)


def precise_problem(seed: int, sizes: Iterable[int] = (9, 10)) -> tuple[np.ndarray, ...] | None:
    """A precise update (x0, P, H, R, z) of 2-4 states (review 38's draws for (9, 10)).

    P and R of conditions up to 1e15, R 1e-6 to 1e-16 of P's scale: the Joseph form
    cancels. ``sizes`` (two consecutive ints, or one) gives m's range. None where
    the draw's truth cannot be sampled (a matrix Cholesky refuses).
    """
    low, *rest = sizes
    high = rest[-1] if rest else low
    rng = np.random.default_rng(seed)
    n, m = int(rng.integers(2, 5)), int(rng.integers(low, high + 1))
    p = spd(rng, n, rng.uniform(0.0, 15.0), rng.uniform(0.0, 4.0))
    scale = float(np.max(np.diag(p)))
    r = spd(rng, m, rng.uniform(0.0, 15.0), 1.0) * scale * 10.0 ** rng.uniform(-16.0, -6.0)
    h = rng.normal(size=(m, n)) * (rng.random((m, n)) < 0.8)
    x0 = rng.normal(size=n) * 10.0 ** rng.uniform(0.0, 6.0)
    try:
        truth = x0 + np.linalg.cholesky(p) @ rng.normal(size=n)
        z = h @ truth + np.linalg.cholesky(r) @ rng.normal(size=m)
    except np.linalg.LinAlgError:
        return None
    return x0, p, h, r, z


def linear(h: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """The measurement function ``state -> h @ state``."""

    def measure(state: np.ndarray) -> np.ndarray:
        return np.asarray(h @ state)

    return measure
