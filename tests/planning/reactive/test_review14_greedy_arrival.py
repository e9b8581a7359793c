"""``greedy_step`` with the goal in the robot's own cell: the last step, to the goal.

No candidate is the robot's own cell, so a caller stepping "until arrival" used
to stop one neighbour short of a goal inside it (or step back and forth across
it). The step is now the goal itself, with ``h == 0``: its cost ``|goal|`` is the
least any cell can have, so the paper's rule is unchanged everywhere else.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.mapping import LocalGrid
from navkit.planning import greedy_step

EMPTY = LocalGrid.from_points([])


@pytest.mark.parametrize("progress", [False, True])
@pytest.mark.parametrize(
    "goal", [(0.03, -0.04), (-0.049, 0.049), (0.05, -0.05), (-0.05, 0.0), (0.0, 0.0), (5e-324, 0.0)]
)
def test_goal_in_the_robot_cell_is_the_last_step(goal: tuple[float, float], progress: bool) -> None:
    step = greedy_step(EMPTY, goal, require_progress=progress)
    assert step.cell == (10, 10)
    np.testing.assert_array_equal(step.waypoint_robot_xy, goal)
    assert step.h == 0.0
    assert step.g == pytest.approx(math.hypot(*goal), rel=1e-15, abs=0.0)
    assert step.cost == step.g


def test_goal_just_outside_the_robot_cell_is_a_neighbour() -> None:
    step = greedy_step(EMPTY, (0.05 * (1.0 + 1e-5), 0.0))
    assert step.cell == (10, 11) and step.h > 0.0
    np.testing.assert_array_equal(step.waypoint_robot_xy, EMPTY.cell_to_world([10, 11]))


def test_walled_in_robot_still_arrives_in_its_own_cell() -> None:
    # Returns all around, and one in the robot's own cell (which never blocks).
    ring = [[0.1 * dx, 0.1 * dy] for dx in (-1, 0, 1) for dy in (-1, 0, 1)]
    grid = LocalGrid.from_points(ring)
    assert grid.occupied[9:12, 9:12].all()
    step = greedy_step(grid, (0.02, 0.01))
    assert step.cell == (10, 10) and step.h == 0.0
    # A goal beyond the ring is still unreachable.
    with pytest.raises(NoPathError, match="line of sight"):
        greedy_step(grid, (0.3, 0.0))


def _walk(
    start: np.ndarray, goal: np.ndarray, heading: float, grid: LocalGrid
) -> tuple[int, np.ndarray]:
    """Step in the world frame until a step's h is 0; the steps taken and the final position."""
    c, s = math.cos(heading), math.sin(heading)
    pos = start.copy()
    for k in range(1, 401):
        dx, dy = goal - pos
        step = greedy_step(grid, (c * dx + s * dy, -s * dx + c * dy))
        wx, wy = step.waypoint_robot_xy
        pos = pos + np.array([c * wx - s * wy, s * wx + c * wy])
        if step.h == 0.0:
            return k, pos
    return 0, pos


@settings(max_examples=40, deadline=None)
@given(
    st.tuples(st.floats(-100.0, 100.0), st.floats(-100.0, 100.0)),
    st.tuples(st.floats(-4.0, 4.0), st.floats(-4.0, 4.0)),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.05, 0.1, 0.25]),
)
def test_stepping_until_arrival_reaches_the_goal(
    start: tuple[float, float], offset: tuple[float, float], heading: float, res: float
) -> None:
    grid = LocalGrid.from_points([], half_width=10 * res, resolution=res)
    origin = np.array(start)
    goal = origin + np.array(offset)
    steps, end = _walk(origin, goal, heading, grid)
    assert steps > 0, "never arrived"
    # The last step lands on the goal, up to the rounding of world coordinates.
    assert np.abs(end - goal).max() <= 1e-12 * (np.abs(goal).max() + 1.0)


test_stepping_until_arrival_reaches_the_goal_thoroughly = slow_twin(
    test_stepping_until_arrival_reaches_the_goal, max_examples=300
)


def test_goal_on_a_cell_border_is_reached_from_either_side() -> None:
    # Robot frames made from world coordinates put a goal on the border between the
    # robot's cell and a neighbour's on either side by rounding: the walk must not
    # step back and forth across it.
    for x0 in (0.0, 0.1, 0.3, 1e3 + 0.1):
        goal = np.array([x0 + 0.05, 0.0])
        steps, end = _walk(np.array([x0, 0.0]), goal, 0.0, EMPTY)
        assert steps == 1 and np.abs(end - goal).max() <= 1e-12 * (x0 + 1.0)
