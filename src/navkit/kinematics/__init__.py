"""Wheel kinematics: omnidirectional and differential drives, encoders.

Twists are body-frame ``navkit.geometry.Twist2D`` (m/s, m/s, rad/s); wheel
speeds are angular, rad/s; distances are metres.
"""

from navkit.kinematics._diff import DiffDrive, OdometryMethod
from navkit.kinematics._encoders import tick_delta, ticks_to_distance
from navkit.kinematics._omni import OmniDrive

__all__ = ["DiffDrive", "OdometryMethod", "OmniDrive", "tick_delta", "ticks_to_distance"]
