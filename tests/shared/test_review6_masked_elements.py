"""Masked entries inside a list are refused, as a masked array's are.

``np.ma.array`` reads the top-level elements of a list (masked rows, the
``np.ma.masked`` constant); NumPy's plain conversions read them as their data.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

from navkit._shared.validation import as_array, as_float_array, integer_readings, refuse_masked
from navkit.kinematics import tick_delta

_ROW = np.ma.masked_array([1.0, 2.0], mask=[False, True])


@pytest.mark.parametrize(
    "value",
    [
        [_ROW, [3.0, 4.0]],
        ([3.0, 4.0], _ROW),
        [1.0, np.ma.masked],
        [np.ma.masked_invalid([np.nan, 1.0]), np.ma.masked_invalid([2.0, 3.0])],
    ],
)
@pytest.mark.parametrize("finite", [True, False])
def test_float_arrays_refuse_masked_list_elements(value: Any, finite: bool) -> None:
    with warnings.catch_warnings():  # np.ma.array agrees that these hold masked entries
        warnings.simplefilter("ignore", UserWarning)
        assert np.ma.getmaskarray(np.ma.array(value)).any()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "converting a masked element to nan" either
        with pytest.raises(ValueError, match=r"^ranges has masked entries"):
            as_float_array(value, "ranges", finite=finite)


def test_boolean_arrays_and_refuse_masked_see_list_elements() -> None:
    value: Any = [np.ma.masked_array([True, False], mask=[True, False]), [False, False]]
    with pytest.raises(ValueError, match=r"^occupied has masked entries"):
        as_array(value, "occupied")
    with pytest.raises(ValueError, match=r"^costs has masked entries"):
        refuse_masked(value, "costs")


def test_masked_list_elements_without_masked_entries_are_their_data() -> None:
    value = [np.ma.masked_array([1.0, 2.0], mask=[False, False]), np.ma.array([3.0, 4.0])]
    out = as_float_array(value, "points")
    np.testing.assert_array_equal(out, np.ma.array(value).filled(np.nan))


def test_a_boolean_masked_array_in_a_list_is_a_bool_element() -> None:
    # NumPy would read it as 1.0 and 0.0 next to the floats.
    with pytest.raises(TypeError, match=r"^x must hold real numbers, got an element of type bool"):
        as_float_array([np.ma.array([True, False]), [0.5, 1.0]], "x")  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "value",
    [
        np.ma.masked_array([1, 2], mask=[False, True]),
        [np.ma.masked_array([1, 2], mask=[False, True])],
    ],
)
def test_integer_readings_refuse_masked_entries(value: Any) -> None:
    with pytest.raises(ValueError, match=r"^previous has masked entries"):
        integer_readings(value, "previous")
    with pytest.raises(ValueError, match=r"^previous has masked entries"):
        tick_delta(value, 5, bits=16)


def test_integer_readings_of_an_unmasked_masked_array_are_its_data() -> None:
    value = np.ma.masked_array([65535, 2], mask=False)
    np.testing.assert_array_equal(tick_delta(value, [2, 65535], bits=16), [3, -3])
