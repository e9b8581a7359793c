"""Review 42 (EKFREV3): the exact posterior's work is capped, not unbounded in n.

The exact posterior from S's elimination (``_exact_posterior``) replays that
elimination on H P's n columns and multiplies out n (n + 1) / 2 entries: work linear
in n and growing with how far apart P and R lie (24 components of a dense R, 1e280
apart: 46 s with 64 states, 96 s with 128, 197 s with 256, measured on a loaded 2-core
machine; without end in n). Past ``_EXACT_POSTERIOR_WORK_MAX`` (about a minute) the
update raises ``FilterError`` before that work, changing nothing.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from precise_updates import linear, precise_problem


def _reaching_the_exact_posterior() -> tuple[np.ndarray, ...]:
    """Review 38's precise draw 0 (3 components, 4 states): its P is the exact posterior."""
    drawn = precise_problem(0, (2, 4))
    assert drawn is not None
    return drawn


def test_an_exact_posterior_past_its_work_limit_is_refused_changing_nothing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    x0, p, h, r, z = _reaching_the_exact_posterior()
    calls: list[int] = []
    exact_posterior = kernels._exact_posterior

    def recorded(*args: object) -> object:
        calls.append(1)
        return exact_posterior(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(kernels, "_exact_posterior", recorded)
    assert ExtendedKalmanFilter(x0, p).update(z, linear(h), h, r).accepted
    assert calls  # the draw reaches the exact posterior, and within the limit
    # A limit below this draw's work: before review 42 there was none (AttributeError).
    monkeypatch.setattr(kernels, "_EXACT_POSTERIOR_WORK_MAX", 1000.0)
    kept = [a.copy() for a in (x0, p, h, r, z)]
    ekf = ExtendedKalmanFilter(x0, p)
    # Since review 43 (EKFREV5) refused before S's elimination too, H P's products counted.
    with pytest.raises(FilterError, match=r"exact update of 4 states from 3 components"):
        ekf.update(z, linear(h), h, r)
    for a, b in zip(kept, (x0, p, h, r, z), strict=True):
        assert np.array_equal(a, b)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


def test_an_exact_posterior_of_128_states_1e280_apart_is_refused_before_its_work() -> None:
    # 24 components of a dense R, P and R 1e280 apart: S's elimination, then the
    # estimate, 84 s; the replay (96 s measured before review 42) is not made.
    m, n = 24, 128
    rng = np.random.default_rng(n)
    a = rng.normal(size=(n, n))
    p = (a @ a.T / n + np.eye(n)) * 1e140
    b = rng.normal(size=(m, m))
    r = (b @ b.T / m + np.eye(m)) * 1e-140
    h, y = rng.normal(size=(m, n)), rng.normal(size=m)
    elimination = kernels._eliminated(p, h, r, y)
    with pytest.raises(FilterError, match=r"about \d+ s of exact arithmetic, more than"):
        kernels._exact_posterior(p, elimination)
