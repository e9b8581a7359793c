"""A pose where a point is wanted: the message says how to pass the point (session 24, USER).

A new user's soccer loop builds a ``GameState`` from the estimator's ``Pose2D``
(or its ``as_array()``) and a list of tracked players' poses; each of these is
refused, as before, with a message that names the conversion.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.behaviours import BehaviourTarget, GameState, attack
from navkit.geometry import Pose2D

GOALS = {"own_goal_xy": (-4.5, 0.0), "opponent_goal_xy": (4.5, 0.0)}
coord = st.floats(-50.0, 50.0, allow_nan=False)


@given(coord, coord, st.floats(-3.0, 3.0))
def test_a_pose2d_as_a_point_names_pose_x_and_y(x: float, y: float, theta: float) -> None:
    pose = Pose2D(x, y, theta)
    for name in ("robot_xy", "ball_xy"):
        kwargs = {"robot_xy": (0.0, 0.0), "ball_xy": (1.0, 0.0), **GOALS, name: pose}
        with pytest.raises(TypeError, match=rf"^{name} must be a point \(x, y\), got a Pose2D: "
                           r"pass \(pose\.x, pose\.y\)$"):
            GameState(**kwargs)
    # what the message says to pass is accepted and is the pose's position
    state = GameState(robot_xy=(pose.x, pose.y), ball_xy=(1.0, 0.0), **GOALS)
    assert state.robot_xy.tolist() == [x, y]


@given(coord, coord, st.floats(-3.0, 3.0))
def test_a_pose_array_as_a_point_says_to_keep_x_and_y(x: float, y: float, theta: float) -> None:
    pose = np.array([x, y, theta])
    with pytest.raises(ValueError, match=r"^robot_xy must have length 2.*got shape \(3,\) "
                       r"\(a pose \[x, y, theta\]\? pass its \[:2\]\)$"):
        GameState(robot_xy=pose, ball_xy=(1.0, 0.0), **GOALS)
    with pytest.raises(ValueError, match=r"^goal_xy .*\(a pose \[x, y, theta\]\?"):
        BehaviourTarget(pose, [])
    assert GameState(robot_xy=pose[:2], ball_xy=(1.0, 0.0), **GOALS).robot_xy.tolist() == [x, y]


def test_other_wrong_lengths_get_no_pose_hint() -> None:
    for bad in ([1.0], [1.0, 2.0, 3.0, 4.0]):
        with pytest.raises(ValueError) as info:
            GameState(robot_xy=bad, ball_xy=(1.0, 0.0), **GOALS)
        assert "pose" not in str(info.value)


@given(st.lists(st.tuples(coord, coord, st.floats(-3.0, 3.0)), min_size=1, max_size=6))
def test_players_as_poses_name_the_conversion(rows: list[tuple[float, float, float]]) -> None:
    poses = [Pose2D(*r) for r in rows]
    for container in (list, tuple):
        with pytest.raises(TypeError, match=r"^opponents_xy must be points \(x, y\), got Pose2D "
                           r"items: pass \[\(p\.x, p\.y\) for p in poses\]$"):
            GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), opponents_xy=container(poses),
                      **GOALS)
    with pytest.raises(ValueError, match=r"^teammates_xy must have shape \(N, 2\).*"
                       r"\(rows of poses \[x, y, theta\]\? pass its \[:, :2\], shape \(\d+, 2\)"
                       r"(; or, if it is transposed, .*)?\)$"):  # as_points' own (review 53)
        GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), teammates_xy=np.array(rows), **GOALS)
    # the conversions the messages name are accepted and keep the positions
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0),
                      opponents_xy=[(p.x, p.y) for p in poses],
                      teammates_xy=np.array(rows)[:, :2], **GOALS)
    assert state.opponents_xy.tolist() == [[p.x, p.y] for p in poses]
    assert state.teammates_xy.tolist() == [[r[0], r[1]] for r in rows]


def test_valid_inputs_are_unchanged() -> None:
    """Points as tuples, lists of tuples, (N, 2) arrays and NaN rows still work as before."""
    state = GameState(robot_xy=np.array([0.0, 0.0]), ball_xy=[1.0, 0.0],
                      opponents_xy=[(2.0, 1.0), (np.nan, np.nan)], teammates_xy=np.zeros((0, 2)),
                      **GOALS)
    target = attack(state)
    assert target.goal_xy.tolist() == [1.0, 0.0]
    assert target.obstacles_xy.shape == (2, 2)
    assert np.isnan(target.obstacles_xy[1]).all()
