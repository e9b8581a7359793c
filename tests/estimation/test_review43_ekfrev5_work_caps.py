"""Review 47 (EKFREV5): the EKF's precise-update fallbacks under the exact posterior's cap.

Before, unlimited: a dense R's information form refined R's inverse with b³ exact
terms in Python (140 s for 800 components, then refused anyway: no exact route),
and the exact information route converted all m² entries of R to Python integers
(10,000 beams of a diagonal R: 25 s). Each is now decided from sizes before any
work: the refinement past the cap raises ``FilterError`` (after the gate), and the
information route converts R's blocks only, its work capped as well.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels
from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from precise_updates import linear, precise_problem, spd


def _refinement_forbidden(*args: object) -> None:
    raise AssertionError("the refinement ran: the refusal was not decided from sizes")


def test_a_dense_r_too_large_to_refine_is_not_refined(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    rng = np.random.default_rng(0)
    n, m = 3, 400  # 400³ terms: about 19 s at the measured rate, past the 15 s cap
    p = spd(rng, n, 2.0, 1.0)
    r = spd(rng, m, 2.0, 0.0) * 1e-12
    h = rng.normal(size=(m, n))
    y = rng.normal(size=m) * 1e-6
    monkeypatch.setattr(kernels, "_refined_block_inverse", _refinement_forbidden)
    monkeypatch.setattr(kernels, "_refined_inverse", _refinement_forbidden)
    # Not made (None: not available), decided from sizes; finish_cancelled, which has
    # nothing else for such an update, refuses it naming the cost (below).
    assert kernels._information_update(p, h, r, y) is None


def test_past_the_refinement_cap_an_update_is_refused_after_its_gate(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    drawn = precise_problem(5, (25, 28))  # 28 components of a dense R, Joseph form cancels
    assert drawn is not None
    x0, p, h, r, z = drawn
    # A cap the 28-component block exceeds, decided from sizes (no clock read).
    monkeypatch.setattr(kernels, "_RESIDUAL_TERM_WORK", kernels._EXACT_POSTERIOR_WORK_MAX)
    monkeypatch.setattr(kernels, "_refined_block_inverse", _refinement_forbidden)
    ekf = ExtendedKalmanFilter(x0, p)
    with pytest.raises(FilterError, match="information form of a measurement of 28"):
        ekf.update(z, linear(h), h, r)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
    # A measurement the gate rejects is rejected, not refused.
    far = z + 1e6 * np.sqrt(np.diag(h @ p @ h.T + r))
    result = ekf.update(far, linear(h), h, r, gate=100.0)
    assert not result.accepted and result.status.name == "GATED"
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


def _scan(m: int, n: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(m + n)
    p = spd(rng, n, 1.0, 1.0)
    h = rng.normal(size=(m, n))
    r = np.diag(10.0 ** rng.uniform(-9.0, -7.0, m))
    return p, h, r, rng.normal(size=m) * 1e-4


def test_the_information_route_converts_r_s_blocks_only(monkeypatch: pytest.MonkeyPatch) -> None:
    m, n = 2000, 4
    p, h, r, y = _scan(m, n)
    blocks = kernels._r_blocks(r)
    whole = kernels._ExactUpdate(p, h, r, y, blocks)
    converted: list[int] = []
    dyadic = kernels._dyadic

    def counted(a: np.ndarray) -> tuple[list[list[int]], int]:
        converted.append(a.size)
        return dyadic(a)

    monkeypatch.setattr(kernels, "_dyadic", counted)
    again = kernels._ExactUpdate(p, h, r, y, blocks)
    # H, P and y: never R's m² entries (4e6 here; 1e8 integers for 10,000 beams).
    assert max(converted) <= m * n
    # The same exact update (the blocks' common power of two is the whole R's).
    assert again.nis() == whole.nis()
    assert np.array_equal(again.state(np.zeros(n)), whole.state(np.zeros(n)))  # type: ignore[arg-type]
    assert np.array_equal(again.posterior(p), whole.posterior(p))  # type: ignore[arg-type]


def test_the_information_route_is_refused_past_the_cap_from_its_sizes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    p, h, r, y = _scan(1000, 4)
    blocks = kernels._r_blocks(r)
    # The work is m (n + 2)² operations at the unit: at a unit making 1000 beams cost
    # twice the cap, refused before any exact arithmetic; at half of it, taken.
    unit = 2.0 * kernels._EXACT_POSTERIOR_WORK_MAX / (1000 * 6**2)
    monkeypatch.setattr(kernels, "_INFORMATION_OP_WORK", unit)
    monkeypatch.setattr(kernels, "_dyadic", _refinement_forbidden)
    with pytest.raises(FilterError, match="exact update of 4 states from 1000 components"):
        kernels._ExactUpdate(p, h, r, y, blocks)
    monkeypatch.undo()
    monkeypatch.setattr(kernels, "_INFORMATION_OP_WORK", unit / 4.0)
    assert kernels._ExactUpdate(p, h, r, y, blocks).nis() > 0.0


@settings(max_examples=50, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    rows=st.integers(1, 6),
    cols=st.integers(1, 6),
    low=st.integers(-1074, 1023),
    span=st.integers(0, 2000),
)
def test_the_bit_bounds_hold_for_every_float(
    seed: int, rows: int, cols: int, low: int, span: int
) -> None:
    rng = np.random.default_rng(seed)
    exponents = rng.integers(low, min(1023, low + span) + 1, size=(rows, cols))
    with np.errstate(all="ignore"):
        a = np.ldexp(rng.uniform(-1.0, 1.0, (rows, cols)), exponents)
    a[rng.random((rows, cols)) < 0.2] = 0.0
    ints, k = kernels._dyadic(a)
    assert k <= kernels._denominator_bits(a)
    assert max(abs(v).bit_length() for row in ints for v in row) <= kernels._integer_bits(a)


def test_h_p_s_products_of_many_states_are_counted_before_they_are_made(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # 24 components of 1200 states: H P's m n (n + m) exact products, about 20 s at the
    # measured rate, past the cap: refused from sizes, S's integers never made (before
    # review 43 they were, and only the exact posterior's work was capped, after them).
    rng = np.random.default_rng(1200)
    m, n = 24, 1200
    p = np.eye(n) + np.diag(rng.uniform(0.0, 1.0, n))
    r = spd(rng, m, 2.0, 0.0) * 1e-9
    h, y = rng.normal(size=(m, n)), rng.normal(size=m)
    monkeypatch.setattr(kernels, "_eliminated", _refinement_forbidden)
    with pytest.raises(FilterError, match=r"exact update of 1200 states from 24 components"):
        kernels._ExactUpdate(p, h, r, y, [])
    # The exact NIS's estimate counts them too: past the cap, the gate refuses instead.
    assert kernels._exact_nis_work(p, h, r, y) > kernels._EXACT_POSTERIOR_WORK_MAX
