"""Poses at the world entry points of the planners: decided by the names (review 54, FOUND7).

``MapPlanner.plan(start, goal)`` took a pose ``(x, y, theta)`` (its position),
while ``FieldDStar.plan_world(start_xy, goal_xy)`` refused one with the hint
"a pose [x, y, theta]? pass its [:2]" (0921381). Decided: the names say which,
as the README's conventions now state: a ``_xy`` argument is a point and
refuses a pose with that hint, everywhere; ``MapPlanner.plan`` and
``plan_path``, whose ends have no suffix, are the robot-level calls and take a
point or a pose. Both docstrings say so; this pins both sides.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner, plan_path


def _grid() -> OccupancyGrid:
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(2.0, -1.0, 0.4))


def _ends(grid: OccupancyGrid) -> tuple[np.ndarray, np.ndarray]:
    cells = np.array([[2.2, 4.3], [2.6, 15.4]])
    start, goal = np.asarray(grid.cell_to_world(cells), dtype=np.float64)
    return start, goal


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_map_planner_and_plan_path_take_a_robots_pose(
    planner: Literal["astar", "field_dstar"],
) -> None:
    grid = _grid()
    start, goal = _ends(grid)
    mapped = MapPlanner(grid, robot_radius=0.1, planner=planner)
    want = mapped.plan(start, goal)
    for a, b in (
        (Pose2D(start[0], start[1], 1.0), Pose2D(goal[0], goal[1], -2.0)),
        ((*start, 1.0), [*goal, 3.0]),
    ):
        got = mapped.plan(a, b)
        assert got.points.tobytes() == want.points.tobytes()
        assert (got.cost, got.length) == (want.cost, want.length)
        once = plan_path(grid, a, b, robot_radius=0.1, planner=planner)
        assert once.points.tobytes() == want.points.tobytes()


def test_field_dstar_world_points_refuse_a_pose_with_the_way_out() -> None:
    grid = _grid()
    start, goal = _ends(grid)
    planner = FieldDStar(grid.traversal_costs(), resolution=0.1, origin=(2.0, -1.0, 0.4))
    pose = np.array([*start, 0.5])
    with pytest.raises(ValueError, match=r"start_xy .*a pose \[x, y, theta\]\? pass its \[:2\]"):
        planner.plan_world(pose, goal)
    with pytest.raises(ValueError, match=r"goal_xy .*pass its \[:2\]"):
        planner.plan_world(start, (*goal, 0.5))
    path = planner.plan_world(pose[:2], goal)
    assert path.points[0].tolist() == start.tolist()
    with pytest.raises(ValueError, match=r"start_xy .*pass its \[:2\]"):
        planner.replan_world(pose)
    assert planner.replan_world(pose[:2]).points.tobytes() == path.points.tobytes()
