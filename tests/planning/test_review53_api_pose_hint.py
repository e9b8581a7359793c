"""A pose (x, y, theta) given where one world point is wanted: the message says the way out.

Review 52's PIPELINE user handed FieldDStar.plan_world a robot pose; it was
refused as "start_xy must have length 2 along axis 0, got shape (3,)", where
rows of poses given for points already got "pass its [:, :2]" (ce1b1fc).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar

HINT = r"\(a pose \[x, y, theta\]\? pass its \[:2\]\)"


@pytest.fixture
def planner() -> FieldDStar:
    return FieldDStar(np.ones((10, 10)), resolution=0.5)


def test_plan_world_names_a_pose_start(planner: FieldDStar) -> None:
    with pytest.raises(
        ValueError,
        match=r"^start_xy must have length 2 along axis 0, "
        r"got shape \(3,\) " + HINT,
    ):
        planner.plan_world((1.0, 1.0, 0.3), (4.0, 4.0))


def test_plan_world_names_a_pose_goal(planner: FieldDStar) -> None:
    with pytest.raises(ValueError, match=r"^goal_xy .* " + HINT):
        planner.plan_world((1.0, 1.0), np.array([4.0, 4.0, -1.0]))


def test_replan_world_names_a_pose_start(planner: FieldDStar) -> None:
    planner.plan_world((1.0, 1.0), (4.0, 4.0))
    with pytest.raises(ValueError, match=r"^start_xy .* " + HINT):
        planner.replan_world([1.5, 1.0, 0.0])


def test_the_hint_passes_what_it_says(planner: FieldDStar) -> None:
    pose = np.array([1.0, 1.0, 0.3])
    path = planner.plan_world(pose[:2], (4.0, 4.0))
    assert path.points[0].tolist() == [1.0, 1.0]


def test_world_to_cell_and_world_to_node_name_a_pose(planner: FieldDStar) -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
    with pytest.raises(
        ValueError,
        match=r"^points_xy must have shape \(N, 2\) or \(2,\), "
        r"got \(3,\) " + HINT,
    ):
        grid.world_to_cell((1.0, 1.0, 0.0))
    with pytest.raises(ValueError, match=HINT):
        planner.world_to_node((1.0, 1.0, 0.0))


def test_other_shapes_keep_their_messages(planner: FieldDStar) -> None:
    with pytest.raises(
        ValueError,
        match=r"^start_xy must have length 2 along axis 0, "
        r"got shape \(4,\)$",
    ):
        planner.plan_world((1.0, 1.0, 0.0, 0.0), (4.0, 4.0))
    with pytest.raises(ValueError, match=r"^start_xy must be 1-D, got shape \(1, 2\)"):
        planner.plan_world([[1.0, 1.0]], (4.0, 4.0))
    with pytest.raises(ValueError, match=r"^start_xy must contain only finite values$"):
        planner.plan_world((1.0, np.nan), (4.0, 4.0))
    with pytest.raises(TypeError, match=r"^start_xy must hold real numbers"):
        planner.plan_world(("a", "b"), (4.0, 4.0))
    # The refusal is the check's: nothing was planned.
    with pytest.raises(RuntimeError, match="call plan"):
        planner.replan_world()
