"""Review 33 (PAIRS): the grid planners' options met in every combination.

* :func:`astar` and :class:`AStarPlanner` under every ``connectivity`` ×
  ``corner_cutting`` × ``heuristic_weight`` (0, 0.5, 1, 3, 1e6) × ``method``: the
  function and the class agree; a weight of at most 1 gives the cost of the exact
  :func:`distance_field`, a larger one at most that many times it; with 4-connectivity
  ``corner_cutting`` is ignored (the same path); :meth:`AStarPlanner.distance_field`
  equals :func:`distance_field`; a pickled planner plans alike.
* :class:`FieldDStar` under every ``interpolate`` × ``lookahead`` × ``smooth``: the
  function equals the class; after :meth:`~FieldDStar.update_costs` a
  :meth:`~FieldDStar.replan` (also from a new start) equals a fresh plan on the new
  costs, as do copies and pickles made before the update; without ``interpolate``,
  ``smooth`` changes nothing (documented: used with ``interpolate=True``).
* :meth:`FieldDStar.replan_world` after an update of cells marked as obstacles or as
  inflation (``obstacles=``), with ``start_tolerance`` 0, 0.15 m and 1e9 m before and
  after, from the kept start or a new one: the fresh :meth:`~FieldDStar.plan_world`
  on the new costs and obstacles (as documented).

They found nothing: they guard the combinations.
"""

from __future__ import annotations

import copy
import itertools
import math
import pickle
import random
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, Path2D, astar, distance_field, field_dstar

Outcome = Path2D | str


def _outcome(plan: Callable[..., Path2D], *args: Any, **kwargs: Any) -> Outcome:
    """``plan(*args, **kwargs)``, or how it refused (both refusals, however worded)."""
    try:
        return plan(*args, **kwargs)
    except NoPathError:
        return "no path"
    except ValueError:
        return "ValueError"


def _same(a: Outcome, b: Outcome) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return bool(np.array_equal(a.points, b.points) and a.cost == b.cost and a.length == b.length)


def _grid(seed: int) -> tuple[np.ndarray, tuple[int, int], tuple[int, int]]:
    rng = np.random.default_rng(seed)
    if seed >= 16:
        # A wall across the grid: seeds 0-15 never left the goal unreachable, so no
        # combination's refusal was compared.
        costs = np.ones((5, 7)) if seed % 2 == 0 else rng.uniform(1.0, 5.0, (5, 7))
        costs[:, 3] = np.inf
        return costs, (int(rng.integers(5)), 1), (int(rng.integers(5)), 5)
    rows, cols = (int(v) for v in rng.integers(1, 12, 2))
    costs = np.ones((rows, cols)) if seed % 2 == 0 else rng.uniform(1.0, 5.0, (rows, cols))
    costs[rng.random((rows, cols)) < 0.25] = np.inf
    free = np.argwhere(np.isfinite(costs))
    if not len(free):
        costs[0, 0] = 1.0
        free = np.array([[0, 0]])
    start = tuple(int(v) for v in free[rng.integers(len(free))])
    goal = tuple(int(v) for v in free[rng.integers(len(free))])
    return costs, start, goal  # type: ignore[return-value]


ASTAR_OPTIONS = list(
    itertools.product([8, 4], [False, True], [0.0, 0.5, 1.0, 3.0, 1e6], ["astar", "jps", "auto"])
)


@pytest.mark.parametrize("seed", range(18))
def test_astar_option_combinations(seed: int) -> None:
    costs, start, goal = _grid(seed)
    for connectivity, cutting, weight, method in ASTAR_OPTIONS:
        kwargs: dict[str, Any] = {
            "connectivity": connectivity,
            "corner_cutting": cutting,
            "heuristic_weight": weight,
            "method": method,
        }
        try:
            planner = AStarPlanner(costs, **kwargs)
        except ValueError:
            # JPS needs uniform costs, 8-connectivity and weight 1 (documented).
            assert method == "jps"
            continue
        path = _outcome(planner.plan, start, goal)
        assert _same(_outcome(astar, costs, start, goal, **kwargs), path)
        field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=cutting)
        assert np.array_equal(planner.distance_field(goal), field)
        best = float(field[start])
        if isinstance(path, str):
            assert path == "no path" and best == math.inf
        elif weight <= 1.0:
            assert path.cost == pytest.approx(best, rel=1e-12)
        else:
            assert path.cost <= weight * best * (1 + 1e-12)
        if connectivity == 4:
            other = AStarPlanner(costs, **{**kwargs, "corner_cutting": not cutting})
            assert _same(_outcome(other.plan, start, goal), path)
        twin = pickle.loads(pickle.dumps(planner))
        assert _same(_outcome(twin.plan, start, goal), path)


FLAGS = list(itertools.product([True, False], repeat=3))


