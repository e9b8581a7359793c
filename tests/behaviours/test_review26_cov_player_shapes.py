"""Player arrays of a wrong shape that is not a pose array (coverage review, session 30).

Only an ``(N, 3)`` array, or one pose ``(3,)`` (review 53), gets the hint about
poses; any other shape is refused with the plain shape error, naming the
argument, and the array is left as given.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.behaviours import GameState


def _state(**players: Any) -> GameState:
    return GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), own_goal_xy=(-4.5, 0.0),
                     opponent_goal_xy=(4.5, 0.0), **players)  # fmt: skip


@pytest.mark.parametrize("name", ["teammates_xy", "opponents_xy"])
@pytest.mark.parametrize(
    ("value", "shape"),
    [(np.array([1.0, 2.0, 3.0]), "(3,)"), (np.zeros((2, 2, 2)), "(2, 2, 2)"),
     (np.zeros((3, 5)), "(3, 5)")],
)  # fmt: skip
def test_a_wrong_shape_is_refused_without_the_pose_hint(
    name: str, value: np.ndarray, shape: str
) -> None:
    before = value.copy()
    with pytest.raises(ValueError) as info:
        _state(**{name: value})
    # Review 53: one pose (3,) is named as a pose where one point is wanted
    # (as_points' hint, as FieldDStar.plan_world's); the other shapes get none.
    hint = " (a pose [x, y, theta]? pass its [:2])" if shape == "(3,)" else ""
    assert str(info.value) == f"{name} must have shape (N, 2) or (2,), got {shape}{hint}"
    np.testing.assert_array_equal(value, before)


def test_a_ragged_list_is_refused_naming_the_argument() -> None:
    with pytest.raises(ValueError, match=r"^opponents_xy must be a rectangular array"):
        _state(opponents_xy=[[1.0, 2.0, 0.3], [1.0]])
