"""The check shared by the NumPy error-state tests (test helper, review 31)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np


def assert_default_answer(call: Callable[[], Any], mode: str) -> None:
    """``call()`` under ``np.errstate(**{mode: "raise"})`` gives its answer under the defaults.

    NumPy's defaults make underflow no error (and no warning): the answer then is
    the one navkit must give whatever the caller's error state.
    """
    expected = call()
    with np.errstate(**{mode: "raise"}):  # type: ignore[arg-type]
        got = call()  # FloatingPointError before review 31's fixes
    assert np.array_equal(np.asarray(got), np.asarray(expected))
