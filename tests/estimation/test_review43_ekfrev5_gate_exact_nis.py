"""Review 47 (EKFREV5): past the 24-row limit the gate decides on the exact NIS.

With a dense R of more than 24 components (no exact route) and an ill-conditioned S
the kernel's NIS stood: 28.28 (26.11 by BLAS kernel) for an exact 25.81, rejected at
a gate between them (EKFREV3, review 42), and measurements the gate rejects were
refused where only a lower bound of the exact NIS was tried (16 of 240 draws of
25-30 components at gates 0.9-1.1 times the exact NIS). The exact NIS alone (S's
elimination) is now taken where its work, bounded from sizes before any
(``_exact_nis_work``), is within the exact posterior's cap; past it the gate
decides on the lower bound or the update is refused, the state unchanged.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels
from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation._ekf_kernels import _eliminated, _exact_nis_work, _exact_route

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_nis, random_problem
from precise_updates import linear, precise_problem

_FACTORS = (0.5, 0.9, 0.99, 1.0 - 1e-6, 1.0 + 1e-6, 1.01, 1.1, 2.0)


def _past_the_limit(seed: int, sizes: tuple[int, int]) -> tuple[np.ndarray, ...] | None:
    drawn = precise_problem(seed, sizes)
    if drawn is None or _exact_route(drawn[2].shape[1], drawn[3]) is not None:
        return None
    return drawn


@settings(max_examples=3, deadline=None)
@given(seed=st.integers(0, 10**6), factor=st.sampled_from(_FACTORS))
@example(seed=3, factor=1.0 - 1e-6)  # refused before, though the exact NIS rejects
@example(seed=24, factor=0.9)  # S singular as computed: refused before
@example(seed=7, factor=0.99)  # the update fails: refused before ("not positive definite")
def test_past_the_limit_the_gate_agrees_with_the_exact_nis(seed: int, factor: float) -> None:
    drawn = _past_the_limit(seed, (25, 30))
    assume(drawn is not None)
    assert drawn is not None
    x0, p, h, r, z = drawn
    exact = exact_nis(p, h, r, z - h @ x0)
    gate = float(exact * factor) if exact > 0 else 1.0
    ekf = ExtendedKalmanFilter(x0, p)
    try:
        result = ekf.update(z, linear(h), h, r, gate=gate)
    except FilterError:
        # Refused: only a measurement the gate passes (its update not vouched for),
        # the state unchanged.
        assert exact <= gate
        assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
        return
    if result.accepted:
        assert exact <= gate
    else:
        assert exact > gate, result.reason
        assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
        if "at least" in str(result.reason):
            assert result.nis <= exact
        else:
            assert result.nis > gate


def _gated_wrongly_draw() -> tuple[np.ndarray, ...]:
    # EKFREV3's draw (review 42's test file): 28 components of a dense R, S ill-conditioned.
    drawn = _past_the_limit(5, (25, 28))
    assert drawn is not None
    return drawn


def test_past_the_work_cap_the_gate_refuses_what_it_cannot_decide(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    x0, p, h, r, z = _gated_wrongly_draw()
    exact = exact_nis(p, h, r, z - h @ x0)
    # Its exact NIS within the real cap (0.27 s estimated)...
    assert _exact_nis_work(p, h, r, z - h @ x0) <= kernels._EXACT_POSTERIOR_WORK_MAX
    # ...and past a cap of one unit: decided from sizes, no clock read.
    monkeypatch.setattr(kernels, "_EXACT_POSTERIOR_WORK_MAX", 1.0)
    ekf = ExtendedKalmanFilter(x0, p)
    # A gate just below the exact NIS, far above its lower bound: the kernel's NIS
    # (above the exact one on every BLAS that gates here) cannot decide it.
    gate = float(exact) * (1 - 1e-9)
    with pytest.raises(FilterError, match="the gate cannot decide on a measurement of 28"):
        ekf.update(z, linear(h), h, r, gate=gate)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
    # A gate the lower bound exceeds (readings far apart) rejects without the exact NIS.
    far = z + 1e6 * np.sqrt(np.diag(h @ p @ h.T + r))
    result = ekf.update(far, linear(h), h, r, gate=100.0)
    assert not result.accepted and "NIS at least" in str(result.reason)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 5),
    m=st.integers(1, 9),
    log_p=st.floats(-280.0, 280.0),
    log_r=st.floats(-280.0, 280.0),
)
@example(seed=0, n=3, m=9, log_p=280.0, log_r=-280.0)
@example(seed=1, n=1, m=1, log_p=-300.0, log_r=-300.0)
def test_the_work_estimate_bounds_every_integer_of_the_elimination(
    seed: int, n: int, m: int, log_p: float, log_r: float
) -> None:
    # work = m³ b², b bounding the bits of every integer the elimination of [S | y]
    # holds (its minors): checked on the elimination itself.
    rng, p, h, r = random_problem(seed, n, m, log_p, log_r)
    y = rng.normal(size=m) * np.sqrt(np.diag(r) + np.diag(h @ p @ h.T)) * 10.0 ** rng.uniform(-3, 3)
    assume(np.isfinite(p).all() and np.isfinite(r).all() and np.isfinite(y).all())
    assume((np.linalg.eigvalsh(p) > 0).all() and (np.linalg.eigvalsh(r) > 0).all())
    with np.errstate(all="ignore"):
        assume(np.isfinite(h @ p @ h.T + r).all())
    work = _exact_nis_work(p, h, r, y)
    rows = _eliminated(p, h, r, y)[0]
    largest = max(abs(value).bit_length() for row in rows for value in row)
    assert largest <= math.sqrt(work / m**3)
