"""IndoorNav's planning case on a thread pool gives the serial sweep's results."""

from __future__ import annotations

import concurrent.futures
import sys
from collections.abc import Iterator
from typing import Any

import pytest

from navkit.sim import sweep
from navkit.sim.scenarios import IndoorNav
from navkit.sim.scenarios._indoor_nav_mapping import lab_planner


@pytest.fixture
def fast_switching() -> Iterator[None]:
    """Switch threads every 10 µs, so that a race shows within a few trials."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)
    try:
        yield
    finally:
        sys.setswitchinterval(old)


def _planning_values(result: Any) -> list[tuple[int, dict[str, Any]]]:
    """Each planning trial's values, wall-clock times left out."""
    return [
        (r.trial.index, {k: v for k, v in r.values.items() if "wall" not in k})
        for r in result.trials
        if "plan" in r.trial.case
    ]


@pytest.mark.usefixtures("fast_switching")
def test_threaded_sweep_equals_serial() -> None:
    # Every trial used to plan on the one cached Field D* planner, whose search
    # state the other threads rewrote mid-query: false "least cost is inf"
    # errors or other paths.
    scenario = IndoorNav(
        targets=1, paths=1, resolution=0.1, map_source="plan", compare_speed=None
    )
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        threaded = _planning_values(sweep(scenario, trials=1, executor=pool))
    serial = _planning_values(sweep(scenario, trials=1, workers=1))
    assert len(serial) >= 8
    assert threaded == serial


def test_field_dstar_planner_per_thread() -> None:
    here = lab_planner(0.1, False, "field_dstar", "plan")
    assert lab_planner(0.1, False, "field_dstar", "plan") is here
    assert lab_planner(0.1, False, "astar", "plan") is lab_planner(0.1, False, "astar", "plan")
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        there = pool.submit(lab_planner, 0.1, False, "field_dstar", "plan").result()
    assert there is not here
    assert there.plan((1.0, 1.0), (3.0, 2.0)).length == here.plan((1.0, 1.0), (3.0, 2.0)).length
