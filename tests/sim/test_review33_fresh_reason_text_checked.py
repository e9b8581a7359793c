"""Review 33 (FRESH): an end reason is checked as the plain ``str`` it is stored as.

Review 32 stored ``Event.kind`` and ``Metrics.reason`` as plain ``str`` (a
copy of a ``str`` subclass's characters), but checked them against the reasons
before the copy, with the subclass's own ``==``: a case-blind subclass's
``"COLLISION"`` passed and was stored as ``"COLLISION"``, no reason at all.
And an array of several texts reached the check too, raising NumPy's "truth
value of an array is ambiguous", which names no argument. Checked: against
``_trace.py`` of HEAD the first test builds both records (no error) and the
third raises NumPy's message; the second and fourth pin what stays as it was.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from case_blind import CaseBlind
from navkit.sim import Event, Metrics


def _metrics(reason: Any) -> Metrics:
    return Metrics(False, reason, 1.0, *[math.nan] * 6, 0.5, 0, 1.0)


def test_a_str_subclass_equal_to_a_reason_only_by_its_own_eq_is_refused() -> None:
    with pytest.raises(ValueError, match=r"^kind must be one of .*got 'COLLISION'$"):
        Event(1.5, CaseBlind("COLLISION"), "touched")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"^reason must be one of .*got 'TIMEOUT'$"):
        _metrics(CaseBlind("TIMEOUT"))


def test_a_subclass_spelling_a_reason_is_kept_as_plain_text() -> None:
    event = Event(1.5, CaseBlind("collision"), "touched")  # type: ignore[arg-type]
    assert type(event.kind) is str and event.kind == "collision"
    assert type(_metrics(CaseBlind("timeout")).reason) is str


@pytest.mark.parametrize("make", [lambda v: Event(1.5, v, "m"), _metrics], ids=["Event", "Metrics"])
def test_an_array_of_texts_is_refused_naming_the_field(make: Any) -> None:
    with pytest.raises(TypeError, match=r"^(kind|reason) must be a str, got ndarray$"):
        make(np.array(["collision", "timeout"]))


@pytest.mark.parametrize("value", [5, None, "done", b"timeout"])
def test_other_values_are_refused_as_before(value: Any) -> None:
    """No str and equal to no reason: a ValueError quoting it, as before review 33."""
    with pytest.raises(ValueError, match=r"^kind must be one of "):
        Event(1.5, value, "m")
