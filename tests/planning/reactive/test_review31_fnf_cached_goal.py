"""A user's cached_property is not carried stale into a field moved to a new goal (review 31, FNF).

``AttractiveField.with_goal`` (which the controller calls every step) copies what a
user's subclass adds, its instance ``__dict__`` included: the value a
:func:`functools.cached_property` had computed from the old goal came along, so
the moved field answered for the old goal (5.0 for the distance of (3, 4) from
the origin where the goal had moved to (0, 1)). The moved field now computes it
again. Checked against the source before the fix: the first two tests failed
there (5.0 != 1.0). Copies, pickles and ``dataclasses.replace`` of records keep
(or recompute) values that still hold: pinned too.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
import pickle
from typing import Any

import numpy as np
import pytest

from navkit.behaviours import GameState
from navkit.control import PotentialFieldController
from navkit.planning import ConicAttraction


class Reach(ConicAttraction):
    """A cone that also knows (cached) how far its goal lies from the origin."""

    @functools.cached_property
    def goal_norm(self) -> float:
        return math.hypot(*self.goal_xy.tolist())

    @functools.cached_property
    def doubled_gain(self) -> float:  # depends on a parameter only
        return 2.0 * self.m


def test_with_goal_computes_a_cached_property_again() -> None:
    field = Reach((3.0, 4.0), m=1.5)
    assert field.goal_norm == 5.0 and field.doubled_gain == 3.0
    moved = field.with_goal((0.0, 1.0))
    assert moved.goal_norm == 1.0
    assert moved.doubled_gain == 3.0
    assert field.goal_norm == 5.0  # the original keeps its own


class Noted(Reach):
    """The same, with another attribute in its ``__dict__`` (kept as before)."""

    def __init__(self, goal_xy: Any, note: str) -> None:
        super().__init__(goal_xy)
        self.note = note


def test_with_goal_keeps_other_instance_attributes() -> None:
    field = Noted((3.0, 4.0), "mine")
    assert field.goal_norm == 5.0
    moved = field.with_goal((6.0, 8.0))
    assert moved.note == "mine" and moved.goal_norm == 10.0
    assert "goal_norm" not in vars(moved) or vars(moved)["goal_norm"] == 10.0


class Seen(Reach):
    """A field whose force reads its cached goal distance (as a controller steps it)."""

    def _force(self, pts: Any) -> Any:
        return ConicAttraction._force(self, pts) * (1.0 + 0.0 * self.goal_norm)


def test_the_controller_steps_a_field_with_a_cached_property() -> None:
    ctl = PotentialFieldController(Seen((0.0, 0.0)))
    plain = PotentialFieldController(ConicAttraction((0.0, 0.0)))
    for goal in ((1.0, 0.0, 0.0), (0.0, 2.0, 0.0)):
        assert ctl.step((0.0, 0.0, 0.0), goal, 0.1) == plain.step((0.0, 0.0, 0.0), goal, 0.1)


@pytest.mark.parametrize(
    "make_copy",
    [copy.copy, copy.deepcopy, lambda f: pickle.loads(pickle.dumps(f))],
    ids=["copy", "deepcopy", "pickle"],
)
def test_copies_keep_a_value_that_still_holds(make_copy: Any) -> None:
    field = Reach((3.0, 4.0))
    assert field.goal_norm == 5.0
    twin = make_copy(field)
    assert twin.goal_norm == 5.0 and np.array_equal(twin.goal_xy, field.goal_xy)


class Ball(GameState):
    """A user's game state with a cached distance from the robot to the ball."""

    @functools.cached_property
    def ball_distance(self) -> float:
        return float(np.hypot(*(self.ball_xy - self.robot_xy)))


def test_replace_on_a_record_computes_a_cached_property_again() -> None:
    state = Ball(robot_xy=(0.0, 0.0), ball_xy=(3.0, 4.0), own_goal_xy=(-4.5, 0.0),
                 opponent_goal_xy=(4.5, 0.0))  # fmt: skip
    assert state.ball_distance == 5.0
    moved = dataclasses.replace(state, ball_xy=(0.0, 1.0), has_ball=None)
    assert moved.ball_distance == 1.0
