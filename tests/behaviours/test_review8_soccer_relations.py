"""Metamorphic relations of the soccer roles: a mirrored or turned field mirrors or turns them.

Possession is inferred from distances, which negating coordinates leaves bit for
bit, so the relations hold exactly, unseen (NaN) players included.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.behaviours import BehaviourTarget, GameState, attack, defend, support

point = st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0))
players = st.lists(st.one_of(point, st.just((math.nan, math.nan))), max_size=5)
ROLES: tuple[Callable[[GameState], BehaviourTarget], ...] = (attack, defend, support)


def _state(kw: dict[str, Any], transform: Callable[[np.ndarray], np.ndarray]) -> GameState:
    return GameState(**{k: transform(np.asarray(v, dtype=float).reshape(-1, 2)).reshape(
        np.shape(v)) if k.endswith("_xy") else v for k, v in kw.items()})


@settings(max_examples=60, deadline=None)
@given(point, point, players, players, point, st.floats(0.01, 2.0), st.booleans())
def test_roles_follow_a_mirrored_or_turned_field(
    robot: tuple[float, float], ball: tuple[float, float], mates: list[tuple[float, float]],
    opponents: list[tuple[float, float]], own_goal: tuple[float, float], radius: float,
    half_turn: bool,
) -> None:
    """y → -y (the field mirrored) or a half turn (teams swap ends): targets move with it."""
    kw = {
        "robot_xy": robot, "ball_xy": ball,
        "teammates_xy": np.array(mates, dtype=float).reshape(-1, 2),
        "opponents_xy": np.array(opponents, dtype=float).reshape(-1, 2),
        "own_goal_xy": own_goal, "opponent_goal_xy": (-own_goal[0], -own_goal[1]),
        "possession_radius": radius,
    }

    def transform(p: np.ndarray) -> np.ndarray:
        out: np.ndarray = -p if half_turn else p * [1.0, -1.0]
        return out

    before = _state(kw, lambda p: p)
    after = _state(kw, transform)
    assert after.has_ball == before.has_ball
    assert after.opponent_with_ball == before.opponent_with_ball
    for role in ROLES:
        a, b = role(before), role(after)
        np.testing.assert_array_equal(b.goal_xy, transform(a.goal_xy[None])[0])
        np.testing.assert_array_equal(b.obstacles_xy, transform(a.obstacles_xy))
