"""The private argument checks every layer relies on."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared.validation import (
    as_bool,
    as_cell,
    as_float_array,
    as_points,
    finite_float,
    positive_float,
)


@pytest.mark.parametrize(
    "value",
    [
        [1 + 1j, 2.0],
        np.array([1 + 1j]),
        "1.0",
        ["1.0", "2.0"],
        [True, False],
        np.array([True]),
        [None, 1.0],
        [[1.0, 2.0], [3.0]],
        b"12",
    ],
)
def test_arrays_refuse_what_only_converts_by_accident(value: object) -> None:
    with pytest.raises(TypeError, match=r"^x must"):
        as_float_array(value, "x")  # type: ignore[arg-type]


@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), max_size=5))
def test_real_sequences_convert_exactly(values: list[float]) -> None:
    out = as_float_array(values, "x")
    assert out.dtype == np.float64
    assert out.tolist() == values


def test_integer_and_float32_arrays_convert_and_are_not_modified() -> None:
    ints = np.arange(4, dtype=np.int32)
    out = as_float_array(ints, "x")
    assert out.dtype == np.float64 and out.tolist() == [0.0, 1.0, 2.0, 3.0]
    out[0] = 9.0
    assert ints[0] == 0


def test_shape_and_finiteness_are_checked() -> None:
    with pytest.raises(ValueError, match="x must be 2-D"):
        as_float_array([1.0], "x", ndim=2)
    with pytest.raises(ValueError, match="length 3 along axis 0"):
        as_float_array([1.0, 2.0], "x", shape=(3,))
    with pytest.raises(ValueError, match="finite"):
        as_float_array([math.nan], "x")
    assert np.isnan(as_float_array([math.nan], "x", finite=False)[0])


def test_points_shapes() -> None:
    assert as_points([1.0, 2.0], "p").shape == (1, 2)
    assert as_points([], "p").shape == (0, 2)
    with pytest.raises(ValueError, match=r"p must have shape \(N, 2\)"):
        as_points([1.0, 2.0, 3.0], "p")


@pytest.mark.parametrize(
    ("value", "error"),
    [
        ({0: 1, 1: 2}, TypeError),
        ((True, False), TypeError),
        ((np.True_, 1), TypeError),
        ("12", TypeError),
        ((1.5, 2), TypeError),
        ((math.inf, 2), TypeError),
        ((1, 2, 3), ValueError),
        ((9, 0), ValueError),
        ((-1, 0), ValueError),
        (3, TypeError),
    ],
)
def test_cells_must_be_integer_pairs_inside_the_grid(value: object, error: type) -> None:
    with pytest.raises(error, match=r"^cell"):
        as_cell(value, "cell", (5, 5))


def test_cells_accept_integers_of_any_kind() -> None:
    assert as_cell((np.int32(1), 2), "cell", (5, 5)) == (1, 2)
    assert as_cell(np.array([4, 0]), "cell", (5, 5)) == (4, 0)
    assert as_cell((1.0, 2), "cell", (5, 5)) == (1, 2)


def test_scalars_and_flags() -> None:
    assert finite_float(np.float32(0.5), "a") == 0.5
    with pytest.raises(TypeError, match="a must be a real number"):
        finite_float(True, "a")
    with pytest.raises(TypeError, match="a must be a real number"):
        finite_float("1", "a")
    with pytest.raises(ValueError, match="a must be > 0"):
        positive_float(0.0, "a")
    assert positive_float(0.0, "a", allow_zero=True) == 0.0
    assert as_bool(np.True_, "f") is True
    for bad in ("no", None, 2, 1.0):
        with pytest.raises(TypeError, match="f must be a bool"):
            as_bool(bad, "f")
