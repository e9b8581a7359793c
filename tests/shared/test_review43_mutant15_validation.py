"""A list holding a NumPy array and an object whose ``__class__`` says ndarray (MUTANT15).

Review 36 made validation ask an object's type, not ``isinstance``, which
believes ``__class__``; its tests passed the lying object alone or in a pair
with a number. Next to a real array in a list, ``holds_bool`` looks for a
boolean array among the list's arrays: with ``isinstance`` back in that one
place (a surviving mutant), the wrapper was taken for an array and its missing
``dtype`` raised ``AttributeError`` instead of the list being read as the
array-likes it holds. The same for a wrapper whose ``__class__`` says
``np.ma.MaskedArray`` (a proxy of a masked array), alone or next to a real
masked array: ``refuse_masked`` read its missing ``mask`` when it believed
``isinstance``. And ``integer_readings`` of a wrapper of Python integers
that NumPy types as float64 (``[2**64 - 1, -1]``) gives the list's own answer
(the integers, in an object array), not a refusal of its float dtype; ``unpack``
(a pair, a cell) reads a wrapper through ``__array__``, not by iterating it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from class_liars import Liar
from navkit._shared.validation import (
    as_array,
    as_cell,
    as_points,
    holds_bool,
    integer_readings,
    unpack,
)


class MaskedLiar(Liar):
    """A wrapper whose ``__class__`` says ``np.ma.MaskedArray``, without a ``mask``."""

    @property  # type: ignore[misc]
    def __class__(self) -> type:
        return np.ma.MaskedArray


def test_the_liar_passes_isinstance_and_has_no_dtype() -> None:
    liar: Any = Liar([1.0, 2.0])
    assert isinstance(liar, np.ndarray)
    assert not hasattr(liar, "dtype")


@pytest.mark.parametrize("first", [True, False])
def test_a_list_of_an_array_and_a_liar_is_read_as_its_numbers(first: bool) -> None:
    items: list[Any] = [np.array([1.0, 2.0]), Liar([3.0, 4.0])]
    if not first:
        items.reverse()
    assert holds_bool(items) is False
    got = as_points(items, "points")
    np.testing.assert_array_equal(
        got, [[1.0, 2.0], [3.0, 4.0]] if first else [[3.0, 4.0], [1.0, 2.0]]
    )


def test_a_boolean_array_next_to_a_liar_is_still_refused() -> None:
    items: list[Any] = [np.array([True, False]), Liar([3.0, 4.0])]
    assert holds_bool(items) is True
    with pytest.raises(
        TypeError, match=r"^points must hold real numbers, got an element of type bool"
    ):
        as_points(items, "points")


def test_a_masked_array_liar_is_read_as_an_array_like() -> None:
    liar: Any = MaskedLiar([1.0, 2.0])
    assert isinstance(liar, np.ma.MaskedArray)
    assert not hasattr(liar, "mask")
    np.testing.assert_array_equal(as_array(liar, "mask"), [1.0, 2.0])
    np.testing.assert_array_equal(as_points([liar, liar], "points"), [[1.0, 2.0], [1.0, 2.0]])


def test_a_masked_array_liar_next_to_a_masked_array_is_read_or_refused_by_the_mask() -> None:
    unmasked: list[Any] = [np.ma.array([1.0, 2.0]), MaskedLiar([3.0, 4.0])]
    np.testing.assert_array_equal(as_array(unmasked, "mask"), [[1.0, 2.0], [3.0, 4.0]])
    masked: list[Any] = [np.ma.array([1.0, 2.0], mask=[False, True]), MaskedLiar([3.0, 4.0])]
    with pytest.raises(ValueError, match=r"^mask has masked entries \(in an element of the list\)"):
        as_array(masked, "mask")


class ListLiar:
    """A wrapper of a Python list whose ``__class__`` says ``np.ndarray``."""

    def __init__(self, data: list[Any]) -> None:
        self._data = data

    @property  # type: ignore[misc]
    def __class__(self) -> type:
        return np.ndarray

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        return np.array(self._data, dtype=dtype)


@pytest.mark.parametrize("readings", [[2**64 - 1, -1], [2**63, 0], [-(2**63) - 1, 5]])
def test_integer_readings_of_a_wrapped_list_are_the_lists(readings: list[int]) -> None:
    expected = integer_readings(readings, "ticks")
    assert expected.dtype == object
    got = integer_readings(ListLiar(readings), "ticks")
    assert got.dtype == object
    assert got.tolist() == expected.tolist() == readings
    with pytest.raises(TypeError, match=r"^ticks must hold integer counter readings, got dtype"):
        integer_readings(ListLiar([*readings[:-1], 0.5]), "ticks")


def test_unpack_reads_a_liar_through_its_array_protocol() -> None:
    assert unpack(Liar([1.0, 2.0, 3.0]), "pose") == (1.0, 2.0, 3.0)
    rows = unpack(Liar([[1.0, 2.0], [3.0, 4.0]]), "pairs")
    assert [row.tolist() for row in rows] == [[1.0, 2.0], [3.0, 4.0]]
    assert as_cell(Liar([1, 2]), "cell", (3, 4)) == (1, 2)
