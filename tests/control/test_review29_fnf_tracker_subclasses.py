"""User subclasses of the trackers and the field controller (review 29, FNF).

Pins the Notes their docstrings now carry: a subclass with slots and an instance
dict copies and pickles (every protocol) as itself with what it adds and its
progress, is named by its repr, steps as the base does (bit for bit, the copy
going on as the original), and an override of a public method changes only its
own callers (``PotentialFieldController.__init__`` calls no ``reset``
since review 31). Checked against a scratch copy of src whose ``PathTracker`` lost
its ``__getstate__`` (protocols 0 and 1 then refuse the trackers): the copy
tests fail there.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.geometry import Twist2D

PATH = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 1.5]])

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]


def _subclass(base: type[Any]) -> type[Any]:
    """A subclass with a slot, an instance dict and a counted override of ``step``."""

    def step(self: Any, *args: Any, **kwargs: Any) -> Twist2D:
        self.steps += 1
        out: Twist2D = base.step(self, *args, **kwargs)
        return out

    return type(f"My{base.__name__}", (base,), {"__slots__": ("steps", "__dict__"), "step": step})


TRACKERS = [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit]
# The subclasses live at module level, where pickle finds them by name.
SUBCLASSES = {base: _subclass(base) for base in TRACKERS}
for _cls in SUBCLASSES.values():
    globals()[_cls.__name__] = _cls
    _cls.__module__ = __name__


def _drive(tracker: Any, pose: np.ndarray, count: int) -> tuple[np.ndarray, list[Twist2D]]:
    """``count`` steps of 0.1 s, the pose following the commands (a unicycle)."""
    out = []
    for _ in range(count):
        cmd = tracker.step(pose, 0.1)
        out.append(cmd)
        c, s = np.cos(pose[2]), np.sin(pose[2])
        pose = pose + 0.1 * np.array([cmd.vx * c - cmd.vy * s, cmd.vx * s + cmd.vy * c, cmd.omega])
    return pose, out


@pytest.mark.parametrize("make_copy", COPIES)
@pytest.mark.parametrize("base", TRACKERS, ids=lambda c: c.__name__)
def test_a_tracker_subclass_copies_as_itself_and_steps_as_the_base(
    base: type[Any], make_copy: Callable[[Any], Any]
) -> None:
    cls = SUBCLASSES[base]
    mine, plain = cls(), base()
    mine.steps, mine.note = 0, [1]
    for tracker in (mine, plain):
        tracker.set_path(PATH, goal_yaw=0.5)
    start = np.array([0.0, 0.02, 0.2])  # within goal_tolerance of the first waypoint
    pose, got = _drive(mine, start, 30)
    _, want = _drive(plain, start, 30)
    assert got == want and mine.steps == 30
    assert any(cmd.vx != 0.0 for cmd in got) and any(cmd.omega != 0.0 for cmd in got)
    assert repr(mine).startswith(f"{cls.__name__}(")
    twin = make_copy(mine)
    assert type(twin) is cls and twin.note == [1] and twin.steps == 30
    assert (twin.phase, twin.progress) == (mine.phase, mine.progress)
    _, after_twin = _drive(twin, pose, 20)
    _, after_mine = _drive(mine, pose, 20)
    assert after_twin == after_mine
    assert twin.steps == mine.steps == 50


@pytest.mark.parametrize("base", TRACKERS, ids=lambda c: c.__name__)
def test_set_path_calls_no_public_method(base: type[Any]) -> None:
    tracker = SUBCLASSES[base]()
    tracker.steps = 0
    tracker.set_path(PATH)
    assert tracker.steps == 0


class MyController(PotentialFieldController):
    __slots__ = ("resets",)

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        self.resets = 0

    def reset(self) -> None:
        # The base's __init__ does not call it (documented since review 31).
        self.resets += 1
        super().reset()


@pytest.mark.parametrize("make_copy", COPIES)
def test_a_controller_subclass_copies_as_itself_and_steps_as_the_base(
    make_copy: Callable[[Any], Any],
) -> None:
    mine, plain = MyController(max_speed=0.4), PotentialFieldController(max_speed=0.4)
    assert mine.resets == 0  # not from __init__
    goal = (2.0, 1.0, 0.0)
    obstacles = np.array([[1.0, 0.6]])
    for ctl in (mine, plain):
        for k in range(5):
            ctl.step((0.1 * k, 0.0, 0.0), goal, 0.1, obstacles=obstacles)
    twin = make_copy(mine)
    assert type(twin) is MyController and twin.resets == 0
    assert repr(twin).startswith("MyController(")
    # The copy goes on as the original, and both as the base controller.
    cmds = [
        ctl.step((0.5, 0.0, 0.0), goal, 0.1, obstacles=obstacles) for ctl in (twin, mine, plain)
    ]
    assert cmds[0] == cmds[1] == cmds[2]
    assert cmds[0].vx != 0.0
    twin.reset()
    assert (twin.resets, mine.resets) == (1, 0)
