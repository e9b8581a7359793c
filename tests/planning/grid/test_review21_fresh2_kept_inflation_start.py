"""``FieldDStar.replan_world()``: a kept world start closed as inflation may escape.

A fresh-eyes review of ``start_tolerance``: a robot's kept start point whose
cell :meth:`~navkit.planning.FieldDStar.update_costs` closed with
``obstacles=False`` (the ring grown around a new obstacle) was refused by
``replan_world(start_tolerance=...)`` as if it were an obstacle, while the
same point given as ``start_xy`` escaped. Both now give the same path; a cell
closed as an obstacle (the default), a node start and a ``plan_cells`` start
are still refused.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from navkit.planning import FieldDStar

START = (2.5, 2.4)  # cell (2, 2)
GOAL = (7.5, 7.5)
RING = [(r, c) for r in range(1, 4) for c in range(1, 4)]


def planner() -> FieldDStar:
    return FieldDStar(np.ones((8, 8)), obstacles=np.zeros((8, 8), dtype=bool))


def same(a: object, b: object) -> None:
    assert np.array_equal(a.points, b.points)  # type: ignore[attr-defined]
    assert a.cost == b.cost and a.length == b.length  # type: ignore[attr-defined]


def test_a_kept_start_closed_as_inflation_escapes_as_the_point_given() -> None:
    kept = planner()
    kept.plan_world(START, GOAL)
    kept.update_costs(RING, np.inf, obstacles=False)
    given = pickle.loads(pickle.dumps(kept))
    path = kept.replan_world(start_tolerance=2.5)
    same(path, given.replan_world(START, start_tolerance=2.5))
    assert path.points[0].tolist() == list(START)
    # The escape leaves the ring: its second point is a passable cell's centre.
    x, y = path.points[1]  # identity origin, 1 m cells: cell (floor(y), floor(x))
    row, col = int(np.floor(y)), int(np.floor(x))
    assert (row, col) not in RING
    assert np.isfinite(kept.costs[row, col])
    # And equals a fresh plan from that point on the current costs.
    fresh = FieldDStar(kept.costs, obstacles=np.zeros((8, 8), dtype=bool))
    same(path, fresh.plan_world(START, GOAL, start_tolerance=2.5))


def test_without_tolerance_the_refusal_says_how_and_changes_nothing() -> None:
    kept = planner()
    kept.plan_world(START, GOAL)
    kept.update_costs(RING, np.inf, obstacles=False)
    before = pickle.dumps(kept)
    with pytest.raises(
        ValueError,
        match=r"kept from the last plan.*within the inflation.*"
        r"pass start_tolerance > 0",
    ):
        kept.replan_world()
    with pytest.raises(ValueError, match=r"no passable cell centre within start_tolerance"):
        kept.replan_world(start_tolerance=1.0)
    assert pickle.dumps(kept) == before


@pytest.mark.parametrize("how", ["obstacle", "node", "cells"])
def test_other_kept_starts_never_escape(how: str) -> None:
    kept = planner()
    if how == "node":
        kept.plan((2, 2), (7, 7))
    elif how == "cells":
        kept.plan_cells((2, 2), (7, 7))
    else:
        kept.plan_world(START, GOAL)
    kept.update_costs(RING, np.inf, obstacles=how == "obstacle")
    with pytest.raises(ValueError, match=r"kept from the last plan"):
        kept.replan_world(start_tolerance=2.5)


def test_an_update_failing_part_way_marks_no_obstacle(monkeypatch: pytest.MonkeyPatch) -> None:
    # A MemoryError growing the list of changed cells (or a Ctrl-C there) left the
    # cells marked as obstacles with their old, finite costs: the planner as before.
    kept = FieldDStar(np.ones((40, 40)), obstacles=np.zeros((40, 40), dtype=bool))
    kept.plan_world((0.5, 0.5), (39.5, 39.5))
    cells = [(r, c) for r in range(10, 30) for c in range(10, 30)]
    costs = kept.costs
    assert kept._obstacles is not None
    kinds = kept._obstacles.copy()  # what start_tolerance reads

    def no_memory(*args: object, **kwargs: object) -> None:
        raise MemoryError("probe")

    monkeypatch.setattr(np, "zeros", no_memory)
    with pytest.raises(MemoryError, match="probe"):
        kept.update_costs(cells, np.inf, obstacles=True)
    monkeypatch.undo()
    assert np.array_equal(kept.costs, costs)
    assert np.array_equal(kept._obstacles, kinds)
    # Done again, the update goes through, with its kinds.
    kept.update_costs(cells, np.inf, obstacles=True)
    with pytest.raises(ValueError, match=r"\(20, 20\) \(cost inf\), an obstacle"):
        kept.plan_world((20.5, 20.5), (39.5, 39.5), start_tolerance=30.0)


def test_no_cells_take_an_empty_list_of_obstacle_flags() -> None:
    # NumPy types [] float64: refused as "not boolean" for no cells at all.
    kept = planner()
    kept.plan_world(START, GOAL)
    before = pickle.dumps(kept)
    kept.update_costs([], [], obstacles=[])
    kept.update_costs(np.zeros((0, 2), dtype=np.int64), np.inf, obstacles=[])
    assert pickle.dumps(kept) == before
    with pytest.raises(ValueError, match=r"obstacles must be a bool or have shape \(1,\)"):
        kept.update_costs([(0, 0)], np.inf, obstacles=[])
    with pytest.raises(TypeError, match="obstacles must be a bool or a boolean array"):
        kept.update_costs([(0, 0)], np.inf, obstacles=[1.0])
