"""Field D* repair bound: a hopeless repair is given up early, a promising one goes on."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from navkit.planning import FieldDStar
from navkit.planning.grid import _field_dstar as field_dstar_module

SIZE = 96
START = (0, 0)
GOAL = (SIZE, SIZE)


@pytest.fixture(autouse=True)
def _no_minimum_work(monkeypatch: pytest.MonkeyPatch) -> None:
    # The bounds in fractions of a fresh search only: these maps are small.
    monkeypatch.setattr(field_dstar_module, "_REPAIR_MIN_WORK", 0)
    monkeypatch.setattr(field_dstar_module, "_REPAIR_PROBE_MIN_WORK", 0)


def _probe(fresh: int) -> float:
    """The first stage's work bound after a fresh search of ``fresh`` expansions (its work)."""
    return field_dstar_module._REPAIR_PROBE * fresh


def _single_bound(monkeypatch: pytest.MonkeyPatch) -> None:
    """One stage as long as the cap: no projection before the repair ends or reaches it."""
    monkeypatch.setattr(field_dstar_module, "_REPAIR_PROBE", field_dstar_module._REPAIR_CAP)


def _costs(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((SIZE, SIZE)) < 0.15, np.inf, 1.0)
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    return costs


def _block(costs: np.ndarray, distance: float) -> list[tuple[int, int]]:
    """The 2 x 2 cells ``distance`` along the fresh path (negative: from the end)."""
    line = shapely.LineString(FieldDStar(costs).plan(START, GOAL).points + 0.5)
    at = line.interpolate(distance if distance >= 0 else line.length + distance)
    r, c = math.floor(at.x), math.floor(at.y)
    cells = [(r + dr, c + dc) for dr in (-1, 0) for dc in (-1, 0)]
    return [cell for cell in cells if min(cell) >= 2 and max(cell) < SIZE - 2]


def _replan(costs: np.ndarray, cells: list[tuple[int, int]]) -> tuple[int, int, np.ndarray]:
    """(replan expansions, fresh expansions, fresh points), the replan checked against fresh."""
    planner = FieldDStar(costs)
    planner.plan(START, GOAL)
    planner.update_costs(cells, np.inf)
    got = planner.replan()
    changed = costs.copy()
    for cell in cells:
        changed[cell] = np.inf
    fresh = FieldDStar(changed).plan(START, GOAL)
    np.testing.assert_array_equal(got.points, fresh.points)
    assert got.cost == fresh.cost
    return got.expanded, fresh.expanded, fresh.points


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_a_change_near_the_goal_is_given_up_after_the_probe(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Blocked 4 cells before the goal: nearly every node value rises.
    costs = _costs(seed)
    replan, fresh, _ = _replan(costs, _block(costs, -4.0))
    # The first stage stops within one rising expansion (RAISE_WORK units) past its
    # bound, and its projection gives up.
    assert fresh < replan <= fresh + _probe(fresh) + 3
    # Without the projection the same repair runs on to the cap.
    _single_bound(monkeypatch)
    full, _, _ = _replan(costs, _block(costs, -4.0))
    assert full > replan


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_repairs_the_probe_lets_through_match_the_single_bound(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Changes at several distances from the start: the staged bound gives the same
    # expansions as one bound wherever that one repairs without falling back.
    costs = _costs(seed)
    past_probe = 0
    for distance in (3.0, 8.0, 15.0, 25.0):
        cells = _block(costs, distance)
        two_stage, fresh, _ = _replan(costs, cells)
        with monkeypatch.context() as m:
            _single_bound(m)
            single, _, _ = _replan(costs, cells)
        if single < fresh:  # repaired under the single bound
            assert two_stage == single
            past_probe += single > _probe(fresh)
    assert past_probe > 0  # some repair outlived the probe and went on


def test_the_fallback_reuses_the_planner_arrays(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(field_dstar_module, "_REPAIR_CAP", 0.0)
    costs = _costs(6)
    planner = FieldDStar(costs)
    planner.plan(START, GOAL)
    arrays = [planner._g, planner._rhs, *planner._heap]
    cells = _block(costs, -6.0)
    planner.update_costs(cells, np.inf)
    got = planner.replan()
    after = [planner._g, planner._rhs, *planner._heap]
    assert all(a is b for a, b in zip(arrays, after, strict=True))
    changed = costs.copy()
    for cell in cells:
        changed[cell] = np.inf
    np.testing.assert_array_equal(got.points, FieldDStar(changed).plan(START, GOAL).points)


@pytest.mark.parametrize("seed", [3, 5])
def test_repairs_longer_than_a_twentieth_of_a_search_go_on(seed: int) -> None:
    # Changes along the path: those whose projected repair stays under a fresh
    # search are repaired to the end (not cut short at a fixed small fraction of
    # it, which made replans after changes mid-path cost a fresh search and more).
    costs = _costs(seed)
    long_repairs = 0
    for distance in (10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0):
        replan, fresh, _ = _replan(costs, _block(costs, distance))
        if replan < fresh:  # repaired, no fallback
            long_repairs += replan > 0.05 * fresh
    assert long_repairs > 0
