"""FrozenDict: the read-only, picklable mapping behind the records' figures.

``TrialResult.values`` and ``ScenarioResult.summary`` were plain dicts inside
frozen records (``r.summary["x"] = 1`` worked, and a ``copy.copy`` of a record
shared its dict). ``types.MappingProxyType`` cannot be pickled, and the
records travel to worker processes and Dask; ``navkit._shared.frozendict``
holds a small Mapping that behaves as a dict for reading, comparing, printing
and pickling, and refuses every change.
"""

from __future__ import annotations

import copy
import json
import pickle
import struct
from collections.abc import Mapping
from types import MappingProxyType

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared.frozendict import FrozenDict

KEYS = st.text(max_size=4)
FIGURES = st.dictionaries(KEYS, st.floats(allow_nan=False), max_size=8)


@given(FIGURES)
def test_it_reads_compares_and_prints_as_its_dict(items: dict[str, float]) -> None:
    m = FrozenDict(items)
    assert m == items and items == m
    assert m.__ne__(items) is False and items.__ne__(m) is NotImplemented  # reflected
    assert (m != items) is False and (items != m) is False
    assert m == FrozenDict(reversed(list(items.items())))  # order-free, as dicts
    assert m == MappingProxyType(items)  # another Mapping
    assert repr(m) == repr(items) and str(m) == str(items)
    assert list(m) == list(items) and len(m) == len(items)
    assert list(m.keys()) == list(items) and list(m.values()) == list(items.values())
    assert list(m.items()) == list(items.items())
    assert dict(m) == items and {**m} == items
    for key, value in items.items():
        assert key in m and m[key] == value and m.get(key) == value
    assert m.get("absent-key", -1.0) == -1.0 and "absent-key" not in m
    assert isinstance(m, Mapping) and not isinstance(m, dict)
    assert hash(m) == hash(FrozenDict(dict(reversed(list(items.items())))))


@given(FIGURES, st.text(max_size=4), st.floats(allow_nan=False))
def test_a_different_item_makes_it_unequal(items: dict[str, float], key: str, value: float) -> None:
    other = {**items, key: value}
    assert (FrozenDict(items) == other) == (items == other)
    assert (FrozenDict(items) == FrozenDict(other)) == (items == other)
    assert (FrozenDict(items) != other) == (items != other)


def test_it_is_equal_to_no_other_kind_of_object() -> None:
    m = FrozenDict({"a": 1.0})
    assert m != [("a", 1.0)] and m != {"a"} and m != 1.0 and m is not None
    assert m.__eq__(("a",)) is NotImplemented


@given(FIGURES)
def test_every_change_is_refused_with_a_clear_error(items: dict[str, float]) -> None:
    m = FrozenDict(items)
    refused = r"FrozenDict is read-only: cannot set 'x' \(edit a copy: dict\(\.\.\.\)\)"
    with pytest.raises(TypeError, match=refused):
        m["x"] = 1.0
    with pytest.raises(TypeError, match=r"FrozenDict is read-only: cannot delete 'x'"):
        del m["x"]
    with pytest.raises(AttributeError, match="read-only: cannot set '_data'"):
        m._data = {}  # type: ignore[misc]
    with pytest.raises(AttributeError, match="read-only: cannot delete '_data'"):
        del m._data
    for name in ("update", "pop", "popitem", "clear", "setdefault"):
        assert not hasattr(m, name)
    with pytest.raises(AttributeError):
        m.mapping_attribute = 1  # type: ignore[attr-defined]
    assert m == items  # nothing changed


def test_the_views_it_hands_out_cannot_change_it() -> None:
    m = FrozenDict({"a": 1.0})
    for view in (m.keys(), m.values(), m.items()):
        assert isinstance(view.mapping, MappingProxyType)  # type: ignore[attr-defined]
        with pytest.raises(TypeError):
            view.mapping["a"] = 2.0  # type: ignore[attr-defined]
    assert m == {"a": 1.0}


def test_it_copies_its_source_so_later_changes_to_the_source_do_not_reach_it() -> None:
    source = {"a": 1.0}
    m = FrozenDict(source)
    source["a"] = 2.0
    source["b"] = 3.0
    assert m == {"a": 1.0}
    assert FrozenDict(a=1.0, b=2.0) == {"a": 1.0, "b": 2.0} == FrozenDict([("a", 1.0), ("b", 2.0)])
    assert FrozenDict() == {} and not FrozenDict()


def test_wrap_takes_the_dict_itself() -> None:
    data = {"a": 1.0}
    m = FrozenDict.wrap(data)
    data["a"] = 5.0  # the caller's promise broken: shows that no copy is made
    assert m["a"] == 5.0


def test_it_is_hashable_exactly_when_its_values_are() -> None:
    assert hash(FrozenDict({"a": 1.0, "b": 2.0})) == hash(FrozenDict({"b": 2.0, "a": 1.0}))
    assert len({FrozenDict({"a": 1.0}), FrozenDict({"a": 1.0}), FrozenDict({"a": 2.0})}) == 2
    with pytest.raises(TypeError, match="unhashable type: 'list'"):
        hash(FrozenDict({"a": [1.0]}))


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
@given(items=st.dictionaries(KEYS, st.floats(), max_size=8))
def test_it_pickles_under_every_protocol(protocol: int, items: dict[str, float]) -> None:
    m = FrozenDict(items)
    back = pickle.loads(pickle.dumps(m, protocol))
    assert type(back) is FrozenDict
    # As a dict pickles, bit for bit (protocol 0 writes floats as text: a NaN loses its sign).
    plain = pickle.loads(pickle.dumps(items, protocol))
    for key, value in plain.items():
        assert struct.pack("<d", back[key]) == struct.pack("<d", value)
    assert list(back) == list(items)
    if protocol > 0:  # and the same as the original, NaN and the sign of zero included
        for key, value in items.items():
            assert struct.pack("<d", back[key]) == struct.pack("<d", value)
    with pytest.raises(TypeError, match="read-only"):
        back["x"] = 1.0


def test_copies_are_the_same_read_only_items() -> None:
    inner = [1.0]
    m = FrozenDict({"a": inner})
    assert copy.copy(m) is m  # nothing in either can change
    deep = copy.deepcopy(m)
    assert type(deep) is FrozenDict and deep == m and deep["a"] is not inner
    inner.append(2.0)
    assert deep["a"] == [1.0]
    pair = copy.deepcopy((m, m))
    assert pair[0] is pair[1]  # deepcopy's memo kept


def test_json_needs_a_dict_as_for_every_other_mapping() -> None:
    m = FrozenDict({"a": 1.0})
    with pytest.raises(TypeError, match="not JSON serializable"):
        json.dumps(m)
    assert json.dumps(dict(m)) == json.dumps({"a": 1.0})


def test_copy_and_union_give_editable_plain_dicts_and_leave_it_unchanged() -> None:
    # What a dict's user writes to edit figures (r.summary.copy(), r.summary | {...}).
    frozen = FrozenDict({"a": 1.0, "b": 2.0})
    edited = frozen.copy()
    edited["a"] = 5.0
    assert type(edited) is dict and frozen["a"] == 1.0
    merged = frozen | {"b": 3.0, "c": 4.0}
    assert type(merged) is dict and merged == {"a": 1.0, "b": 3.0, "c": 4.0}
    left = {"b": 3.0, "c": 4.0} | frozen
    assert type(left) is dict and left == {"a": 1.0, "b": 2.0, "c": 4.0}
    assert frozen == {"a": 1.0, "b": 2.0}
    with pytest.raises(TypeError):
        frozen | [("a", 1)]  # type: ignore[operator]
