"""Users' shape mistakes get a message that names the likely cause and the fix.

Column-per-item arrays (``(3, N)`` for ``(N, 3)``, ``(2, N)`` for ``(N, 2)``), a
scalar or a column vector where a 1-D array is wanted, and a position
``[x, y]`` where a whole pose ``[x, y, theta]`` is wanted.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.control import FollowTheCarrot
from navkit.estimation import ExtendedKalmanFilter
from navkit.geometry import Pose2D, as_pose, as_twist, rollout
from navkit.kinematics import OmniDrive
from navkit.planning import KhatibRepulsion


def test_twists_in_columns_are_reported_as_transposed() -> None:
    twists = np.zeros((3, 5))
    with pytest.raises(ValueError, match="twists") as err:
        rollout(Pose2D(0.0, 0.0, 0.0), twists, 0.1)
    assert "transposed" in str(err.value)
    assert "(5, 3)" in str(err.value)


def test_points_in_columns_are_reported_as_transposed() -> None:
    with pytest.raises(ValueError, match="points_xy") as err:
        Pose2D(0.0, 0.0, 0.0).transform_points(np.zeros((2, 4)))
    assert "transposed" in str(err.value)
    assert "(4, 2)" in str(err.value)


def test_obstacles_in_columns_are_reported_as_transposed() -> None:
    with pytest.raises(ValueError, match="obstacles_xy") as err:
        KhatibRepulsion(np.zeros((2, 6)))
    assert "transposed" in str(err.value)


def test_path_in_columns_is_reported_as_transposed() -> None:
    with pytest.raises(ValueError, match="path") as err:
        FollowTheCarrot().set_path(np.array([[0.0, 1.0, 2.0], [0.0, 0.0, 0.0]]))
    assert "transposed" in str(err.value)


def test_wheel_speeds_in_columns_are_reported_as_transposed() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_speeds") as err:
        drive.forward_batch(np.zeros((3, 7)))
    assert "transposed" in str(err.value)


def test_a_wrong_length_that_is_not_a_transpose_gets_no_transpose_hint() -> None:
    with pytest.raises(ValueError, match="twists") as err:
        rollout(Pose2D(0.0, 0.0, 0.0), np.zeros((5, 2)), 0.1)
    assert "transposed" not in str(err.value)


def test_a_position_for_a_pose_says_a_pose_needs_theta() -> None:
    with pytest.raises(ValueError, match="target") as err:
        as_pose([1.0, 2.0], "target")
    assert "[x, y, theta]" in str(err.value)


def test_two_numbers_for_a_twist_say_what_a_twist_holds() -> None:
    with pytest.raises(ValueError, match="twist") as err:
        as_twist(np.array([0.5, 0.1]))
    assert "[vx, vy, omega]" in str(err.value)


def test_four_numbers_for_a_pose_get_no_position_hint() -> None:
    with pytest.raises(ValueError, match="pose") as err:
        as_pose([1.0, 2.0, 3.0, 4.0])
    assert "give all three" not in str(err.value)


def test_a_column_vector_state_suggests_flattening() -> None:
    with pytest.raises(ValueError, match="x0") as err:
        ExtendedKalmanFilter(np.zeros((3, 1)), np.eye(3))
    assert "ravel" in str(err.value)


def test_a_scalar_measurement_suggests_a_list() -> None:
    ekf = ExtendedKalmanFilter(np.zeros(3), np.eye(3))
    with pytest.raises(ValueError, match="z") as err:
        ekf.update(0.5, lambda x: x[:1], lambda x: np.array([[1.0, 0.0, 0.0]]), np.eye(1))
    assert "[value]" in str(err.value)
