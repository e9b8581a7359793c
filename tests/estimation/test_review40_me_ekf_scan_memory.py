"""A precise update of many beams in little memory (review 40).

The EKF's information-form finish (``_information_update``, taken when the
Joseph form cancels: a scan of precise beams against a wide prior) refined R's
inverse as one m x m matrix, its exact residual holding all m³ products at
once: 115 MB of temporaries for 100 beams, 7.2 GB for 400, and a 1000-beam
update ran the machine out of memory. R's inverse is now refined one diagonal
block at a time (a beam each for a diagonal R) and the exact residual is summed
a few rows at a time.
"""

from __future__ import annotations

import sys
import tracemalloc
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import information_update
from precise_updates import linear


def _scan(seed: int, m: int) -> tuple[np.ndarray, ...]:
    """A 3-state pose, a prior 1e12 times wider than ``m`` beams of distinct variances."""
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    p = (q * 10.0 ** np.linspace(0.0, 10.0, 3)) @ q.T
    p = 0.5 * (p + p.T)
    angles = np.linspace(-np.pi, np.pi, m, endpoint=False)
    h = np.column_stack([np.cos(angles), np.sin(angles), rng.normal(size=m)])
    variance = float(np.max(np.diag(p))) * 1e-12
    r = np.diag(variance * 10.0 ** rng.uniform(0.0, 2.0, m))
    x0 = rng.normal(size=3) * 10.0
    z = h @ x0 + np.sqrt(np.diag(r)) * rng.normal(size=m)
    return x0, p, h, r, z


def _reference(
    x0: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The exact posterior's mean and covariance, rounded once."""
    x, post = information_update(x0, p, h, r, y)
    return np.array([float(v) for v in x]), np.array([[float(v) for v in row] for row in post])


def test_a_precise_scan_of_a_hundred_beams_is_finished_in_little_memory() -> None:
    x0, p, h, r, z = _scan(0, 100)
    ExtendedKalmanFilter(x0, p).update(z, linear(h), h, r)  # compiled outside the count
    ekf = ExtendedKalmanFilter(x0, p)
    tracemalloc.start()
    try:
        result = ekf.update(z, linear(h), h, r)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert result.accepted
    # Before: 115 MB (the m³ products of R's refined inverse); R and H are 80 kB each.
    assert peak < 20e6, peak
    x_exact, p_exact = _reference(x0, p, h, r, z - h @ x0)
    unit = np.sqrt(np.diag(p_exact))
    assert np.max(np.abs(ekf.P - p_exact) / np.outer(unit, unit)) <= 2.0**-40
    assert np.max(np.abs(ekf.x - x_exact) / unit) <= 2.0**-20


@pytest.mark.parametrize("terms", [1, 7, 50, 1 << 21])
def test_the_exact_residual_is_the_same_in_any_number_of_rows_at_a_time(
    terms: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(terms)
    a = rng.normal(size=(9, 5)) * 10.0 ** rng.uniform(-3, 3, (9, 5))
    b = rng.normal(size=(5, 4))
    c = a @ b  # the residual is all cancellation: only exact sums get it right
    whole = kernels._exact_residual(a, b, c)
    monkeypatch.setattr(kernels, "_RESIDUAL_TERMS", terms)
    assert kernels._exact_residual(a, b, c).tobytes() == whole.tobytes()
    exact = [
        [float(sum(Fraction(a[i, k]) * Fraction(b[k, j]) for k in range(5)) - Fraction(c[i, j]))
         for j in range(4)]
        for i in range(9)
    ]  # fmt: skip
    assert whole.tolist() == exact


def test_r_s_inverse_by_blocks_is_the_whole_inverse_for_a_diagonal_r() -> None:
    r = np.diag(10.0 ** np.random.default_rng(3).uniform(-12.0, 3.0, 40))
    whole = kernels._refined_inverse(r)
    blocks = kernels._refined_block_inverse(r)
    assert whole is not None and blocks is not None
    # Held as its blocks since review 44 (EKFREV6); dense() lays them side by side.
    inv, bound, scaled, refined = blocks.dense()
    assert inv.tobytes() == whole[0].tobytes()
    for got, want in zip((scaled, refined, blocks.d), whole[3][:3], strict=True):
        assert got.tobytes() == want.tobytes()
    # κ is the largest block's (a beam's: below 4, D scaling each to [0.5, 2)).
    assert blocks.kappa <= whole[2] < 4.0
    assert np.all(bound <= whole[1])
