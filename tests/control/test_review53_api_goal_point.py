"""A pose given for a goal point: the control and behaviour layers name it as plan_world does.

PotentialFieldController.desired_velocity's goal_xy said only "must have length 2
along axis 0, got shape (3,)"; the soccer behaviours had hints of their own
words (a second one after as_points' for rows of poses). Both now take their
points through _shared.validation.as_point / as_points.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.behaviours import BehaviourTarget, GameState
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D

HINT = r" \(a pose \[x, y, theta\]\? pass its \[:2\]\)$"
GOALS = {"own_goal_xy": (-2.0, 0.0), "opponent_goal_xy": (2.0, 0.0)}


def test_desired_velocity_names_a_pose_goal() -> None:
    ctl = PotentialFieldController()
    with pytest.raises(
        ValueError, match=r"^goal_xy must have length 2 along axis 0, got shape \(3,\)" + HINT
    ):
        ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0, 0.5))
    goal = np.array([2.0, 0.0, 0.5])
    assert ctl.desired_velocity((0.0, 0.0, 0.0), goal[:2]).tolist() == pytest.approx([0.5, 0.0])


def test_soccer_points_use_the_same_words() -> None:
    with pytest.raises(ValueError, match=r"^ball_xy must have length 2 .*" + HINT):
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0, 0.0), **GOALS)
    with pytest.raises(ValueError, match=r"^goal_xy .*" + HINT):
        BehaviourTarget((1.0, 0.0, 0.0), [])
    # Rows of poses for the players: as_points' one hint, not a second of soccer's own.
    with pytest.raises(ValueError) as info:
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), teammates_xy=np.zeros((5, 3)), **GOALS)
    assert str(info.value) == (
        "teammates_xy must have shape (N, 2) or (2,), got (5, 3) "
        "(rows of poses [x, y, theta]? pass its [:, :2], shape (5, 2))"
    )


def test_other_refusals_unchanged() -> None:
    ctl = PotentialFieldController()
    with pytest.raises(ValueError, match=r"^goal_xy must contain only finite values$"):
        ctl.desired_velocity((0.0, 0.0, 0.0), (np.nan, 0.0))
    with pytest.raises(
        ValueError, match=r"^goal_xy must have length 2 along axis 0, got shape \(4,\)$"
    ):
        ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0, 0.0, 0.0))
    with pytest.raises(TypeError, match=r"^robot_xy must be a point \(x, y\), got a Pose2D"):
        GameState(robot_xy=Pose2D(0.0, 0.0, 0.0), ball_xy=(1.0, 0.0), **GOALS)
