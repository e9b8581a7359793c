"""Which pass checks an A* planner's grid values (review 44, MUTANT19's surviving mutants).

When the options let jump point search run (``method`` "jps" or "auto",
8-connectivity, ``heuristic_weight`` 1), the kernel building JPS's bit tables
checks the values too, so the grid is scanned once and the separate compiled
scan (:func:`~navkit.planning.grid._limits.checked_cost_range`) is neither
called nor compiled on first use; with other options no table is built at
all. Mutants that sent "auto" through both passes, or built the tables for
4-connectivity or a heuristic weight above 1 (which then never used them),
gave the same plans and survived every test: the passes are counted here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.planning.grid import AStarPlanner, _astar, astar


def _counting(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    calls: list[str] = []
    for name in ("checked_cost_range", "jps_tables"):
        real: Callable[..., Any] = getattr(_astar, name)

        def spy(*args: Any, _real: Callable[..., Any] = real, _name: str = name) -> Any:
            calls.append(_name)
            return _real(*args)

        monkeypatch.setattr(_astar, name, spy)
    return calls


@pytest.mark.parametrize(
    ("options", "passes", "method"),
    [
        ({"method": "jps"}, ["jps_tables"], "jps"),
        ({"method": "auto"}, ["jps_tables"], "jps"),
        ({"method": "auto", "corner_cutting": True}, ["jps_tables"], "jps"),
        ({"method": "auto", "heuristic_weight": 1}, ["jps_tables"], "jps"),
        ({"method": "astar"}, ["checked_cost_range"], "astar"),
        ({"method": "auto", "connectivity": 4}, ["checked_cost_range"], "astar"),
        ({"method": "auto", "heuristic_weight": 2.0}, ["checked_cost_range"], "astar"),
        ({"method": "auto", "heuristic_weight": 0.5}, ["checked_cost_range"], "astar"),
    ],
)
def test_the_grid_is_scanned_by_one_pass(
    monkeypatch: pytest.MonkeyPatch, options: dict[str, Any], passes: list[str], method: str
) -> None:
    costs = np.ones((6, 7))
    costs[1:5, 3] = np.inf
    plain = {key: options[key] for key in ("connectivity", "corner_cutting") if key in options}
    expected = astar(costs, (0, 0), (5, 6), **plain)
    calls = _counting(monkeypatch)
    planner = AStarPlanner(costs, **options)
    assert calls == passes
    assert planner.method == method
    del calls[:]
    path = astar(costs, (0, 0), (5, 6), **options)
    assert calls == passes
    if options.get("heuristic_weight", 1.0) <= 1.0:
        assert path.cost == pytest.approx(expected.cost, rel=1e-12)
