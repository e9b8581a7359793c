"""The NIS bounds hold an innovation below 1e-162 (review 44, EKFCHECK).

``_nis_interval``'s last term, ``ρᵀ S⁻¹ ρ <= ‖D ρ‖² / μ``, was summed in floats: the
squares of a ρ below about 1e-162 underflowed to 0, and with w = 0 (ρ = y) the bounds
were ``[0, 0]`` around a positive exact NIS (up to 1e-318 where μ is 1e-8). The bound
is now summed from the exact ρ.
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_nis


def _problem(seed: int) -> tuple[np.ndarray, ...]:
    """A dense R with eigenvalues 1, 1e-3, 1e-8, a small P, and R's least eigenvector."""
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    r = q @ np.diag([1.0, 1e-3, 1e-8]) @ q.T
    r = 0.5 * (r + r.T)
    return np.eye(2) * 1e-3, rng.normal(size=(3, 2)), r, q[:, 2]


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    log_y=st.floats(-175.0, -150.0),
    steps=st.sampled_from([0, 8]),
)
@example(seed=0, log_y=-163.0, steps=8)  # [0, 0] around 5e-324 before
@example(seed=0, log_y=-170.0, steps=0)
def test_the_bounds_hold_a_tiny_innovations_nis(seed: int, log_y: float, steps: int) -> None:
    p, h, r, direction = _problem(seed)
    y = direction * 10.0**log_y
    exact = exact_nis(p, h, r, y)
    assert exact > 0
    found = kernels._nis_interval(p, h, r, y, steps)
    assert found is not None
    low, high = found
    assert 0.0 <= low <= high
    assert Fraction(low) <= exact <= Fraction(high), (low, float(exact), high)
