"""Omni-drive kinematics give NumPy's default answer whatever ``np.seterr`` says (review 31).

The three-wheel Jacobian holds rounding noise (-3.7e-15 for cos(π/2) · 20):
times a velocity of 1e-300 m/s it underflows, ``FloatingPointError`` after a
caller's ``np.seterr(all="raise")`` or ``under="raise"``. The products already
ran in an ``np.errstate`` block for overflow: underflow is ignored there too.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from errstate_checks import assert_default_answer
from navkit.kinematics import OmniDrive


def _drive() -> OmniDrive:
    return OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


_CASES: dict[str, Callable[[], Any]] = {
    "inverse": lambda: _drive().inverse([1e-300, 1e-300, 0.0]),
    "inverse_batch": lambda: _drive().inverse_batch([[1e-300, 1e-300, 0.0]]),
}


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_default_answer_whatever_numpys_error_state(name: str, mode: str) -> None:
    assert_default_answer(_CASES[name], mode)
