"""FrozenDict against dict, operation by operation (review 22, fresh eyes).

Review 21's ``FrozenDict`` (``TrialResult.values``, ``ScenarioResult.summary``)
is to read as a dict does. ``reversed(m)`` raised ``TypeError`` ("not
reversible"), where a dict gives its keys last first (``Mapping`` has no
``__reversed__``). Every reading operation is now compared with the dict's on
random figures, and the spellings that give an editable dict (``copy()``,
``|``, ``|=``) are checked to leave the original as it was.
"""

from __future__ import annotations

import copy
import json
import pickle

from hypothesis import given
from hypothesis import strategies as st

from navkit._shared.frozendict import FrozenDict

FIGURES = st.dictionaries(st.text(max_size=4), st.floats(allow_nan=False), max_size=8)


@given(FIGURES)
def test_it_reverses_as_its_dict(items: dict[str, float]) -> None:
    m = FrozenDict(items)
    assert list(reversed(m)) == list(reversed(items))
    assert list(reversed(m.keys())) == list(reversed(items.keys()))
    assert list(reversed(m.items())) == list(reversed(items.items()))
    assert list(reversed(m.values())) == list(reversed(items.values()))


@given(FIGURES, FIGURES)
def test_merges_give_the_dicts_merges_and_leave_it_alone(
    items: dict[str, float], other: dict[str, float]
) -> None:
    m = FrozenDict(items)
    for merged, expected in (
        (m | other, items | other),
        (other | m, other | items),
        (m | FrozenDict(other), items | other),
    ):
        assert type(merged) is dict and merged == expected
        assert list(merged) == list(expected)  # the dict's key order too
    kept = m
    kept |= other  # rebinds to a new dict, as | gives one
    assert type(kept) is dict and kept == items | other
    edited = dict(other)
    edited |= m
    assert edited == other | items
    assert m == items and type(m) is FrozenDict


@given(FIGURES)
def test_copies_pickles_and_json_keep_its_items_and_order(items: dict[str, float]) -> None:
    m = FrozenDict(items)
    for twin in (
        copy.copy(m),
        copy.deepcopy(m),
        *(pickle.loads(pickle.dumps(m, protocol)) for protocol in range(6)),
    ):
        assert type(twin) is FrozenDict
        assert twin == m and list(twin.items()) == list(items.items())
        assert hash(twin) == hash(m)
    assert json.loads(json.dumps(dict(m))) == json.loads(json.dumps(items))
    edit = m.copy()
    edit["new key"] = 1.0
    assert "new key" not in m
