"""Greedy laser-grid planner: the paper's example, a brute-force oracle, dead ends."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.lines import line_cells
from navkit.errors import NoPathError
from navkit.mapping import LaserScan, LocalGrid
from navkit.planning import GreedyStep, greedy_step


def flat_face_scan(distance: float, half_width: float, n: int = 360) -> LaserScan:
    """Scan of a flat obstacle face ``distance`` ahead spanning ``|y| <= half_width``."""
    th = -math.pi + 2.0 * math.pi * np.arange(n) / n
    with np.errstate(divide="ignore"):
        r = distance / np.cos(th)
    hit = (np.cos(th) > 0) & (np.abs(r * np.sin(th)) <= half_width)
    return LaserScan(np.where(hit, r, math.inf), angle_min=-math.pi,
                     angle_increment=2.0 * math.pi / n, range_min=0.05, range_max=3.5)


def test_obstacle_straight_ahead_chooses_a_side_cell() -> None:
    # The paper's 21 x 21 grid of 0.1 m cells, a box face 0.1 m ahead, goal 3 m ahead.
    grid = flat_face_scan(0.1, 0.15).to_local_grid()
    assert grid.occupied.shape == (21, 21)
    assert grid.occupied[10, 11]  # i = 10y + 10, j = 10x + 10: straight ahead is blocked
    step = greedy_step(grid, (3.0, 0.0))
    row, col = step.cell
    assert row != 10  # a side cell
    assert not grid.occupied[row, col]
    assert all(not grid.occupied[r, c] for r, c in line_cells(10, 10, row, col))
    assert step.waypoint_robot_xy[0] >= 0.0  # sideways, not back
    best, winners = brute_force(grid.occupied, 0.1, 1.0, np.array([3.0, 0.0]), False)
    assert step.cell in winners and step.cost == pytest.approx(best)
    np.testing.assert_allclose(step.waypoint_robot_xy, [0.1 * col - 1.0, 0.1 * row - 1.0])
    assert step.g + step.h == pytest.approx(step.cost)
    assert step.cost > 3.0  # the detour costs more than the straight line


def test_repeated_steps_go_up_to_the_obstacle_then_sideways() -> None:
    # An obstacle 0.5 m ahead: every free axis cell in front of it lies on the straight
    # line (g + h = 3 exactly) and the tie goes to the one nearest the goal.
    first = greedy_step(flat_face_scan(0.5, 0.15).to_local_grid(), (3.0, 0.0))
    assert first.cell == (10, 14)
    np.testing.assert_allclose(first.waypoint_robot_xy, [0.4, 0.0], atol=1e-12)
    # Having moved there the face is 0.1 m ahead and the next step turns aside.
    second = greedy_step(flat_face_scan(0.1, 0.15).to_local_grid(), (2.6, 0.0))
    assert second.cell[0] != 10


def test_free_grid_heads_straight_for_the_goal_on_any_grid_size() -> None:
    grid = LocalGrid.from_points(np.empty((0, 2)), half_width=2.0, resolution=0.05)
    assert grid.occupied.shape == (81, 81)
    step = greedy_step(grid, (10.0, 0.0))
    np.testing.assert_allclose(step.waypoint_robot_xy, [2.0, 0.0])
    assert step.candidates == 81 * 81 - 1
    # A goal inside the grid is chosen itself.
    inside = greedy_step(grid, (0.55, -0.3))
    np.testing.assert_allclose(inside.waypoint_robot_xy, [0.55, -0.3], atol=1e-12)
    assert inside.h == pytest.approx(0.0, abs=1e-12)


def brute_force(occupied: np.ndarray, res: float, half: float, goal: np.ndarray,
                progress: bool) -> tuple[float, set[tuple[int, int]]]:
    """Best g + h over all visible free cells, and the cells tying with it.

    Ties are within ``1e-12·(‖goal‖ + half_width)``, the documented tolerance.
    """
    n = occupied.shape[0]
    c0 = n // 2
    occ = occupied.copy()
    occ[c0, c0] = False
    h_robot = float(np.hypot(*goal))
    costs: dict[tuple[int, int], float] = {}
    for i in range(n):
        for j in range(n):
            if (i, j) == (c0, c0) or occ[i, j]:
                continue
            p = np.array([j * res - half, i * res - half])
            h = float(np.hypot(*(goal - p)))
            if progress and not h < h_robot:
                continue
            if any(occ[r, c] for r, c in line_cells(c0, c0, i, j)):
                continue
            costs[(i, j)] = float(np.hypot(*p)) + h
    if not costs:
        return math.inf, set()
    best = min(costs.values())
    tol = 1e-12 * (h_robot + half)
    return best, {cell for cell, f in costs.items() if f <= best + tol}


@settings(max_examples=60, deadline=None)
@given(
    st.integers(1, 8),
    st.sampled_from([0.05, 0.1, 0.25]),
    st.floats(0.0, 0.6),
    st.integers(0, 2**32 - 1),
    st.tuples(st.floats(-4.0, 4.0), st.floats(-4.0, 4.0)),
    st.booleans(),
)
def test_matches_brute_force(
    half_cells: int, res: float, density: float, seed: int, goal: tuple[float, float],
    progress: bool,
) -> None:
    n = 2 * half_cells + 1
    occupied = np.random.default_rng(seed).random((n, n)) < density
    grid = LocalGrid(occupied, resolution=res, half_width=half_cells * res)
    reach = 0.5 * res * (1.0 + 1e-6)  # the robot's own cell, border included
    if abs(goal[0]) <= reach and abs(goal[1]) <= reach:
        # The goal in the robot's cell: the last step, to the goal itself.
        step = greedy_step(grid, goal, require_progress=progress)
        assert step.cell == (half_cells, half_cells) and step.h == 0.0
        assert step.g == pytest.approx(math.hypot(*goal), rel=1e-15)
        np.testing.assert_array_equal(step.waypoint_robot_xy, goal)
        return
    best, winners = brute_force(occupied, res, half_cells * res, np.array(goal), progress)
    if not winners:
        with pytest.raises(NoPathError):
            greedy_step(grid, goal, require_progress=progress)
        return
    step = greedy_step(grid, goal, require_progress=progress)
    assert step.cost == pytest.approx(best, abs=1e-8)
    assert step.cell in winners
    # Among tied cells the one nearest the goal.
    h_of = {c: math.hypot(goal[0] - (c[1] * res - half_cells * res),
                          goal[1] - (c[0] * res - half_cells * res)) for c in winners}
    assert step.h == pytest.approx(min(h_of.values()), abs=1e-12)


def boxed(cells: list[tuple[int, int]]) -> LocalGrid:
    occ = np.zeros((21, 21), dtype=bool)
    for r, c in cells:
        occ[r, c] = True
    return LocalGrid(occ, resolution=0.1, half_width=1.0)


def test_walled_in_robot_raises_no_path() -> None:
    ring = [(10 + dr, 10 + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if (dr, dc) != (0, 0)]
    with pytest.raises(NoPathError, match="line of sight") as info:
        greedy_step(boxed(ring), (3.0, 0.0))
    assert info.value.expanded == 21 * 21 - 9


def test_goal_behind_a_wall_with_progress_required_raises() -> None:
    # A cup open toward the back: every cell nearer the goal is hidden behind the wall.
    cup = [(r, 11) for r in range(0, 21)] + [(9, 10), (11, 10)]
    cup += [(9, c) for c in range(0, 10)] + [(11, c) for c in range(0, 10)]
    grid = boxed(cup)
    with pytest.raises(NoPathError, match="nearer the goal"):
        greedy_step(grid, (3.0, 0.0), require_progress=True)
    # The paper's rule has no such restriction: it retreats along the corridor behind.
    step = greedy_step(grid, (3.0, 0.0))
    assert step.cell[0] == 10 and step.cell[1] < 10


def test_return_in_the_robot_cell_does_not_block() -> None:
    grid = LocalGrid.from_points([[0.0, 0.0]])
    assert grid.occupied[10, 10]
    waypoint = greedy_step(grid, (0.0, 5.0)).waypoint_robot_xy
    np.testing.assert_allclose(waypoint, [0.0, 1.0], atol=1e-12)


def test_bad_input() -> None:
    grid = LocalGrid.from_points([])
    with pytest.raises(ValueError, match="goal_robot_xy"):
        greedy_step(grid, (math.nan, 0.0))
    with pytest.raises(ValueError, match="goal_robot_xy"):
        greedy_step(grid, (1.0, 0.0, 0.0))
    with pytest.raises(TypeError, match="local_grid"):
        greedy_step(np.zeros((21, 21), dtype=bool), (1.0, 0.0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="require_progress"):
        greedy_step(grid, (1.0, 0.0), require_progress=1)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="require_progress"):
        greedy_step(grid, (1.0, 0.0), require_progress="no")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="positional"):
        greedy_step(grid, (1.0, 0.0), True)  # type: ignore[misc]
    assert greedy_step(grid, (1.0, 0.0), require_progress=np.bool_(True)).cell == (10, 20)


def test_inputs_are_not_modified() -> None:
    # The robot's own cell is cleared on a copy, never on the grid or the goal.
    grid = LocalGrid.from_points([[0.0, 0.0], [0.3, 0.0]])
    before = grid.occupied.copy()
    goal = np.array([1.0, 0.5])
    greedy_step(grid, goal)
    np.testing.assert_array_equal(grid.occupied, before)
    np.testing.assert_array_equal(goal, [1.0, 0.5])
    assert goal.flags.writeable


def test_greedy_step_is_a_frozen_result() -> None:
    step = greedy_step(LocalGrid.from_points([]), (2.0, 0.0))
    assert (step.cell, step.candidates) == ((10, 20), 21 * 21 - 1)
    assert isinstance(step.cell[0], int) and isinstance(step.g, float)
    with pytest.raises(dataclasses.FrozenInstanceError):
        step.g = 0.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        step.waypoint_robot_xy[0] = 5.0
    assert not hasattr(step, "__dict__")
    waypoint = np.array([0.2, 0.0])
    built = GreedyStep((10, 12), waypoint, 0.2, 1.8, 440)
    waypoint[0] = 9.0
    assert built.waypoint_robot_xy[0] == 0.2 and built.cost == pytest.approx(2.0)
    with pytest.raises(ValueError, match="waypoint_xy"):
        GreedyStep((10, 12), (0.2, 0.0, 0.0), 0.2, 1.8, 440)


def test_copied_and_unpickled_steps_stay_read_only(
    duplicate: Callable[[GreedyStep], GreedyStep],
) -> None:
    step = greedy_step(LocalGrid.from_points([[0.1, 0.0]]), (2.0, 0.0))
    copy = duplicate(step)
    assert (copy.cell, copy.g, copy.h, copy.candidates) == (
        step.cell, step.g, step.h, step.candidates
    )
    np.testing.assert_array_equal(copy.waypoint_robot_xy, step.waypoint_robot_xy)
    with pytest.raises(ValueError, match="read-only"):
        copy.waypoint_robot_xy[0] = 5.0
