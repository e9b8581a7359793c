"""A user's ``__getstate__`` dict of exactly two fields restores (review 31, mutants).

Without a ``__setstate__`` of the user's, navkit restores a state as Python
does: a dict, or a pair ``(dict or None, dict)`` — a pair only when the state
is a ``tuple`` of two. The tests of review 30 used states of three or more
fields, so reading *any* state of length 2 as a pair passed them; then a dict
of two fields (``EncoderReading``'s, ``BehaviourTarget``'s) was unpacked into
its two keys and refused ("got a str in it"). Also pinned: the words of the
frozen guard's refusals ("set" an attribute, "assign to" a field). Checked: the
first test fails on the ``or`` mutant of ``isinstance(state, tuple) and
len(state) == 2`` in ``frozen.py``, the second on the ``!=`` mutant of
``verb == "assign to"``, the third (a subclass's private slot, which Python
mangles, copies whole) on the mutant that mangles only ``__x__`` names; all
pass on HEAD.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.behaviours import BehaviourTarget
from navkit.geometry import Pose2D
from navkit.sim import EncoderReading

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)),
]


class Reading(EncoderReading):
    def __getstate__(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


class Target(BehaviourTarget):
    def __getstate__(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_a_two_field_dict_state_restores_each_field(duplicate: Callable[[Any], Any]) -> None:
    reading = Reading(1.5, np.array([3, 4]))
    again = duplicate(reading)
    assert type(again) is Reading and again.stamp == 1.5
    np.testing.assert_array_equal(again.ticks, [3, 4])
    target = Target([1.0, 2.0], [[0.0, 1.0]])
    moved = duplicate(target)
    assert type(moved) is Target
    np.testing.assert_array_equal(moved.goal_xy, [1.0, 2.0])
    np.testing.assert_array_equal(moved.obstacles_xy, [[0.0, 1.0]])


@pytest.mark.parametrize(
    ("act", "words"),
    [
        (lambda obj: setattr(obj, "note", 1), "cannot set attribute 'note'"),
        (lambda obj: delattr(obj, "note"), "cannot delete attribute 'note'"),
        (lambda obj: setattr(obj, "stamp", 2.0), "cannot assign to field 'stamp'"),
        (lambda obj: delattr(obj, "stamp"), "cannot delete field 'stamp'"),
    ],
    ids=["set", "delete", "assign-field", "delete-field"],
)
def test_a_frozen_record_names_what_was_refused(act: Callable[[Any], None], words: str) -> None:
    # frozen_setattr's messages: an attribute is "set" (Python's word for slots and
    # dicts), a field "assigned to" (dataclasses' word); no test pinned "set" until
    # the ``!=`` mutant of ``verb == "assign to"`` in frozen.py passed the suite.
    reading = EncoderReading(1.5, np.array([3, 4]))
    with pytest.raises(dataclasses.FrozenInstanceError, match=words) as info:
        act(reading)
    assert "EncoderReading is frozen" in str(info.value)


class Tagged(Pose2D):
    """A user's subclass with a private slot (``_Tagged__tag``) and a dunder-named one."""

    __slots__ = ("__note__", "__tag")

    def tag(self) -> str:
        return str(self.__tag)

    def set_tag(self, tag: str) -> None:
        self.__tag = tag


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_a_subclass_private_slot_is_copied(duplicate: Callable[[Any], Any]) -> None:
    pose = Tagged(1.0, 2.0, 0.5)
    pose.set_tag("kept")
    pose.__note__ = "also"  # type: ignore[attr-defined]
    again = duplicate(pose)
    assert (again.x, again.y, again.theta) == (1.0, 2.0, 0.5)
    assert again.tag() == "kept" and again.__note__ == "also"
