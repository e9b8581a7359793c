"""``frozen``'s table of source shells after a copy that is still held (review 44, MUTANT18).

A record with a user's ``__getstate__`` is copied and pickled through a source
shell kept in a per-thread table (``frozen._SHELLS``), whose entry ``_Forget``
drops once the state is through. Review 33 checked the table after copies that
failed; the surviving mutants here kept the entry after a copy that succeeded,
as long as the pickler's or deep copy's memo (which holds the shell) lived, and
``_forget`` of a record without an entry (or with another record's under its
id) raised or dropped the other's.
"""

from __future__ import annotations

import copy
import io
import pickle
from typing import Any

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
    copied = copy.deepcopy(record, memo)
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
