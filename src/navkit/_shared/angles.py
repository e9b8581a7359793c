"""Private pure-Python angle wrapping, shared by every layer that wraps one float.

:func:`navkit.geometry.wrap_angle` (its float path), :class:`navkit.geometry.Pose2D`
and the path trackers of :mod:`navkit.control` wrap single Python floats here;
compiled kernels use :func:`navkit._shared.se2.wrap_scalar`, the same operations.
"""

from __future__ import annotations

import math

_TWO_PI = 2.0 * math.pi


def wrap_float(a: float) -> float:
    """Wrap one finite Python float to (-π, π], bit for bit :func:`~navkit.geometry.wrap_angle`.

    ``math.fmod`` is exact (``a - k * 2π`` with no rounding), and so is the one
    fold into (-π, π] (Sterbenz: both operands within a factor 2). Not
    ``pi - ((pi - a) % 2pi)``: its difference and the divisor ``%`` adds to a
    negative remainder are rounded, up to 6e4 ulps of the result for angles below
    100 rad and all of its bits beyond 1e19.
    """
    if -math.pi < a <= math.pi:
        return a
    r = math.fmod(a, _TWO_PI)
    if r > math.pi:
        return r - _TWO_PI
    return r + _TWO_PI if r <= -math.pi else r
