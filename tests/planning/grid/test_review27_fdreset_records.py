"""Field D* fresh searches blank only the records the last one wrote (review 27, FDRESET).

Every fresh search (``FieldDStar.plan*``, ``MapPlanner(planner="field_dstar")``)
used to refill every node record and heap slot first: a short plan on a 4096²
map took 25 ms, nearly all of it the two fills. A fresh search now keeps the
box of the nodes it expands (and ``_reset`` that of the sources),
``_work[2:6]``; every record written lies in that box widened by one node, and
only that is blanked (a repair's box was the whole grid until review 28).
Checked here without clocks: the invariant (every record outside the widened box is blank, bit for
bit, after any sequence of plans, updates, moves and replans), how many
records the next reset blanks after a long plan, a short plan and a replan,
that records beyond the box are left alone, bit-identity of a reused planner
with fresh ones, an interrupt between the reset and the search, and pickles
made before the box (whole grid, or empty if unused).
"""

from __future__ import annotations

import pickle
from typing import Any, cast

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.planning import FieldDStar
from navkit.planning.grid import _field_dstar
from navkit.planning.grid._dstar_heap import POS, RECORD

SIDE = 200


def _blank_bits() -> NDArray[np.int64]:
    blank = np.full(RECORD, np.inf)
    blank.view(np.int64)[POS] = -1
    return blank.view(np.int64)


def _outside_blank(planner: FieldDStar) -> bool:
    """Whether every record outside the box of written records, widened by one, is blank."""
    top, bottom, left, right = (int(v) for v in planner._work[2:6])
    recs = planner._vals.view(np.int64).reshape(planner._nrows, planner._ncols, RECORD)
    outside = np.ones(recs.shape[:2], dtype=bool)
    if bottom >= top:
        outside[max(top - 1, 0) : bottom + 2, max(left - 1, 0) : right + 2] = False
    return bool(np.all(recs[outside] == _blank_bits()))


