"""``plain_value`` types only a PLAIN_FLOAT or float64 argument (review 35, MUTANT4).

Its typing returns no signature for anything else, so numba reports a typing
error naming the call. Without that guard (a mutant that passed the suite) an
int64 or float32 argument was typed as float64 and reached the lowering, which
failed with a bare ``AssertionError`` on the LLVM types (``('i64', 'double')``)
instead. Oracle: numba's own contract, a ``TypingError`` for a call that has no
implementation for its argument types.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import pytest
from numba.core.errors import TypingError

from navkit.estimation._plain_float import plain_value


@numba.njit(cache=False)
def _take(x: Any) -> float:
    return float(plain_value(x))


def test_a_float64_argument_is_its_value() -> None:
    assert _take(1.5) == 1.5
    assert _take(np.float64(-0.25)) == -0.25


@pytest.mark.parametrize("value", [np.int64(3), np.float32(2.5), np.int32(1)])
def test_other_argument_types_fail_at_typing(value: Any) -> None:
    with pytest.raises(TypingError):
        _take(value)
