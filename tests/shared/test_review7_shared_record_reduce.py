"""``reduce_record``: copies of frozen slotted records and subclasses keep read-only arrays."""

from __future__ import annotations

import copy
import pickle
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from navkit._shared.frozen import reduce_record


@dataclass(frozen=True, slots=True)
class _Record:
    values: np.ndarray
    label: str = ""

    def __reduce__(self) -> tuple[Any, ...]:
        return reduce_record(self, ("values",))


@dataclass(frozen=True, slots=True)
class _Tagged(_Record):
    tag: int = 0


class _Plain(_Record):
    pass


def _roundtrip(value: Any) -> Any:
    return pickle.loads(pickle.dumps(value))


@pytest.mark.parametrize("make_copy", [copy.copy, copy.deepcopy, _roundtrip])
def test_copies_keep_class_fields_attributes_and_read_only_arrays(make_copy: Any) -> None:
    tagged = make_copy(_Tagged(np.arange(3.0), "a", 7))
    assert type(tagged) is _Tagged and (tagged.label, tagged.tag) == ("a", 7)
    assert not tagged.values.flags.writeable
    np.testing.assert_array_equal(tagged.values, np.arange(3.0))
    plain = _Plain(np.zeros(2))
    object.__setattr__(plain, "extra", [1, 2])  # (a frozen dataclass refuses setattr)
    copied = make_copy(plain)
    assert type(copied) is _Plain and vars(copied)["extra"] == [1, 2]
    assert not copied.values.flags.writeable


def test_a_shallow_copy_leaves_the_original_array_writeable() -> None:
    original = _Record(np.zeros(2))
    copied = copy.copy(original)
    assert original.values.flags.writeable and not copied.values.flags.writeable
    original.values[0] = 5.0
    assert copied.values[0] == 5.0  # a view: a shallow copy shares the data
    deep = copy.deepcopy(original)
    original.values[1] = 6.0
    assert deep.values[1] == 0.0
