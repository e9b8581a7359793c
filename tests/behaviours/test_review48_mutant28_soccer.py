"""A contested ball in each role, and the pose hint only for (N, 3) players.

Review 48 (mutation testing, MUTANT28). Two mutants of the soccer roles passed
every test:

* ``attack`` heading for the ball, not the opponents' goal, when this robot
  holds the ball and an opponent is given as holding it too (a contested
  ball, which ``GameState`` documents: a given index is taken as given, also
  when ``has_ball`` is true). ``attack`` documents the goal by ``has_ball``
  alone;
* the "poses [x, y, theta]?" hint given for any array whose second axis is 3
  long (a (2, 3, 2) stack of point pairs too), not only for (N, 3) poses.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.behaviours import GameState, attack, defend, support

OWN = (-4.5, 0.0)
THEIRS = (4.5, 0.0)


def _contested() -> GameState:
    return GameState(
        robot_xy=(1.0, 0.0),
        ball_xy=(1.1, 0.0),
        teammates_xy=[[-1.0, 2.0]],
        opponents_xy=[[3.0, 1.0], [1.2, 0.05]],
        own_goal_xy=OWN,
        opponent_goal_xy=THEIRS,
        opponent_with_ball=1,
    )


def test_a_contested_ball_keeps_both_holders() -> None:
    state = _contested()
    assert state.has_ball is True and state.opponent_with_ball == 1


def test_attack_with_a_contested_ball_heads_for_the_opponents_goal() -> None:
    state = _contested()
    target = attack(state)
    np.testing.assert_array_equal(target.goal_xy, THEIRS)
    np.testing.assert_array_equal(target.obstacles_xy, state.opponents_xy)


def test_defend_and_support_with_a_contested_ball() -> None:
    state = _contested()
    target = defend(state)
    np.testing.assert_array_equal(target.goal_xy, state.ball_xy)
    np.testing.assert_array_equal(target.obstacles_xy, [[3.0, 1.0]])
    target = support(state)
    np.testing.assert_array_equal(target.goal_xy, [-1.7, 0.0])
    np.testing.assert_array_equal(
        target.obstacles_xy, [[-1.0, 2.0], [3.0, 1.0], [1.2, 0.05], [-4.5, 0.0]]
    )


def _players_of(name: str, players: np.ndarray) -> dict[str, Any]:
    return {name: players}


@pytest.mark.parametrize("name", ["teammates_xy", "opponents_xy"])
@pytest.mark.parametrize("shape", [(2, 3, 2), (1, 3, 3), (4, 3, 1)])
def test_only_n_by_3_players_get_the_pose_hint(name: str, shape: tuple[int, ...]) -> None:
    players = np.zeros(shape)
    with pytest.raises(ValueError, match=name) as info:
        GameState(
            robot_xy=(0.0, 0.0),
            ball_xy=(1.0, 0.0),
            own_goal_xy=OWN,
            opponent_goal_xy=THEIRS,
            **_players_of(name, players),
        )
    assert "theta" not in str(info.value) and "[:, :2]" not in str(info.value)
    # The hint itself, for (N, 3) poses.
    with pytest.raises(ValueError, match=r"poses \[x, y, theta\]"):
        GameState(
            robot_xy=(0.0, 0.0),
            ball_xy=(1.0, 0.0),
            own_goal_xy=OWN,
            opponent_goal_xy=THEIRS,
            **_players_of(name, np.zeros((shape[0], 3))),
        )
