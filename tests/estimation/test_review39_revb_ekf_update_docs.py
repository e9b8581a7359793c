"""``ExtendedKalmanFilter.update``'s docstring gives the exact fallbacks' limits (review 39, REVB).

Review 39 (EKFBIG) let cancelled updates of 9 to 12 components
(``_EXACT_CANCELLED_MAX_M``) take the exact posterior mean, covariance and NIS,
but the public docstring still said "at most 8 components" for the state and
the covariance, and that every update of more than 8 kept the kernel's NIS; nor
did it say what the exact arithmetic costs with many states (seconds: 2.3 s for
12 components of 64 states with P and R 1e280 apart, 7.5 s with 128).
"""

from __future__ import annotations

import re

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels


def _doc() -> str:
    doc = ExtendedKalmanFilter.update.__doc__
    assert doc is not None
    return " ".join(doc.split())


def test_the_state_and_covariance_limits_are_the_cancelled_fallbacks() -> None:
    # Review 40 (EKFBIG2): the exact state and covariance for every size, up to the
    # exact arithmetic's limit.
    doc = _doc()
    assert not re.findall(r"for measurements of at most (\d+) components, the exact", doc)
    assert f"would eliminate more than {kernels._EXACT_ELIMINATION_MAX} rows" in doc


def test_the_nis_limits_are_both_named() -> None:
    doc = _doc()
    limit = kernels._EXACT_ELIMINATION_MAX
    assert f"In an update of at most {limit} components" in doc
    # Since review 43 (EKFREV5) the exact NIS alone within the work cap, with a gate.
    assert f"Updates of more than {limit} components with a gate and such an S" in doc
    assert "gated on the exact NIS alone" in doc
    assert "without a gate they keep the kernel's NIS" in doc
    assert "that reach the information form, whose NIS is the exact one" in doc


def test_the_cost_with_many_states_is_given() -> None:
    assert "2.3 s with 64, 7.5 s with 128" in _doc()
