"""GameState stores the validated, converted scalars, not the caller's objects.

Found by mutation testing (session 14): storing ``possession_radius`` and a given
``opponent_with_ball`` as passed (an ``int``, a NumPy scalar) survived every other test.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.behaviours import GameState as _GameState

GOALS: dict[str, Any] = {"own_goal_xy": (-4.5, 0.0), "opponent_goal_xy": (4.5, 0.0)}


def GameState(**kwargs: Any) -> _GameState:
    """The record, built from array_like positions (its fields are typed as arrays)."""
    return _GameState(**kwargs)


@pytest.mark.parametrize("radius", [1, np.float32(0.5), np.int64(2)])
def test_possession_radius_is_stored_as_a_python_float(radius: Any) -> None:
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(5.0, 0.0), possession_radius=radius, **GOALS)
    assert type(state.possession_radius) is float
    assert state.possession_radius == float(radius)


@pytest.mark.parametrize("holder", [np.int64(1), np.uint8(1), np.int32(0)])
def test_given_opponent_with_ball_is_stored_as_a_python_int(holder: Any) -> None:
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(5.0, 0.0),
                      opponents_xy=[[1.0, 1.0], [2.0, 2.0]], opponent_with_ball=holder, **GOALS)
    assert type(state.opponent_with_ball) is int
    assert state.opponent_with_ball == int(holder)
