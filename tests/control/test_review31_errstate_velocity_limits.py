"""Velocity limits give NumPy's default answer whatever the caller's ``np.seterr`` (review 31).

The length of a velocity change is ``np.linalg.norm``, whose squares underflow
for a change of 1e-200 m/s (or for the small component of a 1e200 one):
``FloatingPointError`` after a caller's ``np.seterr(all="raise")`` or
``under="raise"``, in ``limit_velocity_change`` and in every
``PotentialFieldController.step`` that limits acceleration.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from errstate_checks import assert_default_answer
from navkit.control import limit_velocity_change

_LIMITS = {"max_accel": 0.5, "max_decel": 2.0, "dt": 0.1}

_CASES: dict[str, Callable[[], Any]] = {
    "a change of 1e-200 m/s": lambda: limit_velocity_change(
        [0.0, 0.0], [1e-200, 1e-200], **_LIMITS
    ),
    "a tiny change from a speed": lambda: limit_velocity_change(
        [0.3, 0.0], [0.3, 1e-200], **_LIMITS
    ),
    "a change of 1e200 m/s beside 1 m/s": lambda: limit_velocity_change(
        [0.0, 0.0], [1e200, 1.0], **_LIMITS
    ),
}


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_default_answer_whatever_numpys_error_state(name: str, mode: str) -> None:
    assert_default_answer(_CASES[name], mode)


def test_the_error_state_is_the_callers_again() -> None:
    with np.errstate(all="raise"):
        before = np.geterr()
        limit_velocity_change([0.0, 0.0], [1e-200, 1e-200], **_LIMITS)
        assert np.geterr() == before
