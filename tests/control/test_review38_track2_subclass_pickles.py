"""A tracker subclass whose ``__getstate__`` gives Python's default state copies whole
(review 38, TRACK2).

Since review 37 a tracker keeps its per-path state in one object, the slot
``_state``, and its own ``__getstate__`` spells it out as the attributes of
before (``_line``, ``_progress``, ...). A subclass writing its ``__getstate__``
the ordinary way for a slotted class — Python's default state,
``object.__getstate__(self)`` (or ``navkit``'s ``slot_state``), perhaps with
an entry dropped — hands the base's ``__setstate__`` the ``_state`` object
itself, which it threw away for an idle state: every copy and pickle of the
tracker had no path ("has no path: call set_path(path) first") and lost its
progress. The state's fields are now taken from it, into a state of the copy's
own (a shallow copy does not share the original's progress).

The records' classes handle a user's ``__getstate__`` the same way: taken at
its word, as Python takes it (``navkit._shared.frozen.reduce_record``).
Checked against the code before: every test here fails there.
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D, integrate

PATH = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0]])


class Carrot(FollowTheCarrot):
    __slots__ = ("notes",)

    def __getstate__(self) -> object:
        return object.__getstate__(self)  # Python's default: (None, {slot: value})


class Pursuit(RegulatedPurePursuit):
    """With an instance dict, and a cache left out of copies."""

    def __getstate__(self) -> object:
        instance, slots = object.__getstate__(self)
        instance = {k: v for k, v in instance.items() if k != "cache"}
        return instance, slots


class Waypoints(OnOffTracker):
    __slots__ = ("notes",)

    def __getstate__(self) -> object:
        return object.__getstate__(self)


def _made(cls: Any) -> Any:
    tracker = cls()
    tracker.notes = ["kept"]
    if hasattr(tracker, "__dict__"):
        tracker.cache = "dropped"
    tracker.set_path(PATH, goal_yaw=1.0)
    pose = Pose2D(0.0, 0.05, 0.0)
    for _ in range(100):
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    assert tracker.progress > 0.3
    return tracker, pose


def _follow(tracker: Any, pose: Pose2D, count: int) -> list[Twist2D]:
    """The commands to the goal (at most ``count``)."""
    out = []
    for _ in range(count):
        if tracker.done:
            break
        cmd = tracker.step(pose, 0.05)
        out.append(cmd)
        pose = integrate(pose, cmd, 0.05)
    return out


COPIES = {
    "copy": copy.copy,
    "deepcopy": copy.deepcopy,
    "pickle": lambda t: pickle.loads(pickle.dumps(t)),
}


@pytest.mark.parametrize("how", list(COPIES))
@pytest.mark.parametrize("cls", [Carrot, Pursuit, Waypoints])
def test_a_subclass_giving_pythons_default_state_copies_mid_path(cls: Any, how: str) -> None:
    tracker, pose = _made(cls)
    before = (tracker.progress, tracker.phase, tracker.target_xy)
    twin = COPIES[how](tracker)
    assert type(twin) is cls and twin.notes == ["kept"]
    assert not hasattr(twin, "cache")  # the subclass's own choice, kept
    assert (twin.progress, twin.phase, twin.target_xy, twin.goal_yaw) == (*before, 1.0)
    np.testing.assert_array_equal(twin.path_xy, tracker.path_xy)
    # The same next commands as the original's, to the goal; the original untouched
    # by the copy's steps (a state of its own, also for copy.copy).
    commands = _follow(twin, pose, 2000)
    assert twin.done
    assert (tracker.progress, tracker.phase, tracker.target_xy) == before
    assert commands == _follow(tracker, pose, 2000)
