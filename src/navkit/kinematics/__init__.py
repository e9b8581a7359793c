"""Wheel kinematics: omnidirectional and differential drives, encoders.

Twists are body-frame ``navkit.geometry.Twist2D`` (m/s, m/s, rad/s); wheel
speeds are angular, rad/s; distances are metres. Every drive follows one
convention: ``inverse(twist)`` returns the wheel speeds as an array of shape
(N,) (``[left, right]`` for :class:`DiffDrive`), ``forward(wheel_speeds)``
returns a ``Twist2D``, and the ``_batch`` forms map (T, 3) twists to (T, N)
wheel speeds and back.

Ranges: track width, wheel radii and base radius in [1e-6, 1e6] m; encoder
resolution in [1, 1e12] counts per revolution; counters of 2 to 64 bits. Speeds
and distances are any finite numbers; a result that would overflow float64
raises ``ValueError`` naming the argument, never NaN.
"""

from navkit.kinematics._diff import DiffDrive, OdometryMethod
from navkit.kinematics._encoders import tick_delta, ticks_to_distance
from navkit.kinematics._omni import OmniDrive

__all__ = ["DiffDrive", "OdometryMethod", "OmniDrive", "tick_delta", "ticks_to_distance"]
