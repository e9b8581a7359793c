"""A failed copy or pickle of a user-state record leaves no ``_SHELLS`` entry (review 33).

A record class with a user's ``__getstate__`` or ``__setstate__`` is copied
through a per-thread table of source shells (``frozen._SHELLS``), whose entry
the copy drops once the state is through. A copy that failed midway (the
user's ``__getstate__`` raising, or an item of the state that cannot be
copied or pickled) never got there: the entry, and the record it holds,
stayed until that record was copied again. Checked: against ``frozen.py`` of
HEAD every case here but ``copy.copy`` leaves one entry.
"""

from __future__ import annotations

import contextlib
import copy
import gc
import pickle
import threading
import weakref
from collections.abc import Callable
from typing import Any

import pytest

from navkit._shared import frozen
from navkit.planning import ConicAttraction

OPS: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.dumps(obj, protocol=protocol)
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]
IDS = ["copy", "deepcopy", *(f"pickle{p}" for p in range(pickle.HIGHEST_PROTOCOL + 1))]


class Refusing(ConicAttraction):
    """A ``__getstate__`` that raises (a resource it will not hand over)."""

    def __getstate__(self) -> dict[str, Any]:
        raise RuntimeError("no state today")


class Restoring(ConicAttraction):
    """A ``__setstate__`` alone: its state is Python's default, a lock in it."""

    def __setstate__(  # type: ignore[override]
        self, state: tuple[dict[str, Any] | None, dict[str, Any]]
    ) -> None:
        instance, slots = state
        for name, value in slots.items():
            object.__setattr__(self, name, value)
        self.__dict__.update(instance or {})


def _fails(
    op: Callable[[Any], Any], record: Any, error: type[Exception] | tuple[type[Exception], ...]
) -> None:
    # No `as`: a traceback kept would hold the copy's stack, as a caller's would.
    with pytest.raises(error):
        op(record)


@pytest.mark.parametrize("op", OPS, ids=IDS)
def test_a_getstate_that_raises_leaves_no_entry(op: Callable[[Any], Any]) -> None:
    record = Refusing((1.0, 2.0))
    _fails(op, record, RuntimeError)
    assert not frozen._shells()
    # The record is not kept alive by the table either.
    ref = weakref.ref(record)
    del record
    gc.collect()
    assert ref() is None


@pytest.mark.parametrize("op", OPS[1:], ids=IDS[1:])
def test_a_state_item_that_cannot_be_copied_leaves_no_entry(op: Callable[[Any], Any]) -> None:
    record = Restoring((1.0, 2.0))
    record.lock = threading.Lock()  # type: ignore[attr-defined]
    # Protocols 0 and 1 raise a PicklingError, the others a TypeError.
    _fails(op, record, (TypeError, pickle.PicklingError))
    assert not frozen._shells()
    # A later copy works as before, and keeps nothing either.
    del record.lock  # type: ignore[attr-defined]
    twin = copy.deepcopy(record)
    assert type(twin) is Restoring and twin is not record
    assert not frozen._shells()


def test_a_failed_copy_in_one_thread_leaves_other_threads_tables_alone() -> None:
    record = Refusing((1.0, 2.0))
    left: list[int] = []

    def work() -> None:
        with contextlib.suppress(RuntimeError):
            copy.deepcopy(record)
        left.append(len(frozen._shells()))

    thread = threading.Thread(target=work)
    thread.start()
    thread.join()
    assert left == [0] and not frozen._shells()
