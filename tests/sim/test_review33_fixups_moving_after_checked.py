"""Review 33 (FIXUPS): ``MovingObstacle.after`` is checked as the plain ``str`` it is stored as.

The check ran with a ``str`` subclass's own ``==`` and hash before the copy to
plain text, so a case-blind subclass's ``"LOOP"`` passed, was stored as
``"LOOP"``, and ``World(moving=[obstacle])`` then raised a bare
``KeyError: 'LOOP'`` naming no argument. Checked: against ``_world.py`` of HEAD
the first test's constructor raises nothing (the record keeps ``'LOOP'``) and the
second gets the ``KeyError``; the last pins what stays as it was.
"""

from __future__ import annotations

from typing import Any

import pytest

from case_blind import CaseBlind
from navkit.sim import MovingObstacle, World


def _make(after: Any) -> MovingObstacle:
    return MovingObstacle(0.2, [(0.0, 0.0), (1.0, 0.0)], [0.0, 1.0], after=after)


@pytest.mark.parametrize("text", ["LOOP", "Stop", "EXTEND"])
def test_a_subclass_equal_to_a_mode_only_by_its_own_eq_is_refused(text: str) -> None:
    message = rf"^after must be 'stop', 'loop' or 'extend', got '{text}'$"
    with pytest.raises(ValueError, match=message):
        _make(CaseBlind(text))
    with pytest.raises(ValueError, match=rf"^after must be .*got '{text}'$"):
        MovingObstacle.scripted(0.2, [(0.0, 0.0), (1.0, 0.0)], speed=1.0, after=CaseBlind(text))  # type: ignore[arg-type]


def test_a_world_never_meets_a_mode_it_has_no_code_for() -> None:
    try:
        obstacle = _make(CaseBlind("LOOP"))
    except ValueError:
        return  # refused where it was given: the fix
    World(moving=[obstacle])  # HEAD: KeyError: 'LOOP'
    pytest.fail(f"after={obstacle.after!r} was accepted")


@pytest.mark.parametrize("text", ["stop", "loop", "extend"])
def test_a_subclass_spelling_a_mode_is_kept_as_plain_text_and_used(text: str) -> None:
    obstacle = _make(CaseBlind(text))
    assert type(obstacle.after) is str and obstacle.after == text
    World(moving=[obstacle])


@pytest.mark.parametrize("value", [5, None, b"loop", "sideways"])
def test_other_values_are_refused_as_before(value: Any) -> None:
    with pytest.raises(ValueError, match=r"^after must be 'stop', 'loop' or 'extend', got "):
        _make(value)
