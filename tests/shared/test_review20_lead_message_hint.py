"""A navkit object where numbers are wanted is named in the advice (review 20).

The advice for an object with x and y fields read "pass (m.x, m.y)" with ``m``
unexplained; for a ROS message that is the usual name, for a navkit ``Pose2D``
it is not. The advice now names the variable it means, and following it works.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid

GRID = OccupancyGrid(np.zeros((4, 4), np.float32), resolution=1.0)


@pytest.mark.parametrize("wrap", [lambda p: p, lambda p: [p, p]], ids=["alone", "in_a_list"])
def test_a_pose_where_points_are_wanted_is_told_what_to_pass(wrap: object) -> None:
    pose = Pose2D(1.5, 2.5, 0.3)
    with pytest.raises(TypeError) as info:
        GRID.world_to_cell(wrap(pose))  # type: ignore[operator]
    found = re.search(r"pass (\(p\.x, p\.y\)) of that Pose2D p$", str(info.value))
    assert found is not None, str(info.value)
    cells = GRID.world_to_cell(wrap(eval(found.group(1), {"p": pose})))  # type: ignore[operator]
    assert np.asarray(cells).reshape(-1, 2).tolist()[0] == [2, 1]
