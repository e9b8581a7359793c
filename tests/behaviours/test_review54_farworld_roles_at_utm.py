"""The soccer roles on a field at UTM coordinates: the roles at the origin, moved (review 54).

A team's field may be mapped in UTM (x ~ 4.5e5 m, y ~ 5.4e6 m, floats 5.8e-11 and
9.3e-10 m apart). The scene here is drawn at the UTM offset and moved to the origin by
subtracting it (exact: Sterbenz), so both hold the same positions. Possession is
decided on differences of positions (exact), so ``has_ball`` and
``opponent_with_ball`` are the same, ties included; each role's goal and obstacles
are those at the origin moved, rounded once or twice at UTM size (measured: a
support point 4.7e-10 m off, half a spacing).
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.behaviours import GameState, attack, defend, support

OFFSET = np.array([450000.123456, 5400000.654321])
SPACING = float(np.spacing(OFFSET[1]))


@settings(max_examples=150, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), near_ball=st.booleans())
def test_roles_at_utm_are_the_roles_at_the_origin_moved(seed: int, near_ball: bool) -> None:
    rng = np.random.default_rng(seed)
    robot = rng.uniform(-4.0, 4.0, 2)
    ball = robot + rng.normal(0.0, 0.15, 2) if near_ball else rng.uniform(-4.0, 4.0, 2)
    opponents = rng.uniform(-4.0, 4.0, (3, 2))
    opponents[0] = ball + rng.normal(0.0, 0.15, 2)
    teammates = rng.uniform(-4.0, 4.0, (2, 2))
    scene = {
        "robot_xy": robot,
        "ball_xy": ball,
        "teammates_xy": teammates,
        "opponents_xy": opponents,
        "own_goal_xy": np.array([-4.5, 0.0]),
        "opponent_goal_xy": np.array([4.5, 0.0]),
    }
    far = GameState(**{k: v + OFFSET for k, v in scene.items()})
    near = GameState(**{k: (v + OFFSET) - OFFSET for k, v in scene.items()})
    assert (far.has_ball, far.opponent_with_ball) == (near.has_ball, near.opponent_with_ball)
    for role in (attack, defend, support):
        at_utm, at_origin = role(far), role(near)
        assert at_utm.obstacles_xy.shape == at_origin.obstacles_xy.shape
        np.testing.assert_array_less(
            np.abs(at_utm.goal_xy - OFFSET - at_origin.goal_xy), 2 * SPACING + 1e-300
        )
        np.testing.assert_array_less(
            np.abs(at_utm.obstacles_xy - OFFSET - at_origin.obstacles_xy), 2 * SPACING + 1e-300
        )
