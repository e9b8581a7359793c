"""A planner borrowed without its grid's highest cost finds it when needed (review 44, MUTANT21).

:meth:`AStarPlanner._borrowing` documents ``highest`` as optional ("found
when needed"), and :class:`~navkit.planning.grid.MapPlanner` builds its A*
planner that way. A mutant of ``_highest_cost`` that found the cost only when
it was already known (``is not None`` for ``is None``) handed ``None`` on:
no public call reaches a borrowed planner without ``highest`` today (the
map planner only plans by A*, which never asks), so nothing caught it. Here
the borrowed planner must answer exactly as one built by the public
constructor: its distance field (the bucket queue needs the cost range) and
its choice of jump point search (which needs every traversable cell to cost
the same).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning.grid import AStarPlanner


def _grid(uniform: bool) -> np.ndarray:
    costs = np.ones((6, 9)) if uniform else 1.0 + np.arange(54.0).reshape(6, 9) % 4
    costs[1:5, 4] = np.inf
    return costs


@pytest.mark.parametrize("uniform", [True, False])
def test_a_borrowed_planners_distance_field_is_the_public_ones(uniform: bool) -> None:
    costs = _grid(uniform)
    public = AStarPlanner(costs)
    borrowed = AStarPlanner._borrowing(costs.copy(), 1.0, 8, False, 1.0)
    assert borrowed._highest is None  # the case under test: not handed over
    field = borrowed.distance_field((0, 8))
    np.testing.assert_array_equal(field, public.distance_field((0, 8)))
    assert borrowed._highest == float(costs[np.isfinite(costs)].max())


@pytest.mark.parametrize("method", ["jps", "auto"])
def test_a_borrowed_planner_on_uniform_costs_runs_jump_point_search(method: str) -> None:
    costs = _grid(True) * 2.5
    borrowed = AStarPlanner._borrowing(costs.copy(), 2.5, 8, False, 1.0, method)
    public = AStarPlanner(costs, method=method)
    assert borrowed.method == public.method == "jps"
    got, want = borrowed.plan((5, 0), (0, 8)), public.plan((5, 0), (0, 8))
    np.testing.assert_array_equal(got.cells, want.cells)
    assert got.cost == want.cost == pytest.approx(2.5 * want.length)


def test_a_borrowed_planner_on_varying_costs_refuses_jump_point_search() -> None:
    costs = _grid(False)
    assert AStarPlanner._borrowing(costs, 1.0, 8, False, 1.0, "auto").method == "astar"
    with pytest.raises(ValueError, match="cost the same"):
        AStarPlanner._borrowing(costs, 1.0, 8, False, 1.0, "jps")
