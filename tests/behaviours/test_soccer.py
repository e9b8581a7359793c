"""Soccer behaviours: goal and repelling points per game situation."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.behaviours import BehaviourTarget, GameState, attack, defend, support
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, integrate

OWN = (-4.5, 0.0)
THEIRS = (4.5, 0.0)

coord = st.floats(-4.0, 4.0)
pt = st.tuples(coord, coord)
players = st.lists(pt, max_size=5)


def state_of(robot: Any, ball: Any, teammates: Any = (), opponents: Any = (),
             **options: Any) -> GameState:
    """A state on the standard field (own goal on the left)."""
    return GameState(robot_xy=robot, ball_xy=ball, teammates_xy=teammates,
                     opponents_xy=opponents, own_goal_xy=OWN, opponent_goal_xy=THEIRS,
                     **options)


@settings(max_examples=40)
@given(pt, pt, players, players, st.booleans())
def test_behaviour_rules(
    robot: tuple[float, float], ball: tuple[float, float], mates: list[tuple[float, float]],
    opps: list[tuple[float, float]], has_ball: bool,
) -> None:
    holder = 0 if opps and not has_ball else None
    state = state_of(robot, ball, mates, opps, has_ball=has_ball, opponent_with_ball=holder)
    opp = np.array(opps).reshape(-1, 2)
    mate = np.array(mates).reshape(-1, 2)

    target = attack(state)
    np.testing.assert_array_equal(target.goal_xy, THEIRS if has_ball else ball)
    np.testing.assert_array_equal(target.obstacles_xy, opp)

    target = support(state)
    np.testing.assert_allclose(target.goal_xy, (np.array(ball) + OWN) / 2)
    np.testing.assert_array_equal(target.obstacles_xy, np.vstack((mate, opp, [OWN])))

    target = defend(state)
    np.testing.assert_array_equal(target.goal_xy, ball)
    expected = opp[1:] if holder == 0 else opp
    np.testing.assert_array_equal(target.obstacles_xy, expected)


test_behaviour_rules_thoroughly = slow_twin(test_behaviour_rules, max_examples=100)


def test_possession_is_inferred_from_distances() -> None:
    mine = state_of((0.9, 0.0), (1.0, 0.0), [], [[1.1, 0.0]])
    assert mine.has_ball is True and mine.opponent_with_ball is None
    np.testing.assert_array_equal(attack(mine).goal_xy, THEIRS)
    theirs = state_of((0.0, 0.0), (1.0, 0.0), [], [[3.0, 0.0], [math.nan, math.nan],
                                                   [1.2, 0.0]])
    assert theirs.has_ball is False and theirs.opponent_with_ball == 2
    np.testing.assert_array_equal(defend(theirs).obstacles_xy[0], [3.0, 0.0])
    assert defend(theirs).obstacles_xy.shape == (2, 2)
    loose = state_of((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]])
    assert loose.opponent_with_ball is None
    assert defend(loose).obstacles_xy.shape == (1, 2)
    # The possession radius is an option.
    far = state_of((0.0, 0.0), (1.0, 0.0), possession_radius=1.5)
    assert far.has_ball and far.possession_radius == 1.5


def test_teammates_and_opponents_default_to_none() -> None:
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), own_goal_xy=OWN,
                      opponent_goal_xy=THEIRS)
    assert state.teammates_xy.shape == (0, 2) and state.opponents_xy.shape == (0, 2)
    np.testing.assert_array_equal(support(state).obstacles_xy, [OWN])
    assert defend(state).obstacles_xy.shape == (0, 2)


def test_outputs_do_not_alias_the_state() -> None:
    state = state_of((0.0, 0.0), (1.0, 0.0), [[0.0, 1.0]], [[2.0, 1.0]])
    for behaviour in (attack, support, defend):
        target = behaviour(state)
        for out in (target.goal_xy, target.obstacles_xy):
            assert not out.flags.writeable
            for source in (state.ball_xy, state.opponents_xy, state.teammates_xy,
                           state.own_goal_xy, state.opponent_goal_xy):
                assert not np.shares_memory(out, source)
    np.testing.assert_array_equal(state.ball_xy, [1.0, 0.0])
    np.testing.assert_array_equal(state.opponents_xy, [[2.0, 1.0]])


def test_state_is_frozen_and_copies_its_input() -> None:
    robot = np.array([0.0, 0.0])
    opponents = np.array([[2.0, 1.0]])
    state = state_of(robot, (1.0, 0.0), [], opponents)
    robot[0] = 5.0
    opponents[0, 0] = 5.0
    np.testing.assert_array_equal(state.robot_xy, [0.0, 0.0])
    np.testing.assert_array_equal(state.opponents_xy, [[2.0, 1.0]])
    assert robot.flags.writeable and opponents.flags.writeable
    for f in dataclasses.fields(state):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(state, f.name, getattr(state, f.name))
    with pytest.raises(ValueError, match="read-only"):
        state.ball_xy[0] = 3.0
    assert not hasattr(state, "__dict__")


def test_state_fields_are_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        GameState((0.0, 0.0), (1.0, 0.0), [], [], OWN, THEIRS)  # type: ignore[misc]
    with pytest.raises(TypeError, match="own_goal_xy"):
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0),  # type: ignore[call-arg]
                  opponent_goal_xy=THEIRS)


def test_behaviour_target() -> None:
    goal = np.array([1.0, 2.0])
    obstacles = np.array([[3.0, 4.0], [math.nan, math.nan]])
    target = BehaviourTarget(goal, obstacles)
    goal[0] = 9.0
    obstacles[0, 0] = 9.0
    np.testing.assert_array_equal(target.goal_xy, [1.0, 2.0])
    np.testing.assert_array_equal(target.obstacles_xy, [[3.0, 4.0], [math.nan, math.nan]])
    assert goal.flags.writeable and obstacles.flags.writeable
    with pytest.raises(dataclasses.FrozenInstanceError):
        target.goal_xy = goal  # type: ignore[misc]
    assert BehaviourTarget(goal_xy=(0.0, 0.0), obstacles_xy=[]).obstacles_xy.shape == (0, 2)
    assert not isinstance(target, tuple)
    with pytest.raises(ValueError, match="goal_xy"):
        BehaviourTarget((math.nan, 0.0), [])
    with pytest.raises(ValueError, match="obstacles_xy"):
        BehaviourTarget((0.0, 0.0), [[math.inf, 0.0]])
    with pytest.raises(ValueError, match="obstacles_xy"):
        BehaviourTarget((0.0, 0.0), [[1.0, 2.0, 3.0]])


def test_bad_state() -> None:
    with pytest.raises(ValueError, match="ball_xy"):
        state_of((0.0, 0.0), (math.nan, 0.0))
    with pytest.raises(ValueError, match="robot_xy"):
        state_of((0.0, 0.0, 0.0), (1.0, 0.0))
    with pytest.raises(ValueError, match="opponents_xy"):
        state_of((0.0, 0.0), (1.0, 0.0), [], [[math.inf, 0.0]])
    with pytest.raises(ValueError, match="teammates_xy"):
        state_of((0.0, 0.0), (1.0, 0.0), [[1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="own_goal_xy"):
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), own_goal_xy=(math.inf, 0.0),
                  opponent_goal_xy=THEIRS)
    with pytest.raises(ValueError, match="opponent_with_ball"):
        state_of((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]], opponent_with_ball=1)
    with pytest.raises(TypeError, match="opponent_with_ball"):
        state_of((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]], opponent_with_ball=True)
    with pytest.raises(TypeError, match="has_ball"):
        state_of((0.0, 0.0), (1.0, 0.0), has_ball=1)
    with pytest.raises(ValueError, match="possession_radius"):
        state_of((0.0, 0.0), (1.0, 0.0), possession_radius=0.0)
    with pytest.raises(TypeError, match="state"):
        attack("state")  # type: ignore[arg-type]
    # numpy scalars are accepted where a bool or an index is expected.
    state = state_of((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]], has_ball=np.bool_(False),
                     opponent_with_ball=np.int64(0))
    assert state.has_ball is False and state.opponent_with_ball == 0


def test_attacker_reaches_the_ball_past_an_opponent() -> None:
    # Behaviour -> controller -> integrate: the opponent between robot and ball is avoided.
    ctl = PotentialFieldController(k_rep=0.05, influence_radius=0.6, max_speed=0.5)
    pose = Pose2D(-2.0, 0.0, 0.0)
    opponent = np.array([-0.5, 0.1])
    closest = math.inf
    for _ in range(400):
        state = state_of((pose.x, pose.y), (1.0, 0.0), [], [opponent])
        target = attack(state)
        if state.has_ball:
            break
        goal = target.goal_xy
        cmd = ctl.step(pose, (goal[0], goal[1], 0.0), dt=0.05, obstacles=target.obstacles_xy)
        pose = integrate(pose, cmd, 0.05)
        closest = min(closest, math.hypot(pose.x - opponent[0], pose.y - opponent[1]))
    assert state.has_ball
    assert closest > 0.3


def test_replace_infers_possession_again_when_asked() -> None:
    """As documented: replace() keeps inferred values unless they are passed as None."""
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(0.1, 0.0), opponents_xy=[[3.0, 0.0]],
                      own_goal_xy=(-4.0, 0.0), opponent_goal_xy=(4.0, 0.0))  # fmt: skip
    assert state.has_ball is True and state.opponent_with_ball is None
    kept = dataclasses.replace(state, ball_xy=(3.05, 0.0))
    assert kept.has_ball is True and kept.opponent_with_ball is None
    fresh = dataclasses.replace(state, ball_xy=(3.05, 0.0), has_ball=None, opponent_with_ball=None)
    assert fresh.has_ball is False and fresh.opponent_with_ball == 0
