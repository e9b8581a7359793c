"""``costmap`` at a robot radius whose slack lands exactly on a cell (review 43, mutants).

``costmap`` widens ``robot_radius`` by ``CELL_EPS`` cells, so a cell centre
exactly at the widened radius is rare: the suite had none, and the mutants
``dist < robot_radius`` (inscribed test) and ``dist >= robot_radius``
(decaying band) of ``navkit.mapping._costs.inflation_costs`` passed it. At such
a radius the former left the cell out of both zones (cost 0 between a 253 and
a 252: a hole in the inflation) and the latter gave it 252 instead of 253.
The radii below are ``k * res - 1e-9 * res`` as rounded, the ones for which
``radius + 1e-9 * res`` is exactly ``k * res`` (found by search, rechecked
here). Oracle: the documented slack (a radius within 1e-9 cells of a cell's
distance includes it) and costs that never rise away from the obstacle.
Checked: fails on both mutants, passes on HEAD.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap

CASES = [
    (1.0, 2, 1.999999999),
    (0.5, 1, 0.4999999995),
    (0.25, 3, 0.74999999975),
    (0.1, 2, 0.1999999999),
    (0.05, 3, 0.14999999995000002),
]


@pytest.mark.parametrize(("res", "k", "radius"), CASES)
def test_a_cell_exactly_at_the_widened_radius_is_inscribed(
    res: float, k: int, radius: float
) -> None:
    assert radius + 1e-9 * res == k * res  # the case this test is about
    occupied = np.zeros((1, k + 6), dtype=bool)
    occupied[0, 0] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=res)
    cost = costmap(grid, robot_radius=radius, inflation_radius=radius + 4 * res).astype(int)[0]
    assert cost[0] == 254
    assert cost[1 : k + 1].tolist() == [253] * k
    # Outside: Nav2's truncated decay from the widened radius (±1: exp may differ by an ulp).
    for j in range(k + 1, k + 5):
        expected = int(252 * math.exp(-10.0 * (j * res - (radius + 1e-9 * res))))
        assert abs(int(cost[j]) - expected) <= 1, (j, cost.tolist())
    assert (np.diff(cost) <= 0).all(), cost.tolist()


def test_inflate_unknown_gives_unknown_cells_every_positive_cost_down_to_1() -> None:
    # Mutant ``cost <= 1`` for Nav2's ``cost == FREE_SPACE`` (review 43): no test had an
    # unknown cell whose inflated cost is exactly 1. A slow decay over a long row gives
    # every cost from 252 down to 1, then 0 beyond the inflation radius.
    occupied = np.zeros((1, 260), dtype=bool)
    occupied[0, 0] = True
    known = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    unknown = OccupancyGrid.from_occupancy(occupied, resolution=0.05, unknown=~occupied)
    free_cost = costmap(known, robot_radius=0.0, inflation_radius=10.0, cost_scaling_factor=0.5)
    assert {0, 1, 2} <= set(free_cost[0].tolist())
    got = costmap(
        unknown,
        robot_radius=0.0,
        inflation_radius=10.0,
        cost_scaling_factor=0.5,
        inflate_unknown=True,
    )
    assert np.array_equal(got, np.where(free_cost > 0, free_cost, 255))
