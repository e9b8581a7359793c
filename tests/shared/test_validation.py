"""The private argument checks every layer relies on."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared.costs import validate_costs
from navkit._shared.validation import (
    as_array,
    as_bool,
    as_cell,
    as_float_array,
    as_points,
    finite_float,
    is_ragged,
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
        [True, 0.6],  # NumPy converts a bool among numbers to 1.0
        [[0.5, 1.0], (2.0, np.False_)],
        ([1.0], [True]),
        [np.array([True, False]), [0.5, 1.0]],
        [None, 1.0],
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


# Gaps the public-API fuzz test exposed (issue 12): every helper raises only
# ValueError or TypeError naming the argument, whatever it is given.


@pytest.mark.parametrize("value", [10**400, -(10**400), 2**1024])
def test_integers_too_large_for_a_float_are_value_errors(value: int) -> None:
    with pytest.raises(ValueError, match=r"^a must be finite, got an integer of about 10\*\*\d+"):
        finite_float(value, "a")
    with pytest.raises(ValueError, match=r"^a must be finite"):
        positive_float(value, "a")


def test_huge_integers_inside_arrays_are_value_errors() -> None:
    with pytest.raises(ValueError, match=r"^x must hold finite numbers"):
        as_float_array([1.0, 10**400], "x")
    with pytest.raises(ValueError, match=r"^x must hold finite numbers"):
        as_float_array(np.array([10**400], dtype=object), "x")


@pytest.mark.parametrize(
    "value",
    [np.complex128(1 + 0j), 1 + 0j, np.array(1 + 0j), "1.0", np.str_("1.0"), b"1", None, np.True_],
)
def test_scalars_refuse_complex_strings_and_flags(value: object) -> None:
    with pytest.raises(TypeError, match=r"^a must be a real number"):
        finite_float(value, "a")


def test_numpy_real_scalars_and_0d_arrays_are_real_numbers() -> None:
    assert finite_float(np.int8(-3), "a") == -3.0
    assert finite_float(np.uint64(2**63), "a") == 2.0**63
    assert finite_float(np.array(0.25), "a") == 0.25
    with pytest.raises(ValueError, match="a must be finite"):
        finite_float(np.float32("nan"), "a")


@pytest.mark.parametrize("value", [5e-324, 1e-310, np.nextafter(0.0, 1.0)])
def test_positive_means_a_normal_float_so_its_reciprocal_is_finite(value: float) -> None:
    with pytest.raises(ValueError, match=r"^r must be at least 2\.225e-308 \(a normal float\)"):
        positive_float(value, "r")
    with pytest.raises(ValueError, match=r"^r must be 0 or at least"):
        positive_float(value, "r", allow_zero=True)
    smallest = positive_float(2.2250738585072014e-308, "r")
    assert math.isfinite(1.0 / smallest)


@pytest.mark.parametrize(
    "value",
    [
        np.array([1.0, 2.0], dtype=object),
        [np.float32(1.0), np.int64(2)],
        (1, 2.5),
    ],
)
def test_object_arrays_and_sequences_of_real_numbers_convert(value: object) -> None:
    out = as_float_array(value, "x")  # type: ignore[arg-type]
    assert out.dtype == np.float64 and out.shape == (2,)


def test_nested_sequences_of_real_numbers_and_arrays_convert() -> None:
    value = [np.array([1.0, 2.0]), (3, np.float32(4.0)), [np.int8(5), 6.0]]
    np.testing.assert_array_equal(as_float_array(value, "x"), [[1, 2], [3, 4], [5, 6]])


@pytest.mark.parametrize(
    "value",
    [
        np.array([1.0, "2"], dtype=object),
        np.array([1.0, None], dtype=object),
        np.array([1.0, 1j], dtype=object),
        np.array([1.0, True], dtype=object),
        np.array(["1.0"]),
        np.zeros(2, dtype="datetime64[s]"),
        {"x": 1.0},
        {1.0, 2.0},
    ],
)
def test_object_arrays_and_odd_dtypes_are_refused(value: object) -> None:
    with pytest.raises(TypeError, match=r"^x must"):
        as_float_array(value, "x")  # type: ignore[arg-type]


@pytest.mark.parametrize("shape", [(3, 0), (0, 3), (0, 0), (1, 0), (0, 2, 1)])
def test_points_refuse_empty_arrays_of_the_wrong_shape(shape: tuple[int, ...]) -> None:
    with pytest.raises(ValueError, match=r"^p must have shape \(N, 2\) or \(2,\)"):
        as_points(np.empty(shape), "p")


def test_points_accept_no_points() -> None:
    assert as_points(np.empty((0, 2)), "p").shape == (0, 2)
    assert as_points((), "p").shape == (0, 2)


def test_points_are_never_the_callers_array_when_converted_and_never_modified() -> None:
    pts = np.array([[1, 2]], dtype=np.int32)
    out = as_points(pts, "p")
    out[0, 0] = 9.0
    assert pts[0, 0] == 1
    frozen = np.array([[1.0, 2.0]])
    frozen.flags.writeable = False
    assert as_points(frozen, "p").tolist() == [[1.0, 2.0]]
    assert not frozen.flags.writeable


@given(st.one_of(st.floats(), st.integers(), st.complex_numbers(), st.text(max_size=3), st.none()))
def test_finite_float_raises_only_value_or_type_errors(value: object) -> None:
    try:
        out = finite_float(value, "a")
    except (ValueError, TypeError) as exc:
        assert str(exc).startswith("a ")
    else:
        assert math.isfinite(out) and type(out) is float


@given(st.one_of(st.floats(), st.integers()))
def test_positive_float_results_have_finite_reciprocals(value: float) -> None:
    try:
        out = positive_float(value, "a")
    except ValueError:
        return
    assert out > 0.0 and math.isfinite(1.0 / out)


def test_signalling_nans_widen_without_a_warning() -> None:
    # A float32 signalling NaN (raw sensor bytes) made NumPy warn while widening it,
    # an error under -W error; it is a NaN like any other.
    snan = np.array([0x7FA00000, 0x3F800000], dtype=np.uint32).view(np.float32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = as_float_array(snan, "ranges", finite=False)
    assert out.dtype == np.float64 and np.isnan(out[0]) and out[1] == 1.0
    with pytest.raises(ValueError, match="ranges must contain only finite values"):
        as_float_array(snan, "ranges")


def _lists_of(children: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    return st.lists(children, max_size=3)


# Nested lists of numbers, regular or not.
nested = st.recursive(st.integers(-5, 5), _lists_of, max_leaves=12)


@given(nested)
def test_is_ragged_agrees_with_numpy(value: Any) -> None:
    try:
        np.asarray(value, dtype=np.float64)
    except ValueError:
        refused = True
    else:
        refused = False
    assert is_ragged(value) == refused


@given(st.lists(st.integers(0, 3), min_size=1, max_size=3))
def test_numpy_blocks_nested_in_lists(shape: list[int]) -> None:
    block = np.zeros(shape)
    assert not is_ragged([block, block.copy()])
    assert is_ragged([block, np.zeros([*shape[:-1], shape[-1] + 1])])


def test_ragged_nesting_is_a_value_error_naming_the_argument() -> None:
    for value in ([[1, 2], [3]], [1, [2, 3]]):
        with pytest.raises(ValueError, match="pts must be a rectangular array"):
            as_float_array(value, "pts")
        with pytest.raises(ValueError, match="pts must be a rectangular array"):
            as_points(value, "pts")
    with pytest.raises(TypeError, match="pts must"):
        as_float_array([[1, 2], ["a", "b"]], "pts")


def test_masked_entries_are_refused_not_read_as_data() -> None:
    masked = np.ma.masked_invalid([[1.0, 2.0], [np.nan, 4.0]])
    with pytest.raises(ValueError, match="pts has masked entries"):
        as_float_array(masked, "pts", finite=False)
    with pytest.raises(ValueError, match="mask has masked entries"):
        as_array(np.ma.masked_equal([True, False], False), "mask")
    with pytest.raises(ValueError, match="costs has masked entries"):
        validate_costs(np.ma.masked_greater([[1.0, 50.0]], 10.0))
    # Without masked entries a masked array is its data.
    unmasked = np.ma.array([[1.0, 2.0]])
    assert as_float_array(unmasked, "pts").tolist() == [[1.0, 2.0]]
    assert validate_costs(unmasked).tolist() == [[1.0, 2.0]]
