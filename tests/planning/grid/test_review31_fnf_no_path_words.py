"""Grid planners' NoPathError in astar's words, counts in the right number (review 31, FNF).

Before: Field D* said "goal_cell (0, 4) is unreachable from start_cell (0, 0)",
without the count the A* and JPS messages give; JPS said "(expanded 1 jump
points)" and A* "(expanded 1 cells)"; ``MapPlanner`` with a cell planner of the
caller's named any count "nodes" (JPS expands jump points); the greedy step said
"(1 candidates)". Now one shared helper (``navkit._shared.counts.counted``) writes
the counts, and Field D* says "no path from start_cell (0, 0) to goal_cell (0, 4)
(expanded 18 nodes)". Checked against the source before the fix (the helper's
module kept): 7 of the 10 tests failed there; the helper's and the two built-in
``MapPlanner`` cases (counts above 1) passed.
"""

from __future__ import annotations

import re
from functools import partial

import numpy as np
import pytest

from navkit._shared.counts import counted
from navkit.errors import NoPathError
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, astar, greedy_step


def _boxed_in() -> np.ndarray:
    """3 x 3 costs whose start corner (0, 0) has no traversable neighbour."""
    costs = np.ones((3, 3))
    costs[0, 1] = costs[1, 0] = costs[1, 1] = np.inf
    return costs


@pytest.mark.parametrize(("method", "unit"), [("astar", "cell"), ("jps", "jump point")])
def test_one_expansion_is_singular(method: str, unit: str) -> None:
    with pytest.raises(NoPathError) as info:
        AStarPlanner(_boxed_in(), method=method).plan((0, 0), (2, 2))
    assert info.value.expanded == 1
    assert str(info.value) == (
        f"no path from start_cell (0, 0) to goal_cell (2, 2) (expanded 1 {unit})"
    )


def test_field_dstar_speaks_as_astar() -> None:
    costs = np.ones((5, 5))
    costs[:, 2] = np.inf
    planner = FieldDStar(costs)
    with pytest.raises(NoPathError) as cells:
        planner.plan_cells((0, 0), (0, 4))
    n = cells.value.expanded
    assert n > 1
    assert str(cells.value) == (
        f"no path from start_cell (0, 0) to goal_cell (0, 4) (expanded {n} nodes)"
    )
    with pytest.raises(NoPathError) as nodes:
        FieldDStar(costs).plan((0, 0), (0, 5))
    assert re.fullmatch(
        r"no path from start_node \(0, 0\) to goal_node \(0, 5\) \(expanded \d+ nodes\)",
        str(nodes.value),
    ), str(nodes.value)
    with pytest.raises(NoPathError) as astar_info:
        astar(costs, (0, 0), (0, 4))
    # The same sentence, but for what each search expands.
    assert str(astar_info.value).split(" (expanded")[0] == str(cells.value).split(" (expanded")[0]


def _walled() -> OccupancyGrid:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[:, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


@pytest.mark.parametrize(
    ("planner", "unit"),
    [
        ("astar", "cell"),
        ("field_dstar", "node"),
        (partial(astar, method="jps"), "jump point"),
        (partial(astar, method="astar"), "cell"),
    ],
    ids=["astar", "field_dstar", "callable jps", "callable astar"],
)
def test_map_planner_names_the_cell_planners_unit(planner: object, unit: str) -> None:
    with pytest.raises(NoPathError) as info:
        MapPlanner(_walled(), planner=planner).plan((0.25, 0.25), (1.75, 0.25))  # type: ignore[arg-type]
    # (JPS expands 1 jump point here: the start's jump to the wall ends the search.)
    assert str(info.value).endswith(f" (expanded {counted(info.value.expanded, unit)})")


def test_map_planner_gives_a_users_count_bare() -> None:
    def mine(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> None:
        raise NoPathError("walled", expanded=7)

    with pytest.raises(NoPathError) as info:
        MapPlanner(_walled(), planner=mine).plan((0.25, 0.25), (1.75, 0.25))  # type: ignore[arg-type]
    assert str(info.value).endswith("(cell (2, 17)) (expanded 7)"), info.value


def test_greedy_one_candidate_is_singular() -> None:
    # One free cell nearer the goal, two cells ahead, hidden by the one between.
    occupied = np.ones((5, 5), dtype=bool)
    occupied[2, 2] = occupied[2, 4] = False
    grid = LocalGrid(occupied, resolution=0.1, half_width=0.2)
    with pytest.raises(NoPathError) as info:
        greedy_step(grid, (1.0, 0.0), require_progress=True)
    assert info.value.expanded == 1
    assert str(info.value).endswith("(1 candidate)"), info.value


def test_counted() -> None:
    assert [counted(n, "cell") for n in (0, 1, 2)] == ["0 cells", "1 cell", "2 cells"]
    assert counted(1, "jump point") == "1 jump point"
    assert counted(2, "entry", "entries") == "2 entries"
    assert counted(np.int64(1), "node") == "1 node"
