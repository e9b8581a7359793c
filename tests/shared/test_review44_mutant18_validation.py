"""Surviving mutants of ``navkit._shared.validation`` (review 44, MUTANT18).

A systematic pass over every comparison, bound, message, branch and conversion
of the module's helpers left these behaviours untested: each test below failed
with one mutant of the module (named in its docstring) and passes with the code.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import pytest

from navkit._shared.validation import (
    as_array,
    as_cell,
    as_float_array,
    as_points,
    as_sequence,
    bounded_int,
    finite_float,
    unpack,
)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf")])
def test_a_non_finite_float_is_refused_as_not_finite(value: float) -> None:
    """The message of the float fast path says what is wrong (mutant: its words)."""
    with pytest.raises(ValueError, match=rf"^speed must be finite, got {value}$"):
        finite_float(value, "speed")


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.uint32, np.uint64])
def test_a_zero_d_unsigned_array_is_its_number(dtype: type[np.unsignedinteger]) -> None:
    """A reduction of an unsigned array (``counts.max()`` kept 0-d) is a number
    (mutant: dtype kinds ``"fi"``, unsigned arrays refused as no real number)."""
    top = int(np.iinfo(dtype).max)
    got = finite_float(np.array(top, dtype=dtype), "count")
    assert type(got) is float
    assert got == float(top)


def test_a_fraction_too_large_for_a_float_is_named_by_its_type() -> None:
    """``float(Fraction(10**400))`` overflows: the message names the type, not
    ``None`` (mutant: ``_magnitude``'s last ``return`` dropped)."""
    with pytest.raises(ValueError, match=r"^ratio must be finite, got Fraction, too large"):
        finite_float(Fraction(10**400), "ratio")


@pytest.mark.parametrize("value", ["ab", b"ab", {"a": 1}, {}])
def test_strings_and_mappings_are_no_sequence(value: object) -> None:
    """A string iterates over its characters, a mapping over its keys: refused
    with a ``TypeError`` that says what was wanted (mutants: the ``raise``
    dropped, its type, its words)."""
    with pytest.raises(TypeError, match=rf"^scans must be a sequence, got {type(value).__name__}$"):
        as_sequence(value, "scans")


@pytest.mark.parametrize("value", [5, 2.5, None, object()])
def test_a_non_iterable_is_not_a_sequence(value: object) -> None:
    """The message says what was wanted (mutant: its words)."""
    with pytest.raises(TypeError, match=rf"^scans must be a sequence, got {type(value).__name__}$"):
        as_sequence(value, "scans")


@pytest.mark.parametrize("sign", [1, -1])
def test_an_out_of_range_integer_is_written_out_below_ten_to_the_thirty(sign: int) -> None:
    """Below 10**30 in size the message quotes the integer, from 10**30 on its
    magnitude (mutants: ``<=``, ``11**30``, ``10**31``)."""
    below = sign * (10**30 - 1)
    with pytest.raises(ValueError, match=rf"^steps must be in \[0, 10\], got {below}$"):
        bounded_int(below, "steps", 0, 10)
    with pytest.raises(
        ValueError, match=r"^steps must be in \[0, 10\], got an integer of about 10\*\*30$"
    ):
        bounded_int(sign * 10**30, "steps", 0, 10)


def test_two_to_the_thirty_two_is_written_as_a_power() -> None:
    """Range ends from 2**32 on read as powers, below it as numbers (mutant: ``>``)."""
    with pytest.raises(ValueError, match=r"^seed must be in \[0, 2\*\*32\], got 4294967297$"):
        bounded_int(2**32 + 1, "seed", 0, 2**32)
    with pytest.raises(ValueError, match=r"^seed must be in \[0, 4294967295\], got 4294967296$"):
        bounded_int(2**32, "seed", 0, 2**32 - 1)


@pytest.mark.parametrize(
    ("cell", "hint"),
    [
        ((0, 4), True),  # (4, 0) is inside: row 0 is the swapped pair's column
        ((2, 4), True),
        ((3, 4), False),  # (4, 3): column 3 is one past the last
        ((0, 7), False),  # (7, 0): row 7 is outside too
        ((6, 1), False),  # (1, 6): column 6 is outside
        ((0, 5), False),  # (5, 0): row 5 is one past the last
    ],
)
def test_the_swapped_pair_hint_only_when_the_swapped_pair_is_inside(
    cell: tuple[int, int], hint: bool
) -> None:
    """A cell outside a (5, 3) grid whose swap is inside suggests an (x, y) order;
    one whose swap is outside too does not (mutants: each bound of the swap's
    check, and ``or`` for ``and``)."""
    with pytest.raises(ValueError, match="is outside the grid of shape") as info:
        as_cell(cell, "goal", (5, 3))
    message = str(info.value)
    assert message.startswith(f"goal {cell} is outside the grid of shape (5, 3)")
    assert ("was it given as (x, y)?" in message) is hint
    if hint:
        assert f"and {cell[::-1]} is inside" in message


@pytest.mark.parametrize(("cell", "hint"), [((4, 0), True), ((4, 3), False), ((3, 0), True)])
def test_the_swapped_pair_hint_in_a_wide_grid(cell: tuple[int, int], hint: bool) -> None:
    """The same in a (3, 5) grid, where rows are the short side (mutants: the
    swapped row's lower bound and its upper bound read from the wrong axis)."""
    with pytest.raises(ValueError, match="is outside the grid of shape") as info:
        as_cell(cell, "goal", (3, 5))
    assert ("was it given as (x, y)?" in str(info.value)) is hint


def _nested(value: Any, depth: int) -> Any:
    for _ in range(depth):
        value = [value]
    return value


def test_a_bool_at_numpy_s_deepest_level_is_refused() -> None:
    """A 64-D nesting (NumPy's most) with a bool in its innermost list: NumPy
    would read ``[True, 0.5]`` as ``[1.0, 0.5]``, so the walk must reach it
    (mutant: one level fewer, the bool silently read as 1.0)."""
    value = _nested([True, 0.5], 63)
    assert np.asarray(_nested([1.0, 0.5], 63)).ndim == 64
    with pytest.raises(
        TypeError, match=r"^xs must hold real numbers, got an element of type bool$"
    ):
        as_float_array(value, "xs")


def test_raggedness_beyond_numpy_s_dimensions_is_no_wrong_shape() -> None:
    """Ragged lists 66 levels deep cannot be an array whatever their lengths: a
    ``TypeError`` (NumPy's reason quoted), while a ragged nesting NumPy could hold
    is a wrong shape, a ``ValueError`` (mutant: the depth limit 65)."""
    with pytest.raises(ValueError, match=r"^mask must be a rectangular array"):
        as_array(_nested([[1, 2], [3]], 62), "mask")
    with pytest.raises(TypeError, match=r"^mask must be numeric array-like: "):
        as_array(_nested([[1, 2], [3]], 64), "mask")


@pytest.mark.parametrize(
    ("value", "got"), [("ab", "str"), ({0: 1, 1: 2}, "dict"), (5, "5"), (None, "None")]
)
def test_a_cell_that_is_no_pair_is_named_as_such(value: object, got: str) -> None:
    """A string, a mapping or a non-iterable is no (row, col) pair (mutants: the
    words of both messages)."""
    with pytest.raises(TypeError, match=rf"^goal must be a \(row, col\) pair, got {got}$"):
        as_cell(value, "goal", (3, 3))


def test_a_list_that_contains_itself_is_no_array_and_holds_no_bool() -> None:
    """The walks end at NumPy's depth: neither a bool nor raggedness is found in a
    list that contains itself (mutants: the walks' last ``return False`` made True)."""
    loop: list[Any] = []
    loop.append(loop)
    for convert in (as_array, as_float_array):
        with pytest.raises(TypeError, match=r"^grid must be numeric array-like: ") as info:
            convert(loop, "grid")
        assert "bool" not in str(info.value)


@pytest.mark.parametrize(
    "zero_d", [np.array(1.0), np.array({}, dtype=object)], ids=["float", "object"]
)
@pytest.mark.parametrize("first", [True, False])
def test_a_zero_d_array_next_to_a_row_is_ragged(zero_d: Any, first: bool) -> None:
    """A 0-d array is a scalar beside a row, numeric or object (mutants: either
    branch's ``scalars = True`` or its ``continue``)."""
    value = [zero_d, [1.0, 2.0]] if first else [[1.0, 2.0], zero_d]
    with pytest.raises(ValueError, match=r"^grid must be a rectangular array"):
        as_array(value, "grid")


def test_an_array_protocol_that_raises_is_named() -> None:
    """NumPy's reason, after the argument's name (mutant: the error not returned)."""

    class Refusing:
        def __array__(self, dtype: Any = None, copy: Any = None) -> Any:
            raise TypeError("no array today")

    with pytest.raises(TypeError, match=r"^grid must be numeric array-like: no array today$"):
        as_array(Refusing(), "grid")


@pytest.mark.parametrize(("rows", "cols"), [(2, 5), (2, 1), (2, 0)])
def test_points_given_one_column_per_point_get_the_transposed_hint(rows: int, cols: int) -> None:
    with pytest.raises(ValueError, match=r"must have shape \(N, 2\)") as info:
        as_points(np.zeros((rows, cols)), "points")
    assert str(info.value).endswith(
        f" (it looks transposed, one column per item: pass its .T, shape {(cols, rows)})"
    )


@pytest.mark.parametrize("shape", [(3, 5), (5, 3), (3,), (2, 5, 1)])
def test_no_transposed_hint_when_the_transpose_does_not_fit(shape: tuple[int, ...]) -> None:
    with pytest.raises(ValueError, match=r"must have shape \(N, 2\)") as info:
        as_points(np.zeros(shape), "points")
    assert "transposed" not in str(info.value)


def test_the_transposed_hint_for_other_widths() -> None:
    with pytest.raises(ValueError, match=r"along axis 1") as info:
        as_float_array(np.zeros((3, 4)), "poses", shape=(None, 3))
    assert "pass its .T, shape (4, 3)" in str(info.value)


def test_a_memoryview_numpy_cannot_read_is_named() -> None:
    """A pointer format NumPy refuses (mutants: the ``raise`` dropped, its type,
    the word for a memoryview)."""
    view = memoryview(bytes(16)).cast("P")
    with pytest.raises(TypeError, match=r"^pairs is a memoryview NumPy cannot read: "):
        unpack(view, "pairs")


def test_as_array_refuses_masked_entries() -> None:
    with pytest.raises(ValueError, match=r"^mask has masked entries"):
        as_array(np.ma.masked_invalid([1.0, np.nan]), "mask")


@pytest.mark.parametrize("dtype", [np.uint8, np.uint64, np.int8])
def test_integer_arrays_of_any_sign_convert(dtype: type[np.integer[Any]]) -> None:
    got = as_float_array(np.array([1, 2], dtype=dtype), "xs")
    assert got.dtype == np.float64
    np.testing.assert_array_equal(got, [1.0, 2.0])


@pytest.mark.parametrize(
    ("value", "hint"),
    [
        (5.0, " (wrap a single value in a list: [value])"),
        (np.zeros((3, 1)), " (a column or row vector: pass it flattened, e.g. np.ravel(value))"),
        (np.zeros((1, 3)), " (a column or row vector: pass it flattened, e.g. np.ravel(value))"),
        (np.zeros((2, 3)), "got shape (2, 3)"),  # no hint
    ],
)
def test_a_scalar_or_a_vector_where_a_1d_array_is_wanted_gets_a_hint(value: Any, hint: str) -> None:
    with pytest.raises(ValueError, match=r"^xs must be 1-D, got shape ") as info:
        as_float_array(value, "xs", ndim=1)
    assert str(info.value).endswith(hint)


def test_no_one_d_hint_where_two_dimensions_are_wanted() -> None:
    with pytest.raises(ValueError, match=r"^grid must be 2-D, got shape \(\)$"):
        as_float_array(5.0, "grid", ndim=2)


def test_as_float_array_refuses_masked_entries_and_strings() -> None:
    with pytest.raises(ValueError, match=r"^xs has masked entries"):
        as_float_array(np.ma.array([1.0, 2.0], mask=[False, True]), "xs")
    with pytest.raises(TypeError, match=r"^xs must be numeric array-like, got str$"):
        as_float_array("1.0", "xs")
