"""Which pass checks an A* planner's grid values (review 44, MUTANT19's surviving mutants).

When the options let jump point search run (``method`` "jps" or "auto",
8-connectivity, ``heuristic_weight`` 1), the kernel building JPS's bit tables
checks the values too, so the grid is scanned once and the separate compiled
scan (:func:`~navkit.planning.grid._limits.checked_cost_range`) is neither
called nor compiled on first use; with other options no table is built at
all. Mutants that sent "auto" through both passes, or built the tables for
4-connectivity or a heuristic weight above 1 (which then never used them),
gave the same plans and survived every test: the passes are counted here.
Also: an array ``heuristic_weight`` is refused by name, not by NumPy's
"truth value is ambiguous" (a mutant comparing it with 1 survived), and a
thread's scratch is reused by searches of the same size (mutants
reallocating it at every search survived).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.planning.grid import AStarPlanner, _astar, _workspace, astar


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


@pytest.mark.parametrize("method", ["jps", "auto"])
@pytest.mark.parametrize("weight", [np.ones(2), np.ones((1, 1)), [1.0]])
def test_an_array_heuristic_weight_is_refused_by_name(method: str, weight: Any) -> None:
    # The options are compared with 1 only when they are plain numbers: an
    # array's == is an array, whose truth value raised NumPy's "ambiguous" error.
    with pytest.raises(TypeError, match="heuristic_weight must be a real number"):
        AStarPlanner(np.ones((3, 3)), method=method, heuristic_weight=weight)
    with pytest.raises(TypeError, match="heuristic_weight must be a real number"):
        astar(np.ones((3, 3)), (0, 0), (2, 2), method=method, heuristic_weight=weight)


@pytest.mark.parametrize("method", ["astar", "jps"])
def test_searches_of_one_size_reuse_the_threads_scratch(method: str) -> None:
    planner = AStarPlanner(np.ones((20, 30)), method=method)
    planner.plan((0, 0), (19, 29))
    scratch = _astar._jps_scratch.records if method == "jps" else _workspace._local.rec
    planner.plan((19, 0), (0, 29))
    again = _astar._jps_scratch.records if method == "jps" else _workspace._local.rec
    assert again is scratch
