"""MapPlanner's exact ends on awkward points: cell borders and corners, rotated maps, one cell.

The fresh-eyes review of the exact-ends change (session 22) tried to break
it with points on the borders and corners of their cells, on maps whose
origin is turned, with start and goal in one cell or equal, for both built-in
planners: the path begins and ends at the points given, bit for bit, and no
segment of it (the links to the cells' centres included) enters a blocked
cell or leaves the map. Its length is its polyline's; its cost is at least
its length (every passable cell costs at least 1).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from navkit import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner

#: Where in its cell (fractions of a cell along x and y) a point may lie.
_SPOTS = st.one_of(
    st.tuples(st.floats(0.0, 0.999), st.floats(0.0, 0.999)),
    st.sampled_from([(0.0, 0.0), (0.5, 0.5), (0.0, 0.5), (0.5, 0.0), (0.0, 0.999)]),
)


@st.composite
def _cases(draw: st.DrawFn) -> tuple[OccupancyGrid, np.ndarray, str, np.ndarray, np.ndarray]:
    rows, cols = draw(st.integers(2, 9)), draw(st.integers(2, 9))
    seed = draw(st.integers(0, 2**32 - 1))
    occupied = np.random.default_rng(seed).random((rows, cols)) < 0.2
    free = np.argwhere(~occupied)
    if free.size == 0:
        occupied[0, 0] = False
        free = np.argwhere(~occupied)
    resolution = draw(st.sampled_from([0.05, 0.1, 0.3, 1.0]))
    yaw = draw(st.sampled_from([0.0, 0.3, -2.0, math.pi / 2, math.pi]))
    origin = (draw(st.floats(-5.0, 5.0)), draw(st.floats(-5.0, 5.0)), yaw)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=resolution, origin=origin)

    def point() -> np.ndarray:
        row, col = free[draw(st.integers(0, len(free) - 1))]
        u, v = draw(_SPOTS)
        local = [[(col + u) * resolution, (row + v) * resolution]]
        return np.asarray(grid.origin.transform_points(local)[0], dtype=np.float64)

    start = point()
    goal = start.copy() if draw(st.booleans()) and draw(st.booleans()) else point()
    planner = draw(st.sampled_from(["astar", "field_dstar"]))
    return grid, occupied, planner, start, goal


def _cell_of(grid: OccupancyGrid, point: np.ndarray) -> tuple[int, int]:
    row, col = grid.world_to_cell(point)
    return int(row), int(col)


def _in_free_cell(grid: OccupancyGrid, occupied: np.ndarray, point: np.ndarray) -> bool:
    """Whether ``point`` lies in a free cell, or on the border of one (rounding)."""
    rows, cols = occupied.shape
    scale = 1e-9 * grid.resolution
    for dx, dy in itertools.product((0.0, scale, -scale), repeat=2):
        row, col = _cell_of(grid, point + np.array((dx, dy)))
        if 0 <= row < rows and 0 <= col < cols and not occupied[row, col]:
            return True
    return False


@settings(max_examples=60, deadline=None)
@given(case=_cases())
def test_paths_begin_and_end_at_the_points_and_keep_to_free_cells(
    case: tuple[OccupancyGrid, np.ndarray, str, np.ndarray, np.ndarray],
) -> None:
    grid, occupied, planner, start, goal = case
    # A point on the border of a free cell belongs to the cell above or right of
    # it (or, rounded on a turned map, none): the planner refuses it, rightly.
    for point in (start, goal):
        row, col = _cell_of(grid, point)
        rows, cols = occupied.shape
        assume(0 <= row < rows and 0 <= col < cols and not occupied[row, col])
    try:
        path = MapPlanner(grid, robot_radius=0.0, planner=planner).plan(start, goal)
    except NoPathError:
        return  # walled off: nothing to check
    points = path.points
    assert points[0].tobytes() == start.tobytes() and points[-1].tobytes() == goal.tobytes()
    if start.tobytes() == goal.tobytes():
        assert len(points) == 1 and path.cost == 0.0 and path.length == 0.0
    for a, b in itertools.pairwise(points):
        for t in np.linspace(0.0, 1.0, 41):
            # The ends themselves, not a + (b - a) rounded.
            on = a if t == 0.0 else b if t == 1.0 else a + t * (b - a)
            assert _in_free_cell(grid, occupied, on), (a, b, t)
    length = float(np.hypot(*np.diff(points, axis=0).T).sum())
    assert path.length == pytest.approx(length, rel=1e-12, abs=1e-12)
    assert path.cost >= path.length * (1.0 - 1e-12)


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_a_start_and_goal_in_one_cell_are_joined_straight(planner: str) -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((3, 3), dtype=bool), resolution=0.5)
    map_planner = MapPlanner(grid, robot_radius=0.0, planner=planner)
    # Opposite corners of the middle cell (the far one still inside it) and a point on its border.
    path = map_planner.plan((0.5, 0.5), (0.999, 0.75))
    assert path.points.tolist() == [[0.5, 0.5], [0.999, 0.75]]
    assert path.length == path.cost == pytest.approx(math.hypot(0.499, 0.25))
