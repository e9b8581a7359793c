"""Field D* repairs keep the box of the records they write (review 28, FNF item 1).

Since review 27 a fresh search blanks only the box of the records written since
the last one (``_work[2:6]`` widened by one node), but a repair handed the next
fresh search the whole grid: a short plan right after a replan blanked every
record of the map. ``settle`` now widens the box wherever a value falls, in
repairs too (g becomes finite only there, and every record written lies next
to a finite g or is a source). Checked here without clocks: how many records
the next reset blanks after a replan, that a change far from the search does
not grow the box, the invariant (every record outside the widened box is
blank, bit for bit) after falls, rises, moves, cell ends and aborted repairs,
and a reused (and pickled) planner against fresh ones.
"""

from __future__ import annotations

import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from test_review27_fdreset_records import _grids, _outside_blank

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.planning import FieldDStar
from navkit.planning.grid import _field_dstar


def _counting(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The number of records each later reset of any planner blanks."""
    counts: list[int] = []
    real = _field_dstar.clear_box

    def counting(*args: Any) -> int:
        n = real(*args)
        counts.append(n)
        return n

    monkeypatch.setattr(_field_dstar, "clear_box", counting)
    return counts


def _same(got: Any, want: Any) -> bool:
    return bool(
        (got.points.tobytes(), got.cost, got.length, got.expanded)
        == (want.points.tobytes(), want.cost, want.length, want.expanded)
    )


def test_a_short_plan_after_a_replan_blanks_only_the_searched_box(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    side = 200
    changed = np.ones((side, side))
    changed[10:12, 12] = np.inf
    want = FieldDStar(changed).plan((5, 5), (20, 26))
    planner = FieldDStar(np.ones((side, side)))
    counts = _counting(monkeypatch)
    planner.plan((5, 5), (20, 25))
    planner.update_costs([(10, 12), (11, 12)], np.inf)
    planner.replan((6, 5))
    assert _outside_blank(planner)
    _, bottom, _, right = (int(v) for v in planner._work[2:6])
    # The repair's nodes lie near the short plan, far from the grid's far corner
    # (the box used to be the whole grid, 201 x 201 records blanked next).
    assert bottom < 40 and right < 45
    got = planner.plan((5, 5), (20, 26))
    assert counts[0] == 0 and 0 < counts[1] <= 42 * 47
    assert _same(got, want)


def test_a_change_far_from_the_search_leaves_the_box_and_the_records_alone() -> None:
    # The changed cells' corners are requeued with rhs = inf (no neighbour of
    # finite g): their records stay blank, and the box does not grow.
    costs = np.ones((120, 120))
    planner = FieldDStar(costs)
    planner.plan((5, 5), (25, 30))
    box = planner._work[2:6].tolist()
    planner.update_costs([(100, 100), (110, 3), (3, 110)], [np.inf, 5.0, np.inf])
    planner.update_costs([(60, 60)], 1.0)  # no change: nothing listed
    costs[100, 100] = costs[3, 110] = np.inf
    costs[110, 3] = 5.0
    got = planner.replan()
    assert planner._work[2:6].tolist() == box
    assert _outside_blank(planner)
    assert got.points.tobytes() == FieldDStar(costs).plan((5, 5), (25, 30)).points.tobytes()


def test_falls_rises_moves_and_cell_ends_keep_the_invariant() -> None:
    rng = np.random.default_rng(28)
    costs = rng.choice([1.0, 1.0, 2.0, 6.0], size=(80, 90))
    planner = FieldDStar(costs)
    planner.plan_cells((10, 10), (60, 70))  # four sources: the goal cell's corners
    assert _outside_blank(planner)
    steps: list[tuple[list[tuple[int, int]], float, tuple[int, int] | None]] = [
        ([(40, c) for c in range(20, 75)], np.inf, None),  # a wall: values rise
        ([(40, c) for c in range(20, 40)], 1.0, None),  # a gap: values fall
        ([(30, 30), (31, 30)], 1.0, (12, 14)),  # cheaper cells, robot moved
        ([(55, c) for c in range(0, 90, 2)], np.inf, (20, 20)),  # near the goal
    ]
    for cells, value, start in steps:
        planner.update_costs(cells, value)
        costs[tuple(np.array(cells).T)] = value
        planner.replan(start)
        assert _outside_blank(planner)
    # The next fresh search, after all of them, is a fresh planner's, bit for bit.
    assert _same(planner.plan((2, 3), (9, 8)), FieldDStar(costs).plan((2, 3), (9, 8)))
    assert _outside_blank(planner)


def test_an_aborted_repair_falls_back_on_the_tracked_box(monkeypatch: pytest.MonkeyPatch) -> None:
    # A change next to the goal raises nearly every value: the repair is cut short
    # (mid-repair records everywhere it went) and the fresh search that replaces it
    # blanks the box the repair grew, not less.
    costs = np.ones((60, 60))
    planner = FieldDStar(costs)
    planner.plan((0, 0), (58, 58))
    counts = _counting(monkeypatch)
    wall = [(56, c) for c in range(40, 60)] + [(r, 56) for r in range(40, 56)]
    planner.update_costs(wall, np.inf)
    costs[tuple(np.array(wall).T)] = np.inf
    got = planner.replan()
    assert counts, "the repair was not replaced by a fresh search"
    assert _outside_blank(planner)
    want = FieldDStar(costs).plan((0, 0), (58, 58))
    assert got.points.tobytes() == want.points.tobytes()


def _outcome(method: Any, *args: Any, expanded: bool = True) -> tuple[Any, ...] | str:
    """The path (points, cost, length and, if ``expanded``, expansions), or the error type.

    Only the error's type: a replan's message names its kept ends as such, a
    fresh plan's does not (``test_review27_fdreset_records._outcome`` keeps it).
    """
    try:
        path = method(*args)
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__
    return (path.points.tobytes(), path.cost, path.length, *([path.expanded] if expanded else []))


@settings(max_examples=40, deadline=None)
@given(data=st.data(), costs=_grids())
def test_a_reused_and_pickled_planner_matches_fresh_ones_after_replans(
    data: st.DataObject, costs: NDArray[np.float64]
) -> None:
    # Replans (local, rising, falling, moved starts) between plans, the planner
    # pickled and restored at random points: every plan is bit for bit a fresh
    # planner's (expansions too), every replan's path a fresh plan's, the restored
    # copy answers as the original, and no record outside the box is written.
    rows, cols = costs.shape
    planner = FieldDStar(costs)
    current = costs.copy()
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))

    def node() -> tuple[int, int]:
        return data.draw(st.integers(0, rows)), data.draw(st.integers(0, cols))

    for _ in range(data.draw(st.integers(3, 9))):
        step = data.draw(st.sampled_from(["plan", "cells", "replan", "replan", "pickle"]))
        if step == "plan":
            start, end = node(), node()
            got = _outcome(planner.plan, start, end)
            want = _outcome(FieldDStar(current).plan, start, end)
        elif step == "cells":
            a = data.draw(st.integers(0, rows - 1)), data.draw(st.integers(0, cols - 1))
            b = data.draw(st.integers(0, rows - 1)), data.draw(st.integers(0, cols - 1))
            got = _outcome(planner.plan_cells, a, b)
            want = _outcome(FieldDStar(current).plan_cells, a, b)
        elif step == "pickle":
            copy = pickle.loads(pickle.dumps(planner))
            assert copy._work.tobytes() == planner._work.tobytes()
            assert copy._vals.tobytes() == planner._vals.tobytes()
            planner = copy
            continue
        else:
            # A few cells, near a random spot (a local change) or anywhere.
            spot = rng.integers(0, [rows, cols])
            near = np.abs(np.indices((rows, cols)) - spot[:, None, None]).max(axis=0) <= 2
            pick = near if data.draw(st.booleans()) else rng.random((rows, cols)) < 0.05
            cells = np.argwhere(pick & (rng.random((rows, cols)) < 0.6))
            values = rng.choice([1.0, 3.0, np.inf], size=len(cells))
            planner.update_costs(cells, values)
            current[tuple(cells.T)] = values
            goal = planner._goal
            if goal is None or planner._start is None or not planner._goal_on_node:
                continue
            start = node() if data.draw(st.booleans()) else planner._start
            twin = pickle.loads(pickle.dumps(planner))
            full = _outcome(planner.replan, start)
            assert _outcome(twin.replan, start) == full  # expansions too
            # A repair expands other nodes than a fresh search: the path is compared.
            got = full[:3] if isinstance(full, tuple) else full
            want = _outcome(FieldDStar(current).plan, start, goal, expanded=False)
        assert got == want, step
        assert _outside_blank(planner), step


test_a_reused_and_pickled_planner_matches_fresh_ones_after_replans_slow = slow_twin(
    test_a_reused_and_pickled_planner_matches_fresh_ones_after_replans, max_examples=400
)
