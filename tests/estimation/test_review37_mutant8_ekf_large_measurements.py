"""The EKF's cancelled updates of more than 8 components commit a vouched state (mutation review).

An update whose Joseph form cancelled is finished by ``finish_cancelled``. For a
measurement of more than ``_EXACT_NIS_MAX_M`` (8) components there is no exact state:
where the kernel's x has no bound within a quarter posterior deviation or 32 ε of its
size but the information form's x⁺ has, x⁺ is committed (its docstring). Every earlier
test of those measurements was refused or took the kernel's x: deleting the choice of
x⁺ passed them all, and committed states up to 23 posterior deviations (92 times that
tolerance) off the exact posterior mean in random precise updates of 9 and 10
components. The reference is exact rational arithmetic (tests/exact_fractions.py).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf as ekf_module

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update, random_problem

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

_EPS = 2.0**-52


def _problem(seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A random precise update (x0, P, H, R, z) of 2-4 states and 9 or 10 components."""
    draw = np.random.default_rng(seed)
    n = int(draw.integers(2, 5))
    m = int(draw.integers(9, 11))
    log_p = draw.uniform(0.0, 8.0)
    log_r = log_p - draw.uniform(8.0, 20.0)  # R far below H P Hᵀ: the Joseph form cancels
    rng, p, h, r = random_problem(seed, n, m, log_p, log_r)
    x0 = rng.normal(size=n) * 10.0 ** rng.uniform(0.0, 8.0)
    truth = x0 + np.linalg.cholesky(p) @ rng.normal(size=n)
    z = h @ truth + np.linalg.cholesky(r) @ rng.normal(size=m)
    return x0, p, h, r, z


def _linear(h: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    def measure(state: np.ndarray) -> np.ndarray:
        return np.asarray(h @ state)

    return measure


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_cancelled_updates_of_more_than_eight_components_commit_a_vouched_state(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    finished = []
    finish = ekf_module.finish_cancelled

    def counted(*args: object) -> int:
        finished.append(1)
        return finish(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(ekf_module, "finish_cancelled", counted)
    checked = 0
    for seed in range(80):
        x0, p, h, r, z = _problem(seed)
        ekf = ExtendedKalmanFilter(x0, p)
        before = len(finished)
        try:
            result = ekf.update(z, _linear(h), h, r)
        except FilterError:
            continue  # refused: x and P unchanged (tested elsewhere)
        if len(finished) == before or not result.accepted:
            continue
        x_exact, p_exact, _ = exact_update(x0, p, h, r, z - h @ x0)
        mean = np.array([float(v) for v in x_exact])
        deviation = np.sqrt([float(p_exact[i][i]) for i in range(len(x0))])
        tolerance = np.maximum(0.25 * deviation, 32.0 * _EPS * np.abs(mean))
        off = np.abs(ekf.x - mean) / tolerance
        assert off.max() <= 1.0, (seed, off)
        checked += 1
    assert checked >= 40  # most draws reach the fallback and are applied
