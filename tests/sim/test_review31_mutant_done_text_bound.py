"""The refused ``done`` number is shown whole up to 40 characters (review 31, mutants).

``done_flag`` bounds the number it prints at 40 characters (``_text``: beyond,
the first and last 18 around ``...``), so that a 4300-digit int cannot make the
message itself fail. No test pinned the bound: ``<`` for ``<=`` and a bound of
39 or 41 all passed. Checked: each test fails on those three mutants of
``_done.py`` and passes on HEAD.
"""

from __future__ import annotations

import re

import pytest

from navkit.sim._done import done_flag


def _message(value: object) -> str:
    with pytest.raises(ValueError, match=r"tracker\.done must be true or false") as info:
        done_flag(value, "tracker.done")
    return str(info.value)


@pytest.mark.parametrize("digits", [39, 40])
def test_a_number_of_at_most_40_characters_is_shown_whole(digits: int) -> None:
    text = "7" + "1" * (digits - 1)
    assert f"got int {text} (a number" in _message(int(text))


@pytest.mark.parametrize("digits", [41, 42, 300])
def test_a_longer_number_shows_its_first_and_last_18_characters(digits: int) -> None:
    text = "7" + "2" * (digits - 2) + "9"
    shown = re.search(r"got int (\S+) \(a number", _message(int(text)))
    assert shown is not None
    assert shown.group(1) == f"{text[:18]}...{text[-18:]}"
