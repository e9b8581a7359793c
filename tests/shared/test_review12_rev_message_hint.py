"""A ROS message passed whole gets advice that works for the argument it was given to.

The hint added for a message given where an array is wanted listed every field
the message has: a ``geometry_msgs/Point`` given as a point ``(x, y)`` (to
``OccupancyGrid.world_to_cell``, ``Pose2D.transform_points``, ``Path2D``) was
told "pass (m.x, m.y, m.z)", and doing so raised a ValueError for the shape. The
fields suggested are now as many as the argument takes per item.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import pytest

import ros_fakes as ros
from navkit.geometry import Pose2D, quaternion_to_yaw
from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D

GRID = OccupancyGrid(np.zeros((4, 4), np.float32), resolution=1.0)


def _advice(call: Any, value: Any) -> str:
    """The ``pass (...)`` tuple the TypeError suggests, as source text."""
    with pytest.raises(TypeError) as info:
        call(value)
    found = re.search(r"pass (\(m\.[^)]*\))$", str(info.value))
    assert found is not None, str(info.value)
    return found.group(1)


@pytest.mark.parametrize(
    "call",
    [
        GRID.world_to_cell,
        Pose2D(1.0, 2.0, 0.5).transform_points,
    ],
    ids=["world_to_cell", "transform_points"],
)
@pytest.mark.parametrize("wrap", [lambda p: p, lambda p: [p, p]], ids=["alone", "in_a_list"])
def test_a_point_given_as_a_2d_point_is_told_to_pass_x_and_y(call: Any, wrap: Any) -> None:
    point = ros.Point(x=1.5, y=2.5, z=0.0)
    advice = _advice(call, wrap(point))
    assert advice == "(m.x, m.y)"
    # The advice works: the same call with the suggested values succeeds.
    m = point
    call(wrap(eval(advice, {"m": m})))


def test_points_of_shape_n_2_are_told_to_pass_x_and_y() -> None:
    # An argument declared shape (None, 2) (a path's vertices).
    point = ros.Point(x=1.5, y=2.5, z=0.0)

    def call(points: Any) -> Path2D:
        return Path2D(points, "world", cost=0.0, length=0.0, expanded=0)

    advice = _advice(call, [point, point])
    assert advice == "(m.x, m.y)"
    m = point
    assert call([eval(advice, {"m": m})] * 2).points.shape == (2, 2)


def test_the_message_still_lists_every_field_it_has() -> None:
    with pytest.raises(TypeError, match=r"type Point with fields x, y, z \(a ROS message\?\)"):
        GRID.world_to_cell(ros.Point(x=1.0, y=2.0, z=0.0))


def test_a_quaternion_still_gets_all_four_fields() -> None:
    q = ros.Quaternion(x=0.0, y=0.0, z=0.0, w=1.0)
    advice = _advice(quaternion_to_yaw, q)
    assert advice == "(m.x, m.y, m.z, m.w)"
    m = q
    assert quaternion_to_yaw(eval(advice, {"m": m})) == 0.0


def test_no_advice_when_the_message_has_fewer_fields_than_wanted() -> None:
    # A Point where a quaternion (4 values) is wanted: "pass (m.x, m.y, m.z)" would be
    # refused again; the error says what it got, without advice.
    from navkit.geometry import imu_to_base

    q = (0.0, 0.0, 0.0, 1.0)
    with pytest.raises(TypeError, match=r"^mount .* type Point$"):
        imu_to_base(q, (0.0, 0.0, 0.0), (0.0, 0.0, 9.8), mount=ros.Point(x=0.0, y=0.0, z=1.0))
