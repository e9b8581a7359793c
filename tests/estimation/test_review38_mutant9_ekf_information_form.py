"""The EKF fallbacks' information form against exact rational arithmetic (mutation review).

``finish_cancelled`` and ``finish_singular_s`` choose among candidate states and
covariances by the error estimates of :func:`_information_update`: P⁺'s
``error`` (units of ε relative to ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``), ``step_error`` (a bound on
the state step's error, entry by entry) and ``error_of`` (the measured error of
another candidate). For measurements of at most eight components the exact
posterior then overrides most choices, so mutants of these estimates passed
every test through whole updates (review 38). Each promise is checked here
directly, on random badly scaled and ill-conditioned updates, against the exact
posterior ``P - (H P)ᵀ S⁻¹ (H P)`` and step ``P Hᵀ S⁻¹ y`` in
``fractions.Fraction``; and each estimate is checked to be reached within a few
orders of magnitude (not vacuous).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update, posterior_relative
from precise_updates import spd as _spd

_EPS = 2.0**-53


def _problems(seed: int, count: int):  # type: ignore[no-untyped-def]
    """Random updates (P, H, R, y) and their exact posterior and step, rounded once."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        n, m = int(rng.integers(2, 6)), int(rng.integers(1, 5))
        p = _spd(rng, n, rng.uniform(0.0, 14.0), rng.uniform(0.0, 6.0))
        scale = float(np.max(np.diag(p)))
        r = _spd(rng, m, rng.uniform(0.0, 14.0), 2.0) * scale * 10.0 ** rng.uniform(-16.0, 0.0)
        h = rng.normal(size=(m, n)) * (rng.random((m, n)) < 0.8)
        # residuals up to 1e6 deviations of R: the step's bound then carries g's error
        y = rng.normal(size=m) * np.sqrt(np.diag(r)) * 10.0 ** rng.uniform(0.0, 6.0)
        step, post, _ = exact_update(np.zeros(n), p, h, r, y)
        yield (
            p, h, r, y,
            np.array([[float(v) for v in row] for row in post]),
            np.array([float(v) for v in step]),
        )  # fmt: skip


def _found(p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray) -> kernels._Information:
    with np.errstate(all="ignore"):  # as the kernels' callers run it
        found = kernels._information_update(p, h, r, y)
    assert found is not None
    return found


@pytest.fixture(scope="module")
def cases() -> list[tuple[np.ndarray, ...]]:
    return list(_problems(38, 40))


def test_the_posterior_is_within_its_estimated_error(cases: list[tuple[np.ndarray, ...]]) -> None:
    worst = 0.0
    for p, h, r, y, post, _ in cases:
        found = _found(p, h, r, y)
        assert np.array_equal(found.posterior, found.posterior.T)  # exactly symmetric
        error = posterior_relative(found.posterior, post)
        assert error <= _EPS * found.error
        worst = max(worst, error / (_EPS * found.error))
    assert worst > 1e-2


def test_the_step_is_within_its_bound_entry_by_entry(cases: list[tuple[np.ndarray, ...]]) -> None:
    worst = 0.0
    for p, h, r, y, _, step in cases:
        found = _found(p, h, r, y)
        off = np.abs(found.step - step)
        assert (off <= found.step_error).all()
        bounded = found.step_error > 0.0  # 0 where the step is exactly 0 (a state H misses)
        worst = max(worst, float(np.max(off[bounded] / found.step_error[bounded], initial=0.0)))
    assert worst > 1e-2


def test_the_error_estimates_are_not_vacuous(cases: list[tuple[np.ndarray, ...]]) -> None:
    # The step's bound, entry by entry, within 1e4 of the rounding its size and P⁺'s
    # error account for (the worst cases above reach it within 1e2).
    for p, h, r, y, post, step in cases:
        found = _found(p, h, r, y)
        unit = np.sqrt(np.diag(post))
        assert (
            found.step_error <= 1e4 * (np.abs(step) + unit) * max(found.error, 1.0) * _EPS
        ).all()
        assert found.error * _EPS >= found.floor  # J's own error is part of P⁺'s


def test_error_of_measures_a_known_perturbation(cases: list[tuple[np.ndarray, ...]]) -> None:
    # A candidate off the exact posterior by 1e-6 of sqrt(P⁺ᵢᵢ P⁺ⱼⱼ) in one entry pair
    # (P⁺'s error far below that): error_of says 1e-6 / ε, within the estimate's floor.
    for p, h, r, y, post, _ in cases:
        found = _found(p, h, r, y)
        if _EPS * found.error > 1e-8:
            continue  # J too ill-conditioned to measure 1e-6 to a few percent
        n = post.shape[0]
        unit = np.sqrt(np.diag(post))
        bump = np.zeros((n, n))
        bump[0, n - 1] = bump[n - 1, 0] = 1e-6 * unit[0] * unit[n - 1]
        measured = _EPS * found.error_of(post + bump)
        exact_error = posterior_relative(post + bump, post)
        assert 0.5 * exact_error <= measured <= 2.0 * exact_error + _EPS * found.error
        assert found.error_of(np.full((n, n), np.nan)) == np.inf


def test_the_exact_reference_is_the_information_form_s_too() -> None:
    """The oracle's premise: (P⁻¹ + Hᵀ R⁻¹ H)⁻¹ is P - (H P)ᵀ S⁻¹ (H P), exactly."""
    from exact_fractions import fractions, inverse

    p, h, r, _, post, _ = next(_problems(3, 1))
    n, m = p.shape[0], h.shape[0]
    pf, hf, rf = inverse(fractions(p)), fractions(h), inverse(fractions(r))
    info = [
        [pf[i][j] + sum(hf[a][i] * rf[a][b] * hf[b][j] for a in range(m) for b in range(m))
         for j in range(n)]
        for i in range(n)
    ]  # fmt: skip
    got = np.array([[float(v) for v in row] for row in inverse(info)])
    assert np.array_equal(got, post)
    assert isinstance(info[0][0], Fraction)


def test_scaled_inverse_is_the_inverse_to_eps_kappa() -> None:
    # "The inverse of the symmetric a (exactly symmetric) and a bound on κ(D a D) ...
    # whose error relative to sqrt(inv_ii inv_jj) is about ε κ(D a D)": against the
    # exact inverse, badly scaled (entries 1e-12 to 1e12 apart). _s_amplification
    # reads its diagonal: a mutant doubling the inverse survived every other test.
    from exact_fractions import fractions, inverse

    rng = np.random.default_rng(33)
    for trial in range(24):
        n = int(rng.integers(1, 6))
        a = _spd(rng, n, 8.0 * trial / 23, 6.0)
        found = kernels._scaled_inverse(a)
        assert found is not None
        inv, kappa = found
        assert np.array_equal(inv, inv.T)
        exact = np.array([[float(v) for v in row] for row in inverse(fractions(a))])
        unit = np.sqrt(np.diag(exact))
        error = float(np.max(np.abs(inv - exact) / np.outer(unit, unit)))
        assert error <= 4.0 * n * _EPS * kappa, (trial, error, kappa)
