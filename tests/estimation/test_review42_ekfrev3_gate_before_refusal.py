"""Review 42 (EKFREV3): every refusal past the 24-row limit is gated first.

Review 41 gated a computed-singular S past the limit on a lower bound of its exact
NIS before refusing it, so that readings far apart are rejected by a gate, not
refused. An R block singular in exact arithmetic among more than 24 components (its
exact update would need S's elimination) still raised ``FilterError`` at once, from
the gate's retry too: a reading 1000 deviations off at a gate of 100 was refused.
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update
from precise_updates import linear


def _singular_block_readings(offset: float) -> tuple[np.ndarray, ...]:
    """Review 41's R: a 2 x 2 block singular in exact arithmetic among 25 components."""
    m, n = 25, 3
    a, b = 58_893_648, 65_446_701
    r = np.eye(m) * 2.0**-40
    r[:2, :2] = np.array([[a * a, a * b], [a * b, b * b]], dtype=float) * 2.0**-92
    assert Fraction(r[0, 0]) * Fraction(r[1, 1]) == Fraction(r[0, 1]) ** 2
    rng = np.random.default_rng(2)
    h = rng.normal(size=(m, n))
    x0, p = np.zeros(n), np.eye(n)
    z = h @ rng.normal(size=n) + 1e-6 * rng.normal(size=m)
    z[5] += offset
    return x0, p, h, r, z


def test_a_reading_far_off_with_a_singular_r_block_is_rejected_by_the_gate() -> None:
    x0, p, h, r, z = _singular_block_readings(1000.0)
    kept = [a.copy() for a in (x0, p, h, r, z)]
    ekf = ExtendedKalmanFilter(x0, p)
    result = ekf.update(z, linear(h), h, r, gate=100.0)  # before: FilterError
    assert not result.accepted and result.status.name == "GATED"
    assert result.reason is not None and "NIS at least" in result.reason
    assert result.nis > 100.0 and Fraction(result.nis) <= exact_update(x0, p, h, r, z)[2]
    for a, b in zip(kept, (x0, p, h, r, z), strict=True):
        assert np.array_equal(a, b)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


@pytest.mark.parametrize(("offset", "gate"), [(1000.0, None), (0.0, 100.0)])
def test_a_singular_r_block_the_bound_does_not_reject_is_refused_as_filter_error(
    offset: float, gate: float | None
) -> None:
    x0, p, h, r, z = _singular_block_readings(offset)
    ekf = ExtendedKalmanFilter(x0, p)
    with pytest.raises(FilterError, match=r"R's block of components \[0, 1\] is singular") as info:
        ekf.update(z, linear(h), h, r, gate=gate)
    assert type(info.value) is FilterError  # the public class, not a private one
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
