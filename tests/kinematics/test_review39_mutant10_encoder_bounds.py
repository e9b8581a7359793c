"""tick_delta's counter width: 2 to 64 bits, both ends exact (review 39's MUTANT10).

A mutation review of ``navkit.kinematics``: the width check ``2 <= nbits <= 64``
read as ``<= 65`` passed every test, which tried ``bits=1`` only; ``bits=65`` then
failed in NumPy with an ``OverflowError`` (``np.uint64(64 - 65)``), not the
``ValueError`` naming ``bits`` that the docstring promises. Oracle: Python's own
integers (the modular difference mapped to ``[-2**(bits-1), 2**(bits-1))``).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.kinematics import tick_delta


def _signed_step(prev: int, cur: int, bits: int) -> int:
    d = (cur - prev) % (1 << bits)
    return d - (1 << bits) if d >= 1 << (bits - 1) else d


@pytest.mark.parametrize("bits", [0, 1, 65, 66, 128])
def test_a_width_outside_2_to_64_bits_is_a_value_error_naming_bits(bits: int) -> None:
    with pytest.raises(ValueError, match=r"^bits must be an integer from 2 to 64"):
        tick_delta(0, 1, bits=bits)
    with pytest.raises(ValueError, match=r"^bits must be an integer from 2 to 64"):
        tick_delta(np.array([0, 1]), np.array([1, 0]), bits=bits)


@pytest.mark.parametrize("bits", [2, 3, 63, 64])
def test_the_widths_at_both_ends_give_the_modular_step(bits: int) -> None:
    top = (1 << bits) - 1
    half = 1 << (bits - 1)
    pairs = [(top, 0), (0, top), (0, half - 1), (half - 1, 0), (0, half), (half, 0), (1, top)]
    for prev, cur in pairs:
        got = tick_delta(prev, cur, bits=bits)
        assert type(got) is int
        assert got == _signed_step(prev, cur, bits), (bits, prev, cur)
    out = tick_delta([p for p, _ in pairs], [c for _, c in pairs], bits=bits)
    assert out.dtype == np.int64
    assert out.tolist() == [_signed_step(p, c, bits) for p, c in pairs]
