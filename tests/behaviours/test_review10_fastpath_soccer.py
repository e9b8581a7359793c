"""Soccer records: the float64 fast path and the behaviours' unchecked constructor.

``GameState`` and ``BehaviourTarget`` take float64 ``(2,)`` arrays of finite
values without the general conversion; anything else goes through it. The
behaviours build their targets from the state's (already checked) arrays
without the public checks. Both must give what the general path gives: equal
read-only copies that share no memory with their source, and the same errors.
"""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.behaviours import BehaviourTarget, GameState, attack, defend, support

_coord = st.floats(-1e6, 1e6)
_pt = st.tuples(_coord, _coord)


def _same_array(a: np.ndarray, b: np.ndarray) -> None:
    assert type(a) is type(b) is np.ndarray
    assert a.dtype == b.dtype == np.float64 and a.shape == b.shape
    assert a.tobytes() == b.tobytes()
    assert not a.flags.writeable and not b.flags.writeable
    assert a.flags.c_contiguous and b.flags.c_contiguous


def _state(robot: Any, ball: Any, own: Any, opp_goal: Any, opponents: Any) -> GameState:
    return GameState(
        robot_xy=robot,
        ball_xy=ball,
        opponents_xy=opponents,
        teammates_xy=[[0.5, -0.5]],
        own_goal_xy=own,
        opponent_goal_xy=opp_goal,
    )


@settings(max_examples=40, deadline=None)
@given(
    robot=_pt,
    ball=_pt,
    own=_pt,
    opp_goal=_pt,
    opponents=st.lists(_pt, min_size=0, max_size=4),
)
def test_arrays_and_lists_build_the_same_state_and_targets(
    robot: tuple[float, float],
    ball: tuple[float, float],
    own: tuple[float, float],
    opp_goal: tuple[float, float],
    opponents: list[tuple[float, float]],
) -> None:
    opp = np.array(opponents, dtype=np.float64).reshape(-1, 2)
    given_arrays = [np.array(p) for p in (robot, ball, own, opp_goal)]
    kept = [a.copy() for a in given_arrays]
    fast = _state(given_arrays[0], given_arrays[1], given_arrays[2], given_arrays[3], opp)
    slow = _state(list(robot), list(ball), list(own), list(opp_goal), opp.tolist())
    for name in ("robot_xy", "ball_xy", "own_goal_xy", "opponent_goal_xy", "opponents_xy"):
        _same_array(getattr(fast, name), getattr(slow, name))
    for a, k in zip(given_arrays, kept, strict=True):
        assert a.tobytes() == k.tobytes() and a.flags.writeable
        assert not any(np.shares_memory(a, getattr(fast, n)) for n in ("robot_xy", "ball_xy"))
    assert (fast.has_ball, fast.opponent_with_ball) == (slow.has_ball, slow.opponent_with_ball)
    for behaviour in (attack, support, defend):
        target = behaviour(fast)
        public = BehaviourTarget(target.goal_xy.tolist(), target.obstacles_xy.tolist())
        assert type(target) is BehaviourTarget
        _same_array(target.goal_xy, public.goal_xy)
        _same_array(target.obstacles_xy, public.obstacles_xy.reshape(-1, 2))
        for name in ("goal_xy", "obstacles_xy"):
            for source in ("ball_xy", "opponents_xy", "own_goal_xy", "opponent_goal_xy"):
                assert not np.shares_memory(getattr(target, name), getattr(fast, source))


def test_targets_copy_and_pickle_as_public_ones() -> None:
    state = _state((0.0, 0.0), (1.0, 0.0), (-4.5, 0.0), (4.5, 0.0), [[2.0, 1.0], [math.nan] * 2])
    target = support(state)
    for clone in (copy.copy(target), copy.deepcopy(target), pickle.loads(pickle.dumps(target))):
        assert type(clone) is BehaviourTarget
        _same_array(clone.goal_xy, target.goal_xy)
        assert clone.obstacles_xy.tobytes() == target.obstacles_xy.tobytes()
        assert not clone.obstacles_xy.flags.writeable
    with pytest.raises(AttributeError):
        target.goal_xy = np.zeros(2)  # type: ignore[misc]


@pytest.mark.parametrize(
    "bad",
    [
        [math.nan, 0.0],
        [0.0, math.inf],
        [-math.inf, math.nan],
        [1.0, 2.0, 3.0],
        [[1.0, 2.0]],
    ],
)
@pytest.mark.parametrize("name", ["robot_xy", "ball_xy", "own_goal_xy", "opponent_goal_xy"])
def test_bad_points_get_the_general_paths_error(bad: list[Any], name: str) -> None:
    errors = []
    for value in (np.array(bad, dtype=np.float64), bad):
        args: dict[str, Any] = {
            "robot_xy": (0.0, 0.0),
            "ball_xy": (1.0, 0.0),
            "own_goal_xy": (-4.5, 0.0),
            "opponent_goal_xy": (4.5, 0.0),
            name: value,
        }
        with pytest.raises((TypeError, ValueError)) as info:
            GameState(**args)
        errors.append((type(info.value), str(info.value)))
    assert errors[0] == errors[1]
    assert name in errors[0][1]


@pytest.mark.parametrize(
    "goal",
    [np.array([1, 2]), np.array([1.0, 2.0], dtype=np.float32), np.array([1.0, 2.0], dtype=">f8")],
)
def test_other_arrays_give_the_float64_point(goal: np.ndarray) -> None:
    target = BehaviourTarget(goal, np.empty((0, 2)))
    _same_array(target.goal_xy, BehaviourTarget([1.0, 2.0], np.empty((0, 2))).goal_xy)
