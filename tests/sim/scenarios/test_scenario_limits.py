"""Scenario options at their documented limits, and the same seed through ``sweep``.

* omni-apf: a target close enough for the obstacle box to touch the robot at
  its start (0.5-0.7 m) used to be accepted, the run then failing half-way
  with "the robot starts inside an obstacle"; such routes are refused when the
  scenario is built, and from 1 m on the box stands clear of both ends.
* soccer: a Table 6 map of fewer than 120 cells cuts the ring of false minima
  off the grid; the table says so instead of showing 0 false minima beside a
  note about the ring.
* Every scenario gives the same figures (wall-clock ones aside) for a seed
  with one worker and with two.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from navkit.sim import Scenario, sweep
from navkit.sim.scenarios import OmniApf, Soccer
from navkit.sim.scenarios._omni_apf_setup import BODY_RADIUS, obstacle_boxes
from navkit.sim.scenarios._soccer_table6 import table6_values
from scenario_results import SMALL, comparable

# ---------------------------------------------------------------- omni-apf


@pytest.mark.parametrize("distance", [0.5, 0.6, 0.7, 0.99])
@pytest.mark.parametrize("obstacles", [None, True])
def test_omni_apf_refuses_a_route_too_short_for_its_obstacle(
    distance: float, obstacles: bool | None
) -> None:
    with pytest.raises(ValueError, match=r"targets\[1\]"):
        OmniApf(obstacles=obstacles, targets=[(0.0, 3.0), (distance, 0.0)])


def test_omni_apf_keeps_short_routes_without_the_obstacle() -> None:
    assert OmniApf(obstacles=False, targets=[(0.5, 0.0)]).targets == ((0.5, 0.0),)


def test_omni_apf_runs_the_shortest_obstacle_route() -> None:
    """At the 1 m limit the obstacle run starts (it used to raise from 0.5 to 0.7 m)."""
    scenario = OmniApf(noise=False, obstacles=True, targets=[(1.0, 0.0)], duration=2.0)
    result = scenario.run_trial(scenario.trials()[0])
    assert result.values["collisions"] == 0.0
    assert result.values["min_clearance"] > 0.0


@given(
    distance=st.floats(1.0, 50.0),
    angle=st.floats(-math.pi, math.pi),
)
def test_omni_apf_obstacle_stands_clear_of_start_and_target(distance: float, angle: float) -> None:
    target = (distance * math.cos(angle), distance * math.sin(angle))
    if math.hypot(*target) < 1.0:  # rounding just under the limit
        return
    (box,) = obstacle_boxes((target,))
    for end in ((0.0, 0.0), target):
        gap = shapely.distance(box, shapely.Point(end)) - BODY_RADIUS
        assert gap >= 0.1
    # ... and on the way: a robot driving straight would hit it.
    line = shapely.LineString([(0.0, 0.0), target])
    assert shapely.distance(box, line) < BODY_RADIUS


# ------------------------------------------------------------------- soccer


def _table6_note(cells: int) -> str:
    scenario = Soccer(table_cells=cells)
    trial = scenario.trials(1)[-1]
    result = scenario.summarize([scenario.run_trial(trial)], seed=0)
    table = result.tables[-1]
    return " ".join(table.notes)


def test_a_small_table6_map_says_its_ring_is_cut_off() -> None:
    small = table6_values(100)
    assert small["w10_false_minima"] < table6_values(200)["w10_false_minima"]
    note = _table6_note(100)
    assert "100-cell map" in note and "off the grid" in note


def test_from_120_cells_table6_is_the_full_maps() -> None:
    at_limit = table6_values(120)
    full = table6_values(200)
    assert at_limit.keys() == full.keys()
    for key, value in full.items():
        assert at_limit[key] == pytest.approx(value, rel=1e-9, abs=1e-15, nan_ok=True), key
    assert "off the grid" not in _table6_note(120)


# ------------------------------------------------------------ determinism



def _same(a: Any, b: Any) -> bool:
    """Equal, NaN equal to NaN (JSON-like trees)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return (
            isinstance(b, (list, tuple))
            and len(a) == len(b)
            and all(_same(x, y) for x, y in zip(a, b, strict=True))
        )
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SMALL))
def test_one_and_two_workers_give_the_same_result(name: str, shared_data: Path) -> None:
    scenario: Scenario = SMALL[name]()
    one = comparable(sweep(scenario, trials=2, seeds=5, workers=1))
    again = comparable(sweep(scenario, trials=2, seeds=5, workers=1))
    two = comparable(sweep(scenario, trials=2, seeds=5, workers=2))
    assert _same(one, again)
    assert _same(one, two)
    assert len(one["trials"]) >= 2
