"""``frozen``'s table of source shells after a copy that is still held (review 44, MUTANT18).

A record with a user's ``__getstate__`` is copied and pickled through a source
shell kept in a per-thread table (``frozen._SHELLS``), whose entry ``_Forget``
drops once the state is through. Review 33 checked the table after copies that
failed; the surviving mutants here kept the entry after a copy that succeeded,
as long as the pickler's or deep copy's memo (which holds the shell) lived, and
``_forget`` of a record without an entry (or with another record's under its
id) raised or dropped the other's. Also ``rebuild_record``'s renamed fields and
``restore_slots``'s skip of a ``__weakref__`` slot, which no test reached.
"""

from __future__ import annotations

import copy
import io
import pickle
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np
import pytest

from navkit._shared import frozen
from navkit.planning import ConicAttraction


class Stateful(ConicAttraction):
    """A user's ``__getstate__``: what it pickles is its own to say."""

    def __getstate__(self) -> dict[str, Any]:
        return {"note": "kept"}


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_a_finished_pickle_leaves_no_entry_while_its_pickler_lives(protocol: int) -> None:
    record = Stateful((1.0, 2.0))
    pickler = pickle.Pickler(io.BytesIO(), protocol=protocol)
    pickler.dump(record)
    assert pickler.memo  # it holds what it pickled, the source shell among them
    assert id(record) not in frozen._shells()
    assert pickle.loads(pickle.dumps(record, protocol=protocol)).note == "kept"


def test_a_finished_deep_copy_leaves_no_entry_while_its_memo_lives() -> None:
    record = Stateful((1.0, 2.0))
    memo: dict[int, Any] = {}
    copied: Any = copy.deepcopy(record, memo)
    assert copied.note == "kept"
    assert id(record) not in frozen._shells()


def test_forgetting_a_record_without_an_entry_does_nothing() -> None:
    frozen._forget(Stateful((1.0, 2.0)))
    assert not frozen._shells()


def test_forgetting_leaves_another_record_s_entry() -> None:
    """An entry is keyed by ``id``: one under the id that holds another record is
    not the forgotten record's (it cannot happen while the entry holds its record
    alive, but ``_forget`` checks, and a mutant that dropped the check dropped it)."""
    record, other = Stateful((1.0, 2.0)), Stateful((3.0, 4.0))
    table = frozen._shells()
    shell = frozen._Shell(other, (), loaded=False)
    table[id(record)] = shell
    try:
        frozen._forget(record)
        assert table.get(id(record)) is shell
    finally:
        table.pop(id(record), None)


@dataclass(frozen=True, slots=True)
class Renamed:
    """A record whose field ``stamps`` was called ``times`` in older pickles."""

    stamps: Any
    _renamed_fields: ClassVar[Any] = MappingProxyType({"times": "stamps"})


def test_a_renamed_field_loads_from_its_old_name() -> None:
    """``rebuild_record`` maps old names through ``_renamed_fields`` (mutant: the
    mapping read as empty), the array among ``arrays`` under its old name frozen."""
    values = np.arange(3.0)
    record = frozen.rebuild_record(Renamed, {"times": values}, ("times",), None, {})
    assert record.stamps is not values
    np.testing.assert_array_equal(record.stamps, values)
    assert not record.stamps.flags.writeable
    assert values.flags.writeable


class Slotted:
    __slots__ = ("__weakref__", "scratch", "values")
    scratch: Any
    values: Any

    def __setstate__(self, state: Any) -> None:
        frozen.restore_slots(self, state, read_only=("values",))


def test_restore_slots_skips_a_weakref_slot_in_the_state() -> None:
    """A state built from ``__slots__`` may name ``__weakref__``, which cannot be
    set (mutant: the skip dropped, ``AttributeError``)."""
    holder = object.__new__(Slotted)
    holder.__setstate__((None, {"__weakref__": None, "values": np.zeros(2), "scratch": np.ones(2)}))
    assert not holder.values.flags.writeable
    assert holder.scratch.flags.writeable  # not named read-only
