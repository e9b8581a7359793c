"""Table.render on large floats: no digits beyond the float's own, whole numbers kept whole."""

from __future__ import annotations

from decimal import Decimal

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.sim import Table


def _cell(value: float, digits: int) -> str:
    return Table("t", ("name", "value"), (("x", value),)).render(digits=digits).split()[-1]


@pytest.mark.parametrize("digits", [1, 3, 17])
def test_huge_floats_print_in_exponent_notation(digits: int) -> None:
    text = _cell(1.23456789e20, digits)
    assert "e+20" in text
    assert float(text) == float(f"{1.23456789e20:.{digits}g}")
    assert _cell(1e300, digits) in ("1e+300", "1.0000000000000001e+300")
    assert _cell(-1.23456789e20, 17) == "-1.23456789e+20"


def test_whole_numbers_below_the_limit_keep_printing_whole() -> None:
    assert _cell(12345.6, 3) == "12346"
    assert _cell(9.99e16, 3) == "99900000000000000"
    assert _cell(1e16, 17) == "10000000000000000"
    assert _cell(123.0, 3) == "123"
    assert _cell(1.23456, 2) == "1.2"
    # Rounding up to 10**digits prints whole, as 10**digits itself does.
    assert _cell(999.6, 3) == _cell(1000.0, 3) == "1000"
    assert _cell(-9.6, 1) == "-10"


@settings(max_examples=50, deadline=None)
@given(value=st.floats(allow_nan=False, allow_infinity=False), digits=st.integers(1, 17))
def test_no_cell_shows_more_significant_digits_than_asked_or_held(
    value: float, digits: int
) -> None:
    text = _cell(value, digits)
    number = Decimal(text)
    # The printed number is the float to ``digits`` significant digits, or,
    # printed whole, within half a unit of it.
    assert abs(number - Decimal(value)) <= max(
        Decimal(abs(value)) * Decimal(10) ** (1 - digits) / 2, Decimal("0.5")
    )
    significant = number.normalize().as_tuple().digits
    assert len(significant) <= max(digits, 17)


test_no_cell_shows_more_significant_digits_than_asked_or_held_thoroughly = slow_twin(
    test_no_cell_shows_more_significant_digits_than_asked_or_held, max_examples=300
)
