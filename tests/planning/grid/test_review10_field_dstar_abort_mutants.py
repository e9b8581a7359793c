"""A repair of a plan_cells search that is cut short keeps the two cells (mutation testing).

When a repair is hopeless (``_REPAIR_CAP``), FieldDStar replaces it by a fresh
search from the current start on its own arrays, "which returns the same path".
After :meth:`FieldDStar.plan_cells` that fresh search must still start from the
start cell's corners and end at the goal cell's: a wall across the grid forces
the fallback here, and the result must equal a fresh ``plan_cells`` on the new
costs.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.planning import FieldDStar
from navkit.planning.grid import _field_dstar


@pytest.mark.parametrize("n", [20, 40])
def test_a_repair_cut_short_after_plan_cells_equals_a_fresh_plan_cells(
    n: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The bounds in fractions of a fresh search only (these maps are small); the
    # probe at least one unit of work, so that its doubling stages grow.
    monkeypatch.setattr(_field_dstar, "_REPAIR_MIN_WORK", 0)
    monkeypatch.setattr(_field_dstar, "_REPAIR_PROBE_MIN_WORK", 1)
    costs = np.ones((n, n))
    start, goal = (n // 2, 0), (n // 2 + 1, n - 1)
    planner = FieldDStar(costs)
    planner.plan_cells(start, goal)
    resets: list[Any] = []
    real_reset = _field_dstar.FieldDStar._reset

    def counting_reset(self: FieldDStar, *args: Any, **kwargs: Any) -> Any:
        resets.append(kwargs)
        return real_reset(self, *args, **kwargs)

    monkeypatch.setattr(_field_dstar.FieldDStar, "_reset", counting_reset)
    wall = [(r, n // 2) for r in range(n - 2)]  # a long wall: the repair is hopeless
    planner.update_costs(wall, np.inf)
    got = planner.replan_world()
    assert len(resets) == 1  # the fresh search replaced the repair
    new_costs = costs.copy()
    new_costs[: n - 2, n // 2] = np.inf
    fresh = FieldDStar(new_costs)
    want = fresh.plan_cells(start, goal)
    np.testing.assert_array_equal(got.points, fresh.node_to_world(want.points + 0.5))
    assert got.cost == pytest.approx(want.cost, rel=1e-12)
    np.testing.assert_array_equal(planner.replan().points, fresh.replan().points)
