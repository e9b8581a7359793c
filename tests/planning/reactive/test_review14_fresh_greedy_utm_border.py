"""Fresh-eyes review of 28b7fc0: stepping until arrival at UTM-sized world coordinates.

``greedy_step`` now ends a walk with the goal itself once it lies in the robot's
cell, "the border included, and 1e-9 of a half cell beyond it for the rounding of
robot-frame coordinates". That rounding is about 1e-16 of the *world* coordinates,
not of the cell: at a UTM northing of 6e6-1e7 m (every southern-hemisphere site)
it is ~1e-9 m, forty times the slack of a 5 cm grid (2.5e-11 m). A goal on the
border between two cells then lies just outside both of them, and the walk steps
back and forth between the two for ever, the bug the change was to fix (measured:
93 of 400 border goals at 5 cm cells, 139 of 400 at 2.5 cm, none at 0.1 m; with a
slack of 1e-6 of a half cell, now the slack, none of them).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LocalGrid
from navkit.planning import greedy_step


def _walk(res: float, start: list[float], goal: list[float]) -> tuple[int, np.ndarray]:
    """Step (heading 0: robot frame = world axes) until ``h == 0``; steps taken (0: never)."""
    grid = LocalGrid.from_points([], half_width=1.0, resolution=res)
    pos, target = np.array(start), np.array(goal)
    for k in range(1, 401):
        step = greedy_step(grid, tuple(target - pos))
        pos = pos + step.waypoint_robot_xy
        if step.h == 0.0:
            return k, pos
    return 0, pos


@pytest.mark.parametrize(
    ("res", "start", "goal"),
    [
        # 2.5 cells south of the start, on a border (northing 9.7e6 m).
        (0.05, [288755.6507464736, 9712844.091841478], [288755.6507464736, 9712843.966841478]),
        # One cell west, 2.5 cells north (northing 6.3e6 m).
        (0.025, [279229.69657929515, 6344362.364952694], [279229.6715792951, 6344362.427452694]),
    ],
)
def test_walk_to_a_border_goal_at_utm_coordinates_arrives(
    res: float, start: list[float], goal: list[float]
) -> None:
    # The goal is on a cell border as seen from the start, up to world rounding.
    offset = (np.array(goal) - np.array(start)) / res
    assert np.abs(offset * 2.0 - np.round(offset * 2.0)).max() < 1e-6
    steps, end = _walk(res, start, goal)
    assert steps > 0, "the walk never arrived (it steps back and forth across the goal)"
    np.testing.assert_allclose(end, goal, rtol=0.0, atol=1e-8)
