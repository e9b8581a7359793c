"""Validation rules documented in navkit._shared.validation (mutation testing).

Surviving mutants: a 0-d boolean array accepted as a real number, a cell one
row past the grid accepted, and integer readings that NumPy types as float64
(``[2**64 - 1, -1]``, ``[]``) refused as a dtype instead of kept as integers.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.validation import as_cell, finite_float, integer_readings
from navkit.kinematics import tick_delta


@pytest.mark.parametrize("value", [np.array(True), np.array(False)])
def test_a_zero_d_boolean_array_is_no_real_number(value: np.ndarray) -> None:
    # "not bool": a 0-d array counts as its element, and a bool is refused.
    with pytest.raises(TypeError, match=r"^flag must be a real number"):
        finite_float(value, "flag")


def test_a_zero_d_numeric_array_is_its_element() -> None:
    assert finite_float(np.array(2), "a") == 2.0
    assert finite_float(np.array(0.25, dtype=np.float32), "a") == 0.25


@pytest.mark.parametrize("cell", [(3, 0), (0, 4), (3, 4)])
def test_a_cell_on_the_row_or_column_past_the_grid_is_outside(cell: tuple[int, int]) -> None:
    with pytest.raises(ValueError, match=r"^start .* is outside the grid of shape \(3, 4\)"):
        as_cell(cell, "start", (3, 4))
    assert as_cell((2, 3), "start", (3, 4)) == (2, 3)  # the last cell is inside


def test_integers_numpy_types_as_float64_are_kept_as_integers() -> None:
    out = integer_readings([2**64 - 1, -1], "ticks")
    assert [int(v) for v in out] == [2**64 - 1, -1]
    assert integer_readings([], "ticks").size == 0


def test_tick_delta_takes_readings_that_share_no_numpy_integer_dtype() -> None:
    prev, cur = [2**64 - 1, -1], [0, 0]
    # The 64-bit modular difference, signed: computed with Python integers.
    want = [((c - p) % 2**64) - (2**64 if (c - p) % 2**64 >= 2**63 else 0)
            for p, c in zip(prev, cur, strict=True)]
    assert np.asarray(tick_delta(prev, cur, bits=64)).tolist() == want == [1, 1]
    assert np.asarray(tick_delta([], [], bits=64)).size == 0
