"""A user's ``__reduce__`` on a subclass of a navkit record is called (review 37).

Review 36 gave the records without a ``__reduce__`` of their own (``Compass``,
``Metrics``, ``Event``, the readings, ...) a ``__reduce_ex__`` that copies and
pickles a subclass through ``reduce_record`` (what the subclass adds is kept).
``copy`` and ``pickle`` call ``__reduce_ex__`` first, and Python's own calls a
class's ``__reduce__`` when one is defined; navkit's did not, so a user's
subclass defining ``__reduce__`` (to pickle as something else, to drop a handle)
had it ignored in every copy and pickle. It is called now, as for the records
that have a ``__reduce__`` (``Pose2D``): checked for every such record, by copy,
deep copy and every pickle protocol.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from collections.abc import Callable
from typing import Any

import pytest

from test_review21_pickle_public_classes import _INSTANCES

#: The records given review 36's __reduce_ex__ (none of their own), by name.
RECORDS: dict[str, Callable[[], Any]] = {}
for _name, _make in _INSTANCES.items():
    _obj = _make()
    if (
        dataclasses.is_dataclass(_obj)
        and type(_obj).__name__ == _name
        and type(_obj).__reduce__ is object.__reduce__
        and type(_obj).__reduce_ex__ is not object.__reduce_ex__
    ):
        RECORDS[_name] = _make

HOWS: dict[str, Callable[[Any], Any]] = {
    "copy": copy.copy,
    "deepcopy": copy.deepcopy,
    **{
        f"pickle{p}": (lambda o, p=p: pickle.loads(pickle.dumps(o, protocol=p)))
        for p in range(pickle.HIGHEST_PROTOCOL + 1)
    },
}


def _as_base(cls: type, values: dict[str, Any]) -> Any:
    """What the subclass's ``__reduce__`` rebuilds: the record itself, marked."""
    record = cls(**values)
    return ("rebuilt by the user's __reduce__", record)


def _subclass(base: type) -> type:
    """A subclass with a ``__reduce__`` of its own (a module-level name, for pickle)."""
    name = f"Reducing{base.__name__}"
    if name not in globals():

        def __reduce__(self: Any) -> tuple[Any, ...]:
            fields = dataclasses.fields(self)
            return (_as_base, (base, {f.name: getattr(self, f.name) for f in fields if f.init}))

        body = {"__reduce__": __reduce__, "__module__": __name__, "__qualname__": name}
        globals()[name] = type(name, (base,), body)
    sub: type = globals()[name]
    return sub


def test_the_records_are_found() -> None:
    assert {"Compass", "Metrics", "Event"} <= set(RECORDS)


@pytest.mark.parametrize("how", sorted(HOWS))
@pytest.mark.parametrize("name", sorted(RECORDS))
def test_a_subclass_reduce_is_called(name: str, how: str) -> None:
    plain = RECORDS[name]()
    values = {f.name: getattr(plain, f.name) for f in dataclasses.fields(plain) if f.init}
    obj = _subclass(type(plain))(**values)
    marker, rebuilt = HOWS[how](obj)
    assert marker == "rebuilt by the user's __reduce__"
    assert type(rebuilt) is type(plain)
    # The record itself still pickles and copies as before.
    assert type(HOWS[how](plain)) is type(plain)
