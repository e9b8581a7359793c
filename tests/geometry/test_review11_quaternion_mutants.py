"""quaternion_to_yaw at gimbal lock (mutation testing).

"Where that axis points straight up or down (pitch ±90°) the yaw is undefined
and 0 is returned": a quaternion built for pitch ±π/2 leaves a horizontal
component of a few 1e-16 from rounding, which must still count as straight up
or down (a cut-off at 1e-300 returned atan2 of two rounding errors).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw, rpy_to_quaternion


@pytest.mark.parametrize("pitch", [math.pi / 2, -math.pi / 2])
@pytest.mark.parametrize(("roll", "yaw"), [(0.3, 0.7), (1.0, -2.0), (-2.5, 3.0)])
def test_yaw_is_zero_where_the_x_axis_points_straight_up_or_down(
    roll: float, pitch: float, yaw: float
) -> None:
    q = rpy_to_quaternion(roll, pitch, yaw)
    # The rotated x axis, R[:, 0], is vertical up to rounding.
    x, y, z, w = (float(v) for v in q)
    axis = (1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w))
    assert math.hypot(axis[0], axis[1]) < 1e-12
    assert abs(axis[2]) == pytest.approx(1.0)
    assert quaternion_to_yaw(q) == 0.0
    batch = np.asarray(quaternion_to_yaw(np.stack([q, q])))
    assert batch.tolist() == [0.0, 0.0]
