"""Surviving mutants of ``navkit._shared.validation`` (review 44, MUTANT22).

Continues MUTANT18's pass (``integer_readings``, ``_is_integer`` and
``as_float_array``): each test below failed with one mutant of the module
(named in its docstring) and passes with the code.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.validation import as_float_array, integer_readings


class _Point:
    """A ``geometry_msgs/Point``-like message: fields x, y, z."""

    def __init__(self) -> None:
        self.x = 1.0
        self.y = 2.0
        self.z = 3.0


def test_shape_names_the_components_when_none_are_given() -> None:
    """Without ``components``, ``shape[-1]`` says how many fields to suggest
    (mutant: ``components is not None``, the shape ignored)."""
    with pytest.raises(TypeError, match=r"\(a ROS message\?\): pass \(m\.x, m\.y\)$"):
        as_float_array([_Point()], "p", shape=(None, 2))  # type: ignore[arg-type]


def test_explicit_components_win_over_the_shape() -> None:
    """``components`` given is kept, not replaced by ``shape[-1]`` (same mutant)."""
    with pytest.raises(TypeError, match=r"\(a ROS message\?\): pass \(m\.x, m\.y\)$"):
        as_float_array([_Point()], "p", shape=(None, 3), components=2)  # type: ignore[arg-type]


def test_an_empty_shape_asks_for_a_scalar() -> None:
    """``shape=()`` is a 0-D request with no last axis to read components from
    (mutant: ``len(shape) >= 0``, an IndexError)."""
    got = as_float_array(3.0, "v", shape=())
    assert got.shape == () and float(got) == 3.0
    with pytest.raises(ValueError, match=r"^v must be 0-D, got shape \(2,\)$"):
        as_float_array([1.0, 2.0], "v", shape=())


class _Raising:
    """An element whose attribute look-up raises (not an AttributeError)."""

    @property
    def x(self) -> float:
        raise RuntimeError("not a message")


class _OnlyXZ:
    """An element with fields x and z but no y: no ``(x, y)`` message."""

    def __init__(self) -> None:
        self.x = 1.0
        self.z = 3.0


@pytest.mark.parametrize(
    ("item", "type_name"), [(_Raising(), "_Raising"), (_OnlyXZ(), "_OnlyXZ"), (object(), "object")]
)
def test_an_element_that_is_no_message_gets_the_bare_message(item: object, type_name: str) -> None:
    """No hint is an empty hint: the message ends at the element's type (mutants:
    ``_message_hint``'s ``return ""`` for a raising property and for fields that
    are not x, y dropped, a None concatenated: a TypeError of another message)."""
    expected = f"^p must hold real numbers, got an element of type {type_name}$"
    with pytest.raises(TypeError, match=expected):
        as_float_array([item], "p", shape=(None, 2))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=expected):
        as_float_array([item], "p")  # type: ignore[arg-type]


@pytest.mark.parametrize("kind", ["reversed", "broadcast"])
def test_a_two_element_view_with_a_non_positive_stride_comes_back_contiguous(kind: str) -> None:
    """Two values are the shortest view whose layout counts (an FMA of the second
    product onto the first is not one of the first onto the second) (mutant:
    ``arr.shape[0] > 2``, a two-element view passed on as it is)."""
    base = np.array([2.0, 1.0]) if kind == "reversed" else np.array(1.5)
    view = base[::-1] if kind == "reversed" else np.broadcast_to(base, (2,))
    assert not view.flags.c_contiguous
    got = as_float_array(view, "v")
    assert got.flags.c_contiguous
    assert got.tolist() == view.tolist()


@pytest.mark.parametrize(("value", "type_name"), [("12", "str"), (b"12", "bytes"), ("", "str")])
def test_a_string_of_readings_is_named_as_a_string(value: object, type_name: str) -> None:
    """A string is refused as what it is, not by the dtype NumPy gives it (mutant:
    the str/bytes check dropped, a ``got dtype <U2`` message)."""
    with pytest.raises(
        TypeError, match=rf"^left_ticks must hold integer counter readings, got {type_name}$"
    ):
        integer_readings(value, "left_ticks")


def test_a_bool_among_readings_is_a_type_error() -> None:
    """Booleans are no counts (mutant: the bool check's TypeError made ValueError)."""
    with pytest.raises(
        TypeError,
        match=r"^left_ticks must hold integer counter readings, got an element of type bool$",
    ):
        integer_readings([True, 5], "left_ticks")


class _NoArray:
    """An array-like whose conversion fails (neither ragged nor a sequence)."""

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        raise ValueError("no readings here")


def test_readings_numpy_cannot_convert_are_a_type_error_naming_why() -> None:
    """NumPy's reason is kept (mutants: that TypeError dropped, an unbound name,
    or made a ValueError)."""
    with pytest.raises(
        TypeError, match=r"^left_ticks must hold integer counter readings: no readings here$"
    ):
        integer_readings(_NoArray(), "left_ticks")


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.uint32, np.uint64])
def test_unsigned_readings_come_back_unconverted(dtype: type[np.unsignedinteger]) -> None:
    """An unsigned counter is a count (mutant: kinds ``"i"``, unsigned refused)."""
    ticks = np.array([0, np.iinfo(dtype).max], dtype=dtype)
    assert integer_readings(ticks, "left_ticks") is ticks


@pytest.mark.parametrize(("dtype", "shown"), [(bool, "bool"), (np.complex128, "complex128")])
def test_an_empty_buffer_of_no_integer_dtype_is_refused(dtype: type, shown: str) -> None:
    """Only float buffers (an empty list's dtype) are looked at item by item; an
    empty buffer of another dtype is refused by it (mutant: ``kind == "f" or not
    an ndarray``, which found no item that is not an integer and accepted it)."""
    with pytest.raises(
        TypeError, match=rf"^left_ticks must hold integer counter readings, got dtype {shown}$"
    ):
        integer_readings(np.array([], dtype=dtype).data, "left_ticks")