def _blanked(planner: FieldDStar, monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The number of records each later reset of ``planner`` blanks."""
    counts: list[int] = []
    real = _field_dstar.clear_box

    def counting(*args: Any) -> int:
        n = real(*args)
        counts.append(n)
        return n

    monkeypatch.setattr(_field_dstar, "clear_box", counting)
    return counts


def test_a_short_plan_after_a_long_one_blanks_only_its_own_records(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    planner = FieldDStar(np.ones((SIDE, SIDE)))
    counts = _blanked(planner, monkeypatch)
    planner.plan((0, 0), (SIDE, SIDE))  # new: nothing to blank
    assert counts == [0]
    short = planner.plan((5, 5), (30, 35))  # after the long search: nearly every record
    assert counts[1] > 0.9 * (SIDE + 1) ** 2
    planner.plan((6, 5), (30, 35))  # after the short one: its box only
    # A short search on unit costs stays within ~36 nodes of its goal (the
    # heuristic is the octile distance ÷ sqrt(2)): a box of at most 70 × 70 nodes.
    assert 0 < counts[2] <= 70 * 70
    assert short.expanded < counts[2]  # the expanded nodes are in it, and more
    _, bottom, _, right = (int(v) for v in planner._work[2:6])
    assert bottom < 70 and right < 75  # the box of the last search, near its ends
    assert _outside_blank(planner)


def test_records_beyond_the_box_are_left_alone() -> None:
    # The far corner of the records, never reached by short searches near (5, 5),
    # poisoned with a value no search writes: the resets between short plans must
    # not touch it (they blanked the whole records before).
    planner = FieldDStar(np.ones((SIDE, SIDE)))
    planner.plan((5, 5), (30, 35))
    recs = planner._vals.view(np.int64).reshape(SIDE + 1, SIDE + 1, RECORD)
    assert np.all(recs[150:, 150:] == _blank_bits())
    poison = np.int64(0x5A5A5A5A5A5A5A5A)
    recs[150:, 150:] = poison
    for goal in ((30, 36), (31, 30), (12, 40)):
        planner.plan((5, 5), goal)
    assert np.all(recs[150:, 150:] == poison)
    recs[150:, 150:] = _blank_bits()
    assert planner.plan((5, 5), (30, 36)).points.tobytes() == (
        FieldDStar(np.ones((SIDE, SIDE))).plan((5, 5), (30, 36)).points.tobytes()
    )


def test_a_new_planner_and_a_plan_that_fails_keep_the_box_right() -> None:
    costs = np.ones((30, 30))
    costs[:, 15] = np.inf  # two halves
    planner = FieldDStar(costs)
    assert int(planner._work[3]) < int(planner._work[2])  # empty
    with pytest.raises(NoPathError):
        planner.plan((3, 3), (20, 25))
    assert _outside_blank(planner)
    # The search ran from the goal over its whole half (columns 16-30), not beyond.
    assert planner._work[2:].tolist() == [0, 30, 16, 30]
    got = planner.plan((25, 25), (20, 29))
    assert got.points.tobytes() == FieldDStar(costs).plan((25, 25), (20, 29)).points.tobytes()
    assert _outside_blank(planner)


@st.composite
def _grids(draw: st.DrawFn) -> NDArray[np.float64]:
    rows, cols = draw(st.integers(6, 40)), draw(st.integers(6, 40))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    costs = rng.choice([1.0, 1.0, 2.5, 7.0, np.inf], size=(rows, cols))
    return np.asarray(costs, dtype=np.float64)


def _outcome(method: Any, *args: Any, expanded: bool = True) -> tuple[Any, ...] | str:
    """The path (points, cost, length and, if ``expanded``, expansions), or the error.

    Without ``expanded`` (a replan against a fresh plan) only the error's type: a
    replan's message names its kept ends as such.
    """
    try:
        path = method(*args)
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__ + (str(exc) if expanded else "")
    return (path.points.tobytes(), path.cost, path.length, *([path.expanded] if expanded else []))


@settings(max_examples=40, deadline=None)
@given(data=st.data(), costs=_grids())
def test_a_reused_planner_plans_and_replans_as_fresh_ones(
    data: st.DataObject, costs: NDArray[np.float64]
) -> None:
    # Long and short plans (nodes, cells, world points), cost changes and moves in
    # any order: every answer is bit for bit that of a fresh planner on the current
    # costs, and every record outside the box is blank after each step.
    rows, cols = costs.shape
    planner = FieldDStar(costs, resolution=0.5)
    current = costs.copy()
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))

    def node() -> tuple[int, int]:
        return data.draw(st.integers(0, rows)), data.draw(st.integers(0, cols))

    def cell() -> tuple[int, int]:
        return data.draw(st.integers(0, rows - 1)), data.draw(st.integers(0, cols - 1))

    for _ in range(data.draw(st.integers(3, 8))):
        step = data.draw(st.sampled_from(["plan", "plan", "cells", "world", "update"]))
        if step == "plan":
            start, end = node(), node()
            got = _outcome(planner.plan, start, end)
            want = _outcome(FieldDStar(current).plan, start, end)
        elif step == "cells":
            a, b = cell(), cell()
            got = _outcome(planner.plan_cells, a, b)
            want = _outcome(FieldDStar(current).plan_cells, a, b)
        elif step == "world":
            xy = [float(v) for v in rng.uniform(0.0, 0.5 * min(rows, cols), 4)]
            got = _outcome(planner.plan_world, xy[:2], xy[2:])
            want = _outcome(FieldDStar(current, resolution=0.5).plan_world, xy[:2], xy[2:])
        else:
            cells = np.argwhere(rng.random(costs.shape) < 0.08)
            values = rng.choice([1.0, 3.0, np.inf], size=len(cells))
            planner.update_costs(cells, values)
            current[tuple(cells.T)] = values
            # Replans keep the goal of the last node plan that got through its checks.
            goal = planner._goal
            if goal is None or planner._start is None or not planner._goal_on_node:
                continue
            start = node() if data.draw(st.booleans()) else planner._start
            # A repair expands other nodes than a fresh search: the path is compared.
            got = _outcome(planner.replan, start, expanded=False)
            want = _outcome(FieldDStar(current).plan, start, goal, expanded=False)
        assert got == want, step
        assert _outside_blank(planner), step


test_a_reused_planner_plans_and_replans_as_fresh_ones_slow = slow_twin(
    test_a_reused_planner_plans_and_replans_as_fresh_ones, max_examples=400
)


def _before_the_box(planner: FieldDStar) -> Any:
    """``planner``'s pickle state as a version before the box made it (``_work`` a pair)."""
    instance, kept = cast("tuple[Any, dict[str, Any]]", planner.__getstate__())
    kept = dict(kept)
    kept["_work"] = kept["_work"][:2]
    return pickle.loads(pickle.dumps((instance, kept)))  # nothing shared with the planner


def test_pickles_made_before_the_box_blank_every_record_once() -> None:
    costs = np.ones((40, 50))
    costs[10:30, 20] = np.inf
    used = FieldDStar(costs)
    used.plan((0, 0), (40, 50))
    used.update_costs([(5, 5)], np.inf)
    unused = FieldDStar(costs)
    twins = []
    for planner in (used, unused):
        twin = FieldDStar.__new__(FieldDStar)
        twin.__setstate__(_before_the_box(planner))
        twins.append(twin)
    every = [0, 40, 0, 50]  # the node grid is 41 × 51
    assert twins[0]._work[2:].tolist() == every
    assert int(twins[1]._work[3]) < int(twins[1]._work[2])  # never searched: empty
    # The old twin continues as the original, and its next fresh plan as a new one.
    assert _outcome(twins[0].replan) == _outcome(used.replan)
    for twin in twins:
        want = _outcome(FieldDStar(costs).plan, (3, 4), (7, 9))
        assert _outcome(twin.plan, (3, 4), (7, 9)) == want
        assert _outside_blank(twin)
    # Pickled now, the box goes with the planner.
    again = pickle.loads(pickle.dumps(twins[0]))
    assert again._work.tobytes() == twins[0]._work.tobytes()
    assert _outcome(again.replan) == _outcome(twins[0].replan)


def test_an_interrupt_between_the_reset_and_the_search_leaves_no_record_behind(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The sources are queued (their records written) before the search runs: the box
    # must hold them, or the next reset would leave the goal queued at value 0.
    costs = np.ones((60, 60))
    planner = FieldDStar(costs)
    planner.plan((0, 0), (60, 60))
    real = FieldDStar._walk

    def interrupted(self: FieldDStar, *args: Any, **kwargs: Any) -> Any:
        raise KeyboardInterrupt

    monkeypatch.setattr(FieldDStar, "_walk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        planner.plan_cells((50, 50), (40, 45))  # four sources: the goal cell's corners
    assert planner._work[2:].tolist() == [40, 41, 45, 46]
    assert _outside_blank(planner)
    monkeypatch.setattr(FieldDStar, "_walk", real)
    want = FieldDStar(costs).plan((3, 4), (8, 6))
    got = planner.plan((3, 4), (8, 6))
    assert (got.points.tobytes(), got.cost, got.expanded) == (
        want.points.tobytes(), want.cost, want.expanded
    )


def test_a_repair_hands_the_next_fresh_search_its_box(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Repairs keep the box too since review 28 (they handed the next fresh search
    # every record before): the next fresh search blanks the box the plan and the
    # repair grew, not the grid (see test_review28_fnf_field_dstar_repair_box.py).
    changed = np.ones((50, 50))
    changed[10:12, 12] = np.inf
    want = FieldDStar(changed).plan((5, 5), (20, 26))
    planner = FieldDStar(np.ones((50, 50)))
    counts = _blanked(planner, monkeypatch)
    planner.plan((5, 5), (20, 25))
    planner.update_costs([(10, 12), (11, 12)], np.inf)
    planner.replan((6, 5))
    assert planner._work[2:].tolist() != [0, 50, 0, 50]
    assert _outside_blank(planner)
    got = planner.plan((5, 5), (20, 26))
    assert counts[0] == 0 and 0 < counts[1] < 51 * 51
    assert (got.points.tobytes(), got.cost, got.expanded) == (
        want.points.tobytes(), want.cost, want.expanded
    )
    assert 0 < int(planner._work[3]) - int(planner._work[2]) < 50  # its own box again
