"""``navkit._shared.selects``: numba's ``min``/``max`` builtins, without an overload to compile.

Review 50 (issue 17): the simulator's, the fusion filter's, the trackers' and
the grid conversions' kernels call ``min2``/``max2`` instead of the builtins,
which numba compiles as a function of their own per argument types and
process. Written out as conditional expressions they compiled nothing either,
but LLVM kept them as compares and branches where the builtins are selects
(``maxsd``/``minsd``): the intrinsics emit the builtins' own code, so the
values (NaN and signed zeros included) and the optimised code are the same.
"""

from __future__ import annotations

import math
import re

import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.selects import max2, min2

_Pairs = tuple[float, float, int, int, float, float]


@numba.njit
def _pairs_ours(a: float, b: float, i: int, j: int) -> _Pairs:
    return min2(a, b), max2(a, b), min2(i, j), max2(i, j), min2(a, i), max2(i, a)


@numba.njit
def _pairs_builtin(a: float, b: float, i: int, j: int) -> _Pairs:
    return min(a, b), max(a, b), min(i, j), max(i, j), min(a, i), max(i, a)


_SPECIAL = st.sampled_from([0.0, -0.0, math.inf, -math.inf, math.nan, 1.0, -1.0, 5e-324])
_FLOAT = st.one_of(st.floats(allow_nan=True), _SPECIAL)
_INT = st.integers(-(2**63), 2**63 - 1)


def _bits(values: tuple[float | int, ...]) -> list[str]:
    return [float(v).hex() if isinstance(v, float) else repr(int(v)) for v in values]


@settings(max_examples=400, deadline=None)
@given(_FLOAT, _FLOAT, _INT, _INT)
def test_min2_max2_equal_the_builtins_bit_for_bit(a: float, b: float, i: int, j: int) -> None:
    ours = _pairs_ours(a, b, i, j)
    builtin = _pairs_builtin(a, b, i, j)
    assert _bits(ours) == _bits(builtin)
    # And Python's own (the kernels' fallback without numba's JIT): the first kept on ties.
    python = (min(a, b), max(a, b), min(i, j), max(i, j), min(a, float(i)), max(float(i), a))
    assert _bits(ours[:4]) == _bits(python[:4])


@pytest.mark.parametrize(("a", "b"), [(0.0, -0.0), (-0.0, 0.0), (math.nan, 1.0), (1.0, math.nan)])
def test_signed_zeros_and_nan_keep_the_first_as_the_builtins_do(a: float, b: float) -> None:
    got = _pairs_ours(a, b, 0, 0)
    assert _bits(got[:2]) == _bits((min(a, b), max(a, b)))


def _opcodes(ir: str) -> list[str]:
    """The instructions of the LLVM IR function bodies, without names or constants."""
    ops = []
    for line in ir.splitlines():
        match = re.match(r"\s+(?:%\S+ = )?([a-z_]+)\b", line)
        if match and not line.lstrip().startswith(";"):
            ops.append(match.group(1))
    return ops


def test_a_clamp_compiles_to_the_builtins_code() -> None:
    ours = numba.njit(lambda x: min2(max2(x, 0.0), 1.0))
    builtin = numba.njit(lambda x: min(max(x, 0.0), 1.0))
    assert ours(np.float64(2.5)) == builtin(np.float64(2.5)) == 1.0
    ir_ours = next(iter(ours.inspect_llvm().values()))
    ir_builtin = next(iter(builtin.inspect_llvm().values()))
    # The builtin's IR also holds its overload's own function: compare the kernels'.
    assert _opcodes(ir_ours).count("select") >= 2
    assert _opcodes(ir_ours).count("select") <= _opcodes(ir_builtin).count("select")


def test_non_numbers_are_refused_when_typed() -> None:
    bad = numba.njit(lambda: max2((1, 2), 3))
    with pytest.raises(numba.core.errors.TypingError):
        bad()
