"""Mutation-testing gaps of ``MapPlanner.plan(..., start_tolerance=...)`` (review 10).

Each test pins a promise of the escape that a wrong line of the candidate
search survived: candidates hidden behind a wall's end although in the start's
region, a candidate exactly ``start_tolerance`` away along a row or a column,
a nearer candidate just outside the first search window, and the refusal
messages of starts that are never escaped. Expected cells come from an
independent brute force (every cell, shapely's closed-set segment test).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from shapely.geometry import LineString, box

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


def brute_escape(
    planner: MapPlanner, start: tuple[float, float], tolerance: float
) -> tuple[int, int]:
    """The documented escape cell: nearest passable centre (ties: lowest (row, col)) whose
    closed segment from the start touches no occupied square."""
    q = np.asarray(planner.grid.world_to_cell(np.array(start), continuous=True), dtype=float)
    hard = planner.grid.occupied()
    # Grown by the documented margin of 1e-9 cell sides (a corner missed by 1e-16 touches).
    g = 0.5 + 1e-9
    squares = [box(r - g, c - g, r + g, c + g) for r, c in np.argwhere(hard)]
    res = planner.grid.resolution
    rows, cols = planner.costs.shape
    candidates = sorted(
        ((r - q[0]) ** 2 + (c - q[1]) ** 2, r, c)
        for r in range(rows)
        for c in range(cols)
        if math.isfinite(planner.costs[r, c])
        and math.hypot(r - q[0], c - q[1]) * res <= tolerance
    )
    for _, r, c in candidates:
        if not any(LineString([tuple(q), (r, c)]).intersects(s) for s in squares):
            return r, c
    raise AssertionError("no escape expected")


def escape_cell(planner: MapPlanner, start: tuple[float, float], goal: tuple[float, float],
                tolerance: float) -> tuple[int, int]:
    path = planner.plan(start, goal, start_tolerance=tolerance)
    np.testing.assert_array_equal(path.points[0], start)
    cell = tuple(int(v) for v in planner.grid.world_to_cell(path.points[1]))
    np.testing.assert_allclose(path.points[1], planner.grid.cell_to_world(cell), atol=1e-12)
    return cell  # type: ignore[return-value]


def test_a_nearer_centre_behind_the_end_of_a_wall_is_not_taken() -> None:
    # Wall at col 1, rows 1..4, radius 1.5 cells. The start (continuous (1.98, 0.38),
    # cell (2, 0), band) sees free cell (2, 3) 2.6 cells away across the wall; the
    # region around the wall's ends joins them, so only the segment test refuses it.
    occupied = np.zeros((12, 12), dtype=bool)
    occupied[1:5, 1] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=1.0), robot_radius=1.5)
    start = (0.88, 2.48)
    assert not math.isfinite(planner.costs[2, 0]) and math.isfinite(planner.costs[2, 3])
    expected = brute_escape(planner, start, 5.0)
    assert expected != (2, 3)
    assert escape_cell(planner, start, (11.5, 11.5), 5.0) == expected


@pytest.mark.parametrize("axis", [0, 1])
@pytest.mark.parametrize("sign", [1, -1])
def test_a_centre_exactly_start_tolerance_away_along_an_axis_is_taken(axis: int, sign: int) -> None:
    # A one-cell wall, radius 2 cells: the start's cell centre (band, 1 cell from
    # the wall) has its only reachable passable centre 2 cells away, straight away
    # from the wall; tolerance exactly 2 cells (resolution 1: exact arithmetic).
    n = 13
    occupied = np.zeros((n, n), dtype=bool)
    wall = 6 - sign * 1
    if axis == 0:
        occupied[wall, :] = True
    else:
        occupied[:, wall] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=1.0), robot_radius=2.0)
    centre = (6, 6)
    target = (6 + sign * 2, 6) if axis == 0 else (6, 6 + sign * 2)
    assert not math.isfinite(planner.costs[centre]) and math.isfinite(planner.costs[target])
    start = tuple(float(v) for v in planner.grid.cell_to_world(centre))
    goal_cell = (6 + sign * 5, 6) if axis == 0 else (6, 6 + sign * 5)
    goal = tuple(float(v) for v in planner.grid.cell_to_world(goal_cell))
    assert brute_escape(planner, start, 2.0) == target  # type: ignore[arg-type]
    assert escape_cell(planner, start, goal, 2.0) == target  # type: ignore[arg-type]


def test_a_nearer_centre_beyond_the_first_search_window_wins() -> None:
    # One obstacle cell left of the start, radius 11 cells: no passable centre
    # within 10 cells; the nearest, (19, 30), lies 10 columns away, while a
    # farther one, (15, 29), lies within 9 rows and columns of the start.
    occupied = np.zeros((41, 41), dtype=bool)
    occupied[20, 19] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=1.0), robot_radius=11.0)
    start = (20.5, 20.5)  # the centre of cell (20, 20)
    expected = brute_escape(planner, start, 11.0)
    assert expected == (19, 30)
    assert math.isfinite(planner.costs[15, 29])
    assert escape_cell(planner, start, (35.5, 20.5), 11.0) == expected


def obstacle_and_unknown_planner() -> MapPlanner:
    occupied = np.zeros((12, 12), dtype=bool)
    occupied[5, 5] = True
    unknown: NDArray[np.bool_] = np.zeros((12, 12), dtype=bool)
    unknown[0, 11] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    return MapPlanner(grid, robot_radius=0.1)


@pytest.mark.parametrize("tolerance", [0.0, 10.0])
@pytest.mark.parametrize(
    ("start", "reason"),
    [((0.55, 0.55), "is in an obstacle"), ((1.15, 0.05), r"is in unknown space")],
)
def test_starts_never_escaped_say_why_without_the_escape_wording(
    start: tuple[float, float], reason: str, tolerance: float
) -> None:
    # Passable centres lie next to these starts: a hint to pass start_tolerance, or a
    # refusal saying no centre is reachable within it, would both be wrong.
    planner = obstacle_and_unknown_planner()
    with pytest.raises(ValueError, match=reason) as info:
        planner.plan(start, (0.25, 0.25), start_tolerance=tolerance)
    assert "start_tolerance" not in str(info.value)


def test_a_start_on_an_obstacle_square_s_edge_touches_it_and_is_refused() -> None:
    # Obstacle (5, 5), radius one cell: (6, 5) is band. A start exactly on the
    # edge the two cells share (continuous row 5.5) lies in (6, 5) but every
    # segment from it touches the obstacle's square: "a segment touching such a
    # cell's square ... crosses it", so nothing qualifies. A micrometre away from
    # the edge the start escapes.
    occupied = np.zeros((11, 11), dtype=bool)
    occupied[5, 5] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=1.0), robot_radius=1.0)
    goal = (9.5, 9.5)
    on_edge = (5.5, 6.0)
    assert tuple(int(v) for v in planner.grid.world_to_cell(np.array(on_edge))) == (6, 5)
    assert not math.isfinite(planner.costs[6, 5])
    with pytest.raises(ValueError, match="no passable cell centre within start_tolerance"):
        planner.plan(on_edge, goal, start_tolerance=3.0)
    off_edge = (5.5, 6.0 + 1e-6)
    cell = escape_cell(planner, off_edge, goal, 3.0)
    assert cell == brute_escape(planner, off_edge, 3.0)
