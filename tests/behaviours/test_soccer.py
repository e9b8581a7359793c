"""Soccer behaviours: goal and repelling points per game situation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.behaviours import GameState, attack, defend, support
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, integrate

OWN = (-4.5, 0.0)
THEIRS = (4.5, 0.0)

coord = st.floats(-4.0, 4.0)
pt = st.tuples(coord, coord)
players = st.lists(pt, max_size=5)


@settings(max_examples=100)
@given(pt, pt, players, players, st.booleans())
def test_behaviour_rules(
    robot: tuple[float, float], ball: tuple[float, float], mates: list[tuple[float, float]],
    opps: list[tuple[float, float]], has_ball: bool,
) -> None:
    holder = 0 if opps and not has_ball else None
    state = GameState(robot, ball, mates, opps, OWN, THEIRS, has_ball=has_ball,
                      opponent_with_ball=holder)
    opp = np.array(opps).reshape(-1, 2)
    mate = np.array(mates).reshape(-1, 2)

    goal, obstacles = attack(state)
    np.testing.assert_array_equal(goal, THEIRS if has_ball else ball)
    np.testing.assert_array_equal(obstacles, opp)

    goal, obstacles = support(state)
    np.testing.assert_allclose(goal, (np.array(ball) + OWN) / 2)
    np.testing.assert_array_equal(obstacles, np.vstack((mate, opp, [OWN])))

    goal, obstacles = defend(state)
    np.testing.assert_array_equal(goal, ball)
    expected = opp[1:] if holder == 0 else opp
    np.testing.assert_array_equal(obstacles, expected)


def test_possession_is_inferred_from_distances() -> None:
    mine = GameState((0.9, 0.0), (1.0, 0.0), [], [[1.1, 0.0]], OWN, THEIRS)
    assert mine.has_ball and mine.opponent_with_ball is None
    np.testing.assert_array_equal(attack(mine).goal, THEIRS)
    theirs = GameState((0.0, 0.0), (1.0, 0.0), [], [[3.0, 0.0], [math.nan, math.nan],
                                                    [1.2, 0.0]], OWN, THEIRS)
    assert not theirs.has_ball and theirs.opponent_with_ball == 2
    np.testing.assert_array_equal(defend(theirs).obstacles[0], [3.0, 0.0])
    assert defend(theirs).obstacles.shape == (2, 2)
    loose = GameState((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]], OWN, THEIRS)
    assert loose.opponent_with_ball is None
    assert defend(loose).obstacles.shape == (1, 2)


def test_outputs_do_not_alias_the_state() -> None:
    state = GameState((0.0, 0.0), (1.0, 0.0), [[0.0, 1.0]], [[2.0, 1.0]], OWN, THEIRS)
    goal, obstacles = attack(state)
    goal[0] = 99.0
    obstacles[0, 0] = 99.0
    np.testing.assert_array_equal(state.ball, [1.0, 0.0])
    np.testing.assert_array_equal(state.opponents, [[2.0, 1.0]])


def test_bad_state() -> None:
    with pytest.raises(ValueError, match="ball"):
        GameState((0.0, 0.0), (math.nan, 0.0), [], [], OWN, THEIRS)
    with pytest.raises(ValueError, match="opponents"):
        GameState((0.0, 0.0), (1.0, 0.0), [], [[math.inf, 0.0]], OWN, THEIRS)
    with pytest.raises(ValueError, match="teammates"):
        GameState((0.0, 0.0), (1.0, 0.0), [[1.0, 2.0, 3.0]], [], OWN, THEIRS)
    with pytest.raises(ValueError, match="opponent_with_ball"):
        GameState((0.0, 0.0), (1.0, 0.0), [], [[2.0, 0.0]], OWN, THEIRS, opponent_with_ball=1)
    with pytest.raises(TypeError, match="has_ball"):
        GameState((0.0, 0.0), (1.0, 0.0), [], [], OWN, THEIRS, has_ball=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="possession_radius"):
        GameState((0.0, 0.0), (1.0, 0.0), [], [], OWN, THEIRS, possession_radius=0.0)
    with pytest.raises(TypeError, match="state"):
        attack("state")  # type: ignore[arg-type]


def test_attacker_reaches_the_ball_past_an_opponent() -> None:
    # Behaviour -> controller -> integrate: the opponent between robot and ball is avoided.
    ctl = PotentialFieldController(k_rep=0.05, d0=0.6, max_speed=0.5)
    pose = Pose2D(-2.0, 0.0, 0.0)
    opponent = np.array([-0.5, 0.1])
    closest = math.inf
    for _ in range(400):
        state = GameState((pose.x, pose.y), (1.0, 0.0), [], [opponent], OWN, THEIRS)
        goal, obstacles = attack(state)
        if state.has_ball:
            break
        cmd = ctl.step(pose, None, Pose2D(goal[0], goal[1], 0.0), obstacles, 0.05)
        pose = integrate(pose, cmd, 0.05)
        closest = min(closest, math.hypot(pose.x - opponent[0], pose.y - opponent[1]))
    assert state.has_ball
    assert closest > 0.3
