"""SE(2) geometry: angles, poses, twists and their exact integration.

Conventions used across navkit: units are SI (m, rad, s); angles are wrapped to
(-π, π]; world points are ``(x, y)``; twists are expressed in the robot frame.
Wherever navkit takes a pose or a twist, a ``Pose2D``/``Twist2D`` or a sequence of
three numbers works (:func:`as_pose`, :func:`as_twist`).

Ranges: coordinates, angles, velocities are any finite real numbers (complex
numbers, strings and booleans raise ``TypeError``), time steps are finite and
>= 0. A result that would overflow float64 raises ``ValueError`` naming the
argument; no function returns NaN.
"""

from navkit.geometry._angles import angle_diff, wrap_angle
from navkit.geometry._integrate import integrate, rollout
from navkit.geometry._pose import Pose2D, Twist2D, as_pose, as_twist
from navkit.geometry._quaternion import (
    ImuInBase,
    imu_to_base,
    quaternion_to_matrix,
    quaternion_to_yaw,
    rpy_to_quaternion,
    yaw_to_quaternion,
)

__all__ = [
    "ImuInBase",
    "Pose2D",
    "Twist2D",
    "angle_diff",
    "as_pose",
    "as_twist",
    "imu_to_base",
    "integrate",
    "quaternion_to_matrix",
    "quaternion_to_yaw",
    "rollout",
    "rpy_to_quaternion",
    "wrap_angle",
    "yaw_to_quaternion",
]
