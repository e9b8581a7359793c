"""Review 33 (FIXUPS): figure names are stored as plain ``str``.

``TrialResult.values`` and ``ScenarioResult.summary`` kept an ``np.str_`` key as
it was given (a name read from an array), and NumPy 2 prints it as
``np.str_('error')``: ``TrialResult(..., {np.str_("error"): 0.02})`` showed
``values={np.str_('error'): 0.02}``. Checked: against ``_scenario.py`` of HEAD
the first three tests fail (the key's type is ``np.str_``, the repr shows it,
an older pickle keeps it, and two keys spelling the same text left one figure
silently); the last pins what stays as it was.
"""

from __future__ import annotations

import pickle
from typing import Any

import numpy as np
import pytest

from case_blind import CaseBlind
from navkit._shared.frozendict import FrozenDict
from navkit.sim import ScenarioResult, Trial, TrialResult


def _trial(values: Any) -> TrialResult:
    return TrialResult(Trial("a", 0, 0, 1), values)


def _scenario(summary: Any) -> ScenarioResult:
    return ScenarioResult("x", 0, (), (), summary)


@pytest.mark.parametrize(
    ("make", "field"), [(_trial, "values"), (_scenario, "summary")], ids=["values", "summary"]
)
def test_numpy_text_keys_are_stored_and_printed_as_plain_str(make: Any, field: str) -> None:
    record = make({np.str_("error"): 0.02, CaseBlind("Time"): 1.5})
    figures = getattr(record, field)
    assert [type(key) for key in figures] == [str, str]
    assert figures == {"error": 0.02, "Time": 1.5}
    assert f"{field}={{'error': 0.02, 'Time': 1.5}}," in repr(record)


@pytest.mark.parametrize(
    ("make", "field"), [(_trial, "values"), (_scenario, "summary")], ids=["values", "summary"]
)
def test_an_older_pickle_with_numpy_keys_restores_plain_keys(make: Any, field: str) -> None:
    record = make({"error": 0.02})
    # What a record pickled before this review held.
    object.__setattr__(record, field, FrozenDict.wrap({np.str_("error"): 0.02}))
    restored = pickle.loads(pickle.dumps(record))
    assert [type(key) for key in getattr(restored, field)] == [str]
    assert getattr(restored, field) == {"error": 0.02}


def test_two_keys_spelling_the_same_text_are_refused() -> None:
    with pytest.raises(ValueError, match=r"^values has the key 'Error' twice$"):
        _trial({CaseBlind("Error"): 1.0, "Error": 2.0})


@pytest.mark.parametrize("key", [1, b"error", None])
def test_other_keys_are_refused_as_before(key: Any) -> None:
    with pytest.raises(TypeError, match=r"^values keys must be str, got "):
        _trial({key: 1.0})
