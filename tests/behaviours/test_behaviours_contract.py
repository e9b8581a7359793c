"""Issue 12 in navkit.behaviours: records copy (never freeze the caller's arrays), ranges, types."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.behaviours import BehaviourTarget, GameState, attack, defend, support


def state(**kw: object) -> GameState:
    args: dict[str, object] = {
        "robot_xy": (0.0, 0.0),
        "ball_xy": (1.0, 0.0),
        "opponents_xy": [[1.1, 0.0], [3.0, -1.0]],
        "own_goal_xy": (-4.5, 0.0),
        "opponent_goal_xy": (4.5, 0.0),
    }
    args.update(kw)
    return GameState(**args)  # type: ignore[arg-type]


def test_records_copy_arrays_and_never_freeze_the_callers() -> None:
    robot = np.array([0.0, 0.0])
    opponents = np.array([[1.1, 0.0], [3.0, -1.0]])
    teammates = np.array([[-2.0, 1.0]])
    s = state(robot_xy=robot, opponents_xy=opponents, teammates_xy=teammates)
    for arr in (robot, opponents, teammates):
        assert arr.flags.writeable
    opponents[0, 0] = 99.0
    assert s.opponents_xy[0, 0] == 1.1
    assert not s.opponents_xy.flags.writeable and not s.robot_xy.flags.writeable

    goal = np.array([1.0, 0.0])
    obstacles = np.array([[2.0, 1.0]])
    target = BehaviourTarget(goal, obstacles)
    assert goal.flags.writeable and obstacles.flags.writeable
    goal[0] = 5.0
    assert target.goal_xy[0] == 1.0
    from_lists = BehaviourTarget([1.0, 0.0], [[2.0, 1.0], [math.nan, math.nan]])
    assert from_lists.obstacles_xy.shape == (2, 2) and not from_lists.goal_xy.flags.writeable
    # The behaviours' outputs are copies too: they do not share the state's arrays.
    assert not np.shares_memory(attack(s).obstacles_xy, s.opponents_xy)



def test_copied_and_unpickled_records_stay_read_only(
    duplicate: Callable[[object], object],
) -> None:
    # pickle and deepcopy rebuild a frozen record without __post_init__: its arrays
    # came back writable.
    s = state(teammates_xy=[[-2.0, 1.0]])
    for record in (s, support(s)):
        copy = duplicate(record)
        assert type(copy) is type(record)
        for f in dataclasses.fields(record):
            value = getattr(copy, f.name)
            if isinstance(value, np.ndarray):
                np.testing.assert_array_equal(value, getattr(record, f.name))
                assert not value.flags.writeable, f.name
            else:
                assert value == getattr(record, f.name)

@pytest.mark.parametrize("radius", [0.0, 5e-324, 1e-7, 2e6, 1e308])
def test_possession_radius_outside_its_range_is_refused(radius: float) -> None:
    with pytest.raises(ValueError, match="possession_radius must be in"):
        state(possession_radius=radius)


@pytest.mark.parametrize(
    ("kw", "error", "name"),
    [
        ({"possession_radius": True}, TypeError, "possession_radius"),
        ({"possession_radius": "0.3"}, TypeError, "possession_radius"),
        ({"has_ball": "yes"}, TypeError, "has_ball"),
        ({"has_ball": 1}, TypeError, "has_ball"),
        ({"opponent_with_ball": True}, TypeError, "opponent_with_ball"),
        ({"opponent_with_ball": 1.0}, TypeError, "opponent_with_ball"),
        ({"robot_xy": (1 + 1j, 0.0)}, TypeError, "robot_xy"),
        ({"opponents_xy": [[math.inf, 0.0]]}, ValueError, "opponents_xy"),
        ({"ball_xy": (math.nan, 0.0)}, ValueError, "ball_xy"),
    ],
)
def test_wrong_types_and_values_name_the_argument(
    kw: dict[str, object], error: type, name: str
) -> None:
    with pytest.raises(error, match=name):
        state(**kw)


def test_positions_near_the_float_limit_give_finite_targets() -> None:
    s = state(robot_xy=(-1.7e308, 0.0), ball_xy=(1.7e308, 0.0), own_goal_xy=(1.7e308, 0.0),
              opponents_xy=[[-1.7e308, 1.0]])
    assert s.has_ball is False and s.opponent_with_ball is None
    # Half way between ball and own goal: 0.5*(a + b) would overflow (before issue 12 a
    # ValueError "goal_xy must contain only finite values").
    assert support(s).goal_xy.tolist() == [1.7e308, 0.0]


@settings(max_examples=40, deadline=None)  # the first example may load compiled kernels
@given(
    st.tuples(st.floats(-1e300, 1e300), st.floats(-1e300, 1e300)),
    st.tuples(st.floats(-1e300, 1e300), st.floats(-1e300, 1e300)),
    st.lists(st.tuples(st.floats(-1e300, 1e300), st.floats(-1e300, 1e300)), max_size=4),
)
def test_behaviours_of_finite_states_are_finite(
    robot: tuple[float, float], ball: tuple[float, float], opponents: list[tuple[float, float]]
) -> None:
    s = state(robot_xy=robot, ball_xy=ball, opponents_xy=np.array(opponents).reshape(-1, 2))
    for behaviour in (attack, support, defend):
        target = behaviour(s)
        assert np.isfinite(target.goal_xy).all()
        assert np.isfinite(target.obstacles_xy).all()


test_behaviours_of_finite_states_are_finite_thoroughly = slow_twin(
    test_behaviours_of_finite_states_are_finite, max_examples=100
)
