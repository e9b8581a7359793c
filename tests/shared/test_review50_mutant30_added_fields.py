"""Review 50 (MUTANT30): a subclass's ``_added_fields`` and its bases', in their order.

``fill_added_fields`` and ``restore_read_only`` read the ``_added_fields`` of a
record's class and of its bases, bases' first (each in the order its fields
were added). Two mutants of that order survived the suite: the subclass's own
mapping alone (its bases' fields then had no default: a list shorter than the
fields by the bases' added ones was refused), and the subclass's fields
counted before its bases' (a list from before the subclass's field, but after
the base's, set the subclass's field from the base's value). A list is read
into the fields that existed then, wherever the added ones stand (a
subclass's own older field follows its base's added ones). A subclass that
gives a base's added field a default of its own overrides the base's.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from navkit._shared.frozen import (
    fill_added_fields,
    rebuild_from_state,
    rebuild_record,
    restore_read_only,
)


@dataclass(frozen=True, slots=True)
class _Reading:
    """A record that gained ``unit`` (default "m"), then ``scale`` (2 x value)."""

    value: float
    unit: str = "m"
    scale: float = 1.0

    _added_fields = MappingProxyType({"unit": lambda r: "m", "scale": lambda r: 2.0 * r.value})

    def __setstate__(self, state: Any) -> None:
        restore_read_only(self, state, ())


@dataclass(frozen=True, slots=True)
class _Noted(_Reading):
    """A subclass whose own field ``note`` came after its base's two."""

    note: str = "n"

    _added_fields = MappingProxyType({"note": lambda r: f"late {r.unit}"})

    # Its own (the dataclass decorator would give a slotted subclass a plain one).
    __setstate__ = _Reading.__setstate__


@dataclass(frozen=True, slots=True)
class _Feet(_Reading):
    """A subclass whose records made before ``unit`` were in feet."""

    _added_fields = MappingProxyType({"unit": lambda r: "ft"})

    __setstate__ = _Reading.__setstate__


@dataclass(frozen=True, slots=True)
class _Tagged(_Reading):
    """A subclass whose field ``tag`` came with it, before its base's ``unit`` and
    ``scale``: the fields added are not the last ones."""

    tag: str = "t"

    __setstate__ = _Reading.__setstate__


def _restored(cls: type, state: list[Any]) -> Any:
    record = object.__new__(cls)
    record.__setstate__(state)
    return record


def test_a_subclass_list_of_each_age_gets_its_bases_and_its_own_added_fields() -> None:
    # The bases' added fields first, then the subclass's: a list of each age holds
    # the fields that existed then, in order.
    assert _restored(_Noted, [4.0]) == _Noted(4.0, "m", 8.0, "late m")
    assert _restored(_Noted, [4.0, "s"]) == _Noted(4.0, "s", 8.0, "late s")
    assert _restored(_Noted, [4.0, "s", 0.5]) == _Noted(4.0, "s", 0.5, "late s")
    assert _restored(_Noted, [4.0, "s", 0.5, "x"]) == _Noted(4.0, "s", 0.5, "x")


def test_fields_added_to_a_base_are_left_out_where_they_stand() -> None:
    # A list from before the base's two fields: the subclass's own field follows
    # the value, not the added fields' places.
    assert _restored(_Tagged, [4.0, "x"]) == _Tagged(4.0, "m", 8.0, "x")
    assert _restored(_Tagged, [4.0, "s", "x"]) == _Tagged(4.0, "s", 8.0, "x")


def test_a_subclass_default_for_a_base_field_overrides_the_base_one() -> None:
    assert _restored(_Feet, [2.0]) == _Feet(2.0, "ft", 4.0)
    assert rebuild_record(_Feet, {"value": 2.0}, (), None, {}) == _Feet(2.0, "ft", 4.0)
    assert rebuild_from_state(_Feet, (None, {"value": 2.0}), ()) == _Feet(2.0, "ft", 4.0)
    # The base's own records keep the base's default.
    assert _restored(_Reading, [2.0]) == _Reading(2.0, "m", 4.0)
    record = object.__new__(_Feet)
    object.__setattr__(record, "value", 3.0)
    object.__setattr__(record, "scale", 0.5)
    fill_added_fields(record)
    assert (record.unit, record.scale) == ("ft", 0.5)