@pytest.mark.parametrize("seed", range(20))
def test_field_dstar_flag_combinations_replan_as_fresh(seed: int) -> None:
    rng = np.random.default_rng(seed)
    pick = random.Random(seed)
    rows, cols = (int(v) for v in rng.integers(2, 10, 2))
    if seed % 2:
        costs = rng.choice([1.0, 1.0, 2.0, 5.0, np.inf], (rows, cols))
    else:
        costs = np.where(rng.random((rows, cols)) < 0.25, np.inf, 1.0)
    nodes = [(i, j) for i in range(rows + 1) for j in range(cols + 1)]
    start, goal, moved = pick.choice(nodes), pick.choice(nodes), pick.choice(nodes)
    cells = [(int(rng.integers(rows)), int(rng.integers(cols))) for _ in range(3)]
    new_costs = rng.choice([1.0, 3.0, np.inf], 3)
    for interpolate, lookahead, smooth in FLAGS:
        flags = {"interpolate": interpolate, "lookahead": lookahead, "smooth": smooth}
        planner = FieldDStar(costs, **flags)
        first = _outcome(planner.plan, start, goal)
        assert _same(_outcome(field_dstar, costs, start, goal, **flags), first)
        if not interpolate:
            unsmoothed = FieldDStar(costs, **{**flags, "smooth": not smooth})
            assert _same(_outcome(unsmoothed.plan, start, goal), first)
        if isinstance(first, str) and first == "ValueError":
            continue  # no plan made: nothing to repair
        twins = [copy.copy(planner), copy.deepcopy(planner), pickle.loads(pickle.dumps(planner))]
        for p in [planner, *twins]:
            p.update_costs(cells, new_costs)
        fresh = FieldDStar(planner.costs, **flags)
        again = _outcome(planner.replan)
        assert _same(again, _outcome(fresh.plan, start, goal))
        for twin in twins:
            assert _same(_outcome(twin.replan), again)
        assert _same(
            _outcome(planner.replan, moved),
            _outcome(FieldDStar(planner.costs, **flags).plan, moved, goal),
        )


def _world_case(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    pick = random.Random(seed)
    rows, cols = (int(v) for v in rng.integers(6, 14, 2))
    occupied = rng.random((rows, cols)) < 0.08
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(1.0, -2.0, 0.0))

    def point() -> tuple[float, float]:
        return (1.0 + pick.uniform(0, cols * 0.1 - 1e-9), -2.0 + pick.uniform(0, rows * 0.1 - 1e-9))

    new_costs = rng.choice([1.0, 3.0, np.inf], 3)
    marks: Any = pick.choice([None, False, "impassable", "some"])
    if marks == "impassable":
        marks = np.isinf(new_costs)
    elif marks == "some":
        marks = np.array([bool(np.isinf(v)) and pick.random() < 0.5 for v in new_costs])
    return {
        "costs": grid.traversal_costs(robot_radius=0.15, inflation_radius=0.3),
        "occupied": occupied,
        "start": point(),
        "goal": point(),
        "moved": point(),
        "cells": [(int(rng.integers(rows)), int(rng.integers(cols))) for _ in range(3)],
        "new_costs": new_costs,
        "marks": marks,
    }


def _obstacles_after(case: dict[str, Any], before: np.ndarray, kept: np.ndarray) -> np.ndarray:
    """The obstacle mask after update_costs, as its documentation says it changes."""
    out = kept.copy()
    marks = case["marks"]
    for k, (cell, value) in enumerate(zip(case["cells"], case["new_costs"], strict=True)):
        if marks is None:  # closed here: an obstacle; opened: not; else as it was
            if np.isinf(value) and not np.isinf(before[cell]):
                out[cell] = True
            elif not np.isinf(value):
                out[cell] = False
        else:
            mark = marks if isinstance(marks, bool) else bool(marks[k])
            out[cell] = mark and bool(np.isinf(value))
    return out


WORLD_OPTIONS = list(
    itertools.product(
        [True, False], [True, False], [0.0, 0.15, 1e9], [0.0, 0.15, 1e9], [False, True],
        [False, True],
    )
)  # fmt: skip


def _check_world_case(seed: int, options: list[tuple[Any, ...]]) -> None:
    case = _world_case(seed)
    for interpolate, smooth, tol_before, tol_after, move, with_obstacles in options:
        kwargs: dict[str, Any] = {
            "interpolate": interpolate,
            "smooth": smooth,
            "resolution": 0.1,
            "origin": (1.0, -2.0, 0.0),
        }
        obstacles = case["occupied"] if with_obstacles else None
        planner = FieldDStar(case["costs"], obstacles=obstacles, **kwargs)
        first = _outcome(
            planner.plan_world, case["start"], case["goal"], start_tolerance=tol_before
        )
        if isinstance(first, str):
            continue
        before = planner.costs.copy()
        kept = case["occupied"] if with_obstacles else np.isinf(before)
        planner.update_costs(case["cells"], case["new_costs"], obstacles=case["marks"])
        now = _obstacles_after(case, before, kept)
        start = case["moved"] if move else None
        again = _outcome(planner.replan_world, start, start_tolerance=tol_after)
        fresh = FieldDStar(planner.costs, obstacles=now, **kwargs)
        from_scratch = _outcome(
            fresh.plan_world,
            case["moved"] if move else case["start"],
            case["goal"],
            start_tolerance=tol_after,
        )
        assert _same(again, from_scratch)


@pytest.mark.parametrize("seed", range(12))
def test_field_dstar_world_replans_with_obstacles_and_tolerances_as_fresh(seed: int) -> None:
    pick = random.Random(1000 + seed)
    _check_world_case(seed, pick.sample(WORLD_OPTIONS, 30))


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(60))
def test_field_dstar_world_replans_thoroughly(seed: int) -> None:
    _check_world_case(seed, WORLD_OPTIONS)
