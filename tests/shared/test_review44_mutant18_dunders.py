"""``record_eq``, ``record_hash`` and ``bounded_repr`` beyond their doctests (review 44, MUTANT18).

The doctests compare and hash one float field; a mutation pass over
``navkit._shared.dunders`` left alive: tuples of the same length compared
equal whatever their items (and of different lengths raised), a float
compared with a string or None raised ``TypeError``, ints and strings
compared unequal to themselves, a record equal to another class's with the
same fields, every tuple field (and every non-NaN value) hashing alike, a
string field's hash raising, and a four-item tuple shown whole.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import pytest

from navkit._shared.dunders import bounded_repr, record_eq, record_hash


@dataclass(frozen=True, eq=False, repr=False)
class Figure:
    value: Any
    __eq__ = record_eq
    __hash__ = record_hash
    __repr__ = bounded_repr


@dataclass(frozen=True, eq=False, repr=False)
class Other:
    value: Any
    __eq__ = record_eq
    __hash__ = record_hash
    __repr__ = bounded_repr


@pytest.mark.parametrize(
    ("a", "b", "equal"),
    [
        ((1.0, 2.0), (1.0, 2.0), True),
        ((1.0, float("nan")), (1.0, float("nan")), True),
        ((1.0, 2.0), (1.0, 3.0), False),  # same length, an item differs
        ((1.0, 2.0), (1.0, 2.0, 3.0), False),  # lengths differ
        ((1.0,), 1.0, False),  # a tuple and a number
        (1.0, (1.0,), False),
        (1.0, "1.0", False),  # a float and a string
        ("1.0", 1.0, False),
        (float("nan"), None, False),
        (3, 3, True),
        ("a", "a", True),
        ("a", "b", False),
        (None, None, True),
    ],
)
def test_fields_compare_item_by_item(a: Any, b: Any, equal: bool) -> None:
    assert (Figure(a) == Figure(b)) is equal
    assert (Figure(b) == Figure(a)) is equal
    if equal:
        assert hash(Figure(a)) == hash(Figure(b))


def test_records_of_other_classes_are_not_equal() -> None:
    assert Figure(1.0) != Other(1.0)
    assert not Figure(1.0) == Other(1.0)  # noqa: SIM201 (the __eq__ itself)


def test_hashes_tell_values_apart() -> None:
    """Not a contract, but a dict of records must not put every one in one bucket:
    tuple fields and plain values hash by their items, strings hash at all."""
    assert len({hash(Figure((i, i + 1.0))) for i in range(10)}) == 10
    assert len({hash(Figure(float(i))) for i in range(10)}) == 10
    assert len({hash(Figure(str(i))) for i in range(10)}) == 10


@pytest.mark.parametrize(
    ("items", "shown"),
    [
        ((1, 2, 3), "(1, 2, 3)"),
        ((1, 2, 3, 4), "(1, 2, ... 1 more ..., 4)"),
        (tuple(range(10)), "(0, 1, ... 7 more ..., 9)"),
    ],
)
def test_tuples_longer_than_three_are_shortened(items: tuple[int, ...], shown: str) -> None:
    assert repr(Figure(items)) == f"Figure(value={shown})"
