"""Soccer records: subclass copies, the support midpoint, exact range errors.

* ``copy.copy``, ``copy.deepcopy`` and pickling of a subclass of
  :class:`BehaviourTarget` or :class:`GameState` dropped the subclass's own
  attributes (the dataclass's pickle state holds the fields alone), and a
  subclass that is a slotted frozen dataclass came back with writable arrays.
* :func:`support` halved the ball and the own goal before adding them, which
  loses the last bit of sub-normal halves: the midpoint of 5e-324 and 5e-324
  came out 0. Its goal is now the correctly rounded midpoint.
* ``possession_radius`` errors printed the refused value with ``:g``, which
  rounds ``1e6 + 1e-6`` to ``1e+06``, inside the range.
"""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.behaviours import BehaviourTarget, GameState, support


class MyTarget(BehaviourTarget):
    pass


class MyState(GameState):
    pass


def _state(cls: type[GameState] = GameState, **kw: Any) -> GameState:
    args: dict[str, Any] = {
        "robot_xy": (0.0, 0.0),
        "ball_xy": (1.0, 0.0),
        "own_goal_xy": (-4.5, 0.0),
        "opponent_goal_xy": (4.5, 0.0),
        "opponents_xy": [[1.1, 0.0], [np.nan, np.nan]],
    }
    args.update(kw)
    return cls(**args)


COPIES: list[tuple[str, Callable[[Any], Any]]] = [
    ("copy", copy.copy),
    ("deepcopy", copy.deepcopy),
    ("pickle", lambda obj: pickle.loads(pickle.dumps(obj))),
]


@pytest.mark.parametrize(("how", "clone"), COPIES, ids=[c[0] for c in COPIES])
@pytest.mark.parametrize(
    "build",
    [lambda: MyTarget((1.0, 0.0), [[2.0, 1.0], [np.nan, np.nan]]), lambda: _state(MyState)],
    ids=["BehaviourTarget", "GameState"],
)
def test_a_subclass_copies_whole(
    build: Callable[[], Any], how: str, clone: Callable[[Any], Any]
) -> None:
    original = build()
    object.__setattr__(original, "note", ["kept"])
    out = clone(original)
    assert type(out) is type(original)
    assert out.note == ["kept"]
    for name in ("goal_xy", "obstacles_xy", "robot_xy", "ball_xy", "opponents_xy"):
        if hasattr(original, name):
            array = getattr(out, name)
            assert np.array_equal(array, getattr(original, name), equal_nan=True)
            assert not array.flags.writeable
    if isinstance(original, GameState):
        assert (out.has_ball, out.opponent_with_ball) == (
            original.has_ball,
            original.opponent_with_ball,
        )


@dataclass(frozen=True, slots=True, eq=False)
class LabelledTarget(BehaviourTarget):
    label: str = ""


@pytest.mark.parametrize(("how", "clone"), COPIES, ids=[c[0] for c in COPIES])
def test_a_dataclass_subclass_keeps_its_field_and_read_only_arrays(
    how: str, clone: Callable[[Any], Any]
) -> None:
    out = clone(LabelledTarget((1.0, 0.0), [[2.0, 1.0]], "press"))
    assert type(out) is LabelledTarget
    assert out.label == "press"
    assert not out.goal_xy.flags.writeable
    assert not out.obstacles_xy.flags.writeable


def test_old_pickles_load_with_read_only_arrays() -> None:
    target = BehaviourTarget((1.0, 0.0), [[2.0, 1.0]])
    restored = BehaviourTarget.__new__(BehaviourTarget)
    # The former pickle state: the field values as a list, arrays writable copies.
    restored.__setstate__([np.array(target.goal_xy), np.array(target.obstacles_xy)])
    assert not restored.goal_xy.flags.writeable
    assert not restored.obstacles_xy.flags.writeable
    assert np.array_equal(restored.obstacles_xy, target.obstacles_xy)


finite = st.floats(allow_nan=False, allow_infinity=False)


@settings(max_examples=50, deadline=None)
@given(finite, finite, finite, finite)
def test_support_goal_is_the_correctly_rounded_midpoint(
    bx: float, by: float, gx: float, gy: float
) -> None:
    goal = support(_state(ball_xy=(bx, by), own_goal_xy=(gx, gy))).goal_xy
    assert goal[0] == float((Fraction(bx) + Fraction(gx)) / 2)
    assert goal[1] == float((Fraction(by) + Fraction(gy)) / 2)


test_support_goal_is_the_correctly_rounded_midpoint_thoroughly = slow_twin(
    test_support_goal_is_the_correctly_rounded_midpoint, max_examples=300
)


def test_support_midpoint_of_sub_normals_and_of_huge_values() -> None:
    tiny = 5e-324
    goal = support(_state(ball_xy=(tiny, 1.7e308), own_goal_xy=(tiny, 1.7e308))).goal_xy
    assert goal.tolist() == [tiny, 1.7e308]


@pytest.mark.parametrize(
    "radius", [math.nextafter(1e6, math.inf), 1e6 + 1e-6, math.nextafter(1e-6, 0.0)]
)
def test_possession_radius_error_prints_the_value_exactly(radius: float) -> None:
    with pytest.raises(ValueError, match="possession_radius") as err:
        _state(possession_radius=radius)
    assert repr(radius) in str(err.value)


@pytest.mark.parametrize("radius", [1e6, 1e-6])
def test_possession_radius_at_its_limits_is_accepted(radius: float) -> None:
    assert _state(possession_radius=radius).possession_radius == radius
