"""Possession boundaries of GameState that no earlier test pinned down.

Found by mutation testing (session 13): ``<=`` replaced by ``<`` in the
possession rules survived every other test.
"""

from __future__ import annotations

from typing import Any

import pytest

from navkit.behaviours import GameState as _GameState

GOALS: dict[str, Any] = {"own_goal_xy": (-4.5, 0.0), "opponent_goal_xy": (4.5, 0.0)}


def GameState(**kwargs: Any) -> _GameState:
    """The record, built from array_like positions (its fields are typed as arrays)."""
    return _GameState(**kwargs)


def test_robot_exactly_at_possession_radius_holds_the_ball() -> None:
    # has_ball is inferred as ||robot - ball|| <= possession_radius (inclusive).
    at = GameState(robot_xy=(0.0, 0.0), ball_xy=(0.25, 0.0), **GOALS)
    assert at.has_ball is True
    beyond = GameState(robot_xy=(0.0, 0.0), ball_xy=(0.25, 0.0), possession_radius=0.2499, **GOALS)
    assert beyond.has_ball is False


def test_opponent_exactly_at_possession_radius_holds_the_ball() -> None:
    # The nearest seen opponent within possession_radius (inclusive) holds it.
    state = GameState(robot_xy=(-1.0, 0.0), ball_xy=(0.25, 0.0),
                      opponents_xy=[[3.0, 0.0], [0.5, 0.0]], **GOALS)
    assert state.opponent_with_ball == 1
    free = GameState(robot_xy=(-1.0, 0.0), ball_xy=(0.25, 0.0),
                     opponents_xy=[[3.0, 0.0], [0.5, 0.0]], possession_radius=0.2499, **GOALS)
    assert free.opponent_with_ball is None


def test_negative_opponent_with_ball_is_not_an_index() -> None:
    # opponent_with_ball indexes opponents_xy: 0 <= index < L; -1 is refused.
    with pytest.raises(ValueError, match="opponent_with_ball"):
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), opponents_xy=[[1.1, 0.0]],
                  opponent_with_ball=-1, **GOALS)
