"""``navkit._shared.selects`` without numba's private ``do_minmax``.

The intrinsics emit numba's own ``min``/``max`` code through
``numba.cpython.builtins.do_minmax``, which is not public API: a numba that
renamed it would make every kernel module that binds ``min2``/``max2`` fail.
The module then spells the same code out (``_select``); these tests compile
intrinsics on that fallback and check them bit for bit against the builtins.
"""

from __future__ import annotations

import math
import operator
from typing import Any

import numba
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba.core.extending import intrinsic

from navkit._shared import selects

_SPECIAL = st.sampled_from([0.0, -0.0, math.inf, -math.inf, math.nan, 1.0, -1.0, 5e-324])
_FLOAT = st.one_of(st.floats(allow_nan=True), _SPECIAL)
_INT = st.integers(-(2**63), 2**63 - 1)


def _bits(values: tuple[float | int, ...]) -> list[str]:
    return [float(v).hex() if isinstance(v, float) else repr(int(v)) for v in values]


@pytest.fixture(scope="module")
def fallback_pairs() -> Any:
    """A kernel whose min/max are the fallback's, compiled with do_minmax hidden."""
    saved = selects._DO_MINMAX
    selects._DO_MINMAX = selects._select
    try:
        lo = intrinsic(selects._typing(operator.lt))
        hi = intrinsic(selects._typing(operator.gt))

        @numba.njit(cache=False)
        def pairs(a: float, b: float, i: int, j: int) -> Any:
            return lo(a, b), hi(a, b), lo(i, j), hi(i, j), lo(a, i), hi(i, a)

        pairs(0.0, 1.0, 0, 1)  # compile while the fallback is in place
    finally:
        selects._DO_MINMAX = saved
    return pairs


@numba.njit(cache=False)
def _pairs_builtin(a: float, b: float, i: int, j: int) -> Any:
    return min(a, b), max(a, b), min(i, j), max(i, j), min(a, i), max(i, a)


def test_the_fallback_is_used_only_without_do_minmax() -> None:
    from numba.cpython import builtins

    expected = getattr(builtins, "do_minmax", selects._select)
    assert selects._DO_MINMAX is expected


@settings(max_examples=300, deadline=None)
@given(_FLOAT, _FLOAT, _INT, _INT)
def test_the_fallback_equals_the_builtins_bit_for_bit(
    fallback_pairs: Any, a: float, b: float, i: int, j: int
) -> None:
    assert _bits(fallback_pairs(a, b, i, j)) == _bits(_pairs_builtin(a, b, i, j))


@pytest.mark.parametrize(("a", "b"), [(0.0, -0.0), (-0.0, 0.0), (math.nan, 1.0), (1.0, math.nan)])
def test_the_fallback_keeps_the_first_on_ties_and_nan(
    fallback_pairs: Any, a: float, b: float
) -> None:
    got = fallback_pairs(a, b, 3, 3)
    assert _bits(got[:2]) == _bits((min(a, b), max(a, b)))
    assert type(got[2]) is type(got[3]) is int
