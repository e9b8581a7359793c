"""``MapPlanner.plan(start_tolerance=...)`` skips candidates hidden behind a wall.

A start deep in a bent corridor that lies wholly in the inflated band sees no
passable cell in a straight line; with a large tolerance every passable cell
of the map is a candidate. The escape used to test each candidate's segment
(each test as large as the segment's bounding box): 90 s on a 400 × 400 map,
hours on 2000 × 2000. A hard cell that blocks one segment now hides every
candidate behind it, so only a few segments are tested. The work is counted
through the segment tests, not timed.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.planning.grid import _escape


def corridor_planner(n: int, exit_open: bool) -> tuple[MapPlanner, tuple[int, int]]:
    """A room on top, a band-only corridor below it: east from the start, then north."""
    occupied = np.ones((n, n), dtype=bool)
    room = n // 2
    occupied[1:room, 1:-1] = False
    occupied[room + 18 : room + 23, 10:33] = False  # 5 cells wide, radius 3 cells
    occupied[room : room + 23, 28:33] = False
    if exit_open:
        # A slot in the corridor's far wall, straight east of the start, onto a
        # free pocket: the one visible escape, far beyond the corridor's bend.
        occupied[room + 20, 33:40] = False
        occupied[room + 14 : room + 27, 40:60] = False
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    return MapPlanner(grid, robot_radius=0.15), (room + 20, 12)


def counting(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    calls = [0]
    real = _escape._segment_cells

    def wrapped(*args: object) -> object:
        calls[0] += 1
        return real(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(_escape, "_segment_cells", wrapped)
    return calls


def test_a_start_with_every_candidate_hidden_tests_few_segments(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    planner, cell = corridor_planner(120, exit_open=False)
    assert not np.isfinite(planner.costs[cell])
    candidates = int(np.isfinite(planner.costs).sum())
    assert candidates > 2000
    calls = counting(monkeypatch)
    start = planner.grid.cell_to_world(cell)
    with pytest.raises(ValueError, match="no passable cell centre within start_tolerance"):
        planner.plan(start, planner.grid.cell_to_world((10, 60)), start_tolerance=1e9)
    # Every candidate was tested before (one segment test each, in each disc).
    assert calls[0] < candidates // 20


def test_the_one_visible_candidate_is_still_found(monkeypatch: pytest.MonkeyPatch) -> None:
    planner, cell = corridor_planner(120, exit_open=True)
    start = planner.grid.cell_to_world(cell)
    goal = planner.grid.cell_to_world((cell[0], 55))  # in the pocket
    with monkeypatch.context() as patch:
        # The reference: no candidate hidden, every segment tested.
        patch.setattr(
            _escape, "_shadow", lambda q, b, theta, d2: np.zeros(theta.shape[0], dtype=bool)
        )
        want = planner.plan(start, goal, start_tolerance=1e9)
    calls = counting(monkeypatch)
    got = planner.plan(start, goal, start_tolerance=1e9)
    np.testing.assert_array_equal(got.points, want.points)
    assert got.cost == want.cost
    # The escape cell lies in the pocket beyond the slot, not in the room.
    escape = tuple(int(v) for v in planner.grid.world_to_cell(got.points[1]))
    assert escape[0] == cell[0] and escape[1] >= 40
    assert calls[0] < 200
