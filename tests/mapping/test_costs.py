"""Costs from occupancy grids: Nav2 costmap, traversal_costs and validate_costs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap, traversal_costs, validate_costs


def test_costmap_follows_nav2_inflation_layer() -> None:
    occ = np.zeros((1, 12), dtype=bool)
    occ[0, 0] = True
    unknown = np.zeros_like(occ)
    unknown[0, 1] = unknown[0, 4] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.05, unknown=unknown)
    cost = costmap(grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0)
    expected = [254, 253, 253]  # obstacle, unknown inside inscribed radius, inscribed
    # Beyond the inscribed radius: int(252 * exp(-5 (d - 0.1))) up to ceil(0.3/0.05) cells.
    expected += [int(252 * math.exp(-5.0 * (k * 0.05 - 0.1))) for k in range(3, 7)]
    expected += [0] * 5
    expected[4] = 255  # unknown keeps 255 when its inflated cost is < 253
    assert cost[0].tolist() == expected
    assert expected[3] == 196 and expected[6] == 92
    with_unknown = costmap(
        grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0, inflate_unknown=True
    )
    assert with_unknown[0, 4] == int(252 * math.exp(-5.0 * 0.1))
    with pytest.raises(ValueError, match=r"inflation_radius \(0\.1\) must be >= robot_radius"):
        costmap(grid, robot_radius=0.3, inflation_radius=0.1)
    with pytest.raises(ValueError, match="robot_radius must be >= 0"):
        costmap(grid, robot_radius=-0.1, inflation_radius=0.1)
    with pytest.raises(ValueError, match="cost_scaling_factor must be > 0"):
        costmap(grid, robot_radius=0.1, inflation_radius=0.1, cost_scaling_factor=0.0)
    with pytest.raises(TypeError, match="grid must be an OccupancyGrid"):
        costmap(occ, robot_radius=0.1, inflation_radius=0.1)  # type: ignore[arg-type]


def test_traversal_costs_for_planners() -> None:
    occ = np.zeros((1, 12), dtype=bool)
    occ[0, 0] = True
    unknown = np.zeros_like(occ)
    unknown[0, 11] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.05, unknown=unknown)
    costs = traversal_costs(grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0)
    nav2 = costmap(grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0)
    assert np.all(np.isinf(costs[0, :3]))
    assert costs[0, 3] == pytest.approx(1 + 4 * 196 / 252)
    assert costs[0, 8] == 1.0 and np.isinf(costs[0, 11])
    assert np.all(np.diff(costs[0, 3:8]) <= 0)
    band = nav2 < 253
    assert np.allclose(costs[band], 1 + 4 * nav2[band].astype(float) / 252)
    crossing = traversal_costs(
        grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0, unknown_cost=3.0
    )
    assert crossing[0, 11] == 3.0
    assert np.array_equal(validate_costs(costs), costs)
    assert np.array_equal(validate_costs(crossing), crossing)
    point_robot = traversal_costs(grid)
    assert np.isinf(point_robot[0, 0]) and point_robot[0, 1] == 1.0
    with pytest.raises(ValueError, match="unknown_cost must be >= 1"):
        traversal_costs(grid, unknown_cost=0.5)
    with pytest.raises(ValueError, match="cost_weight must be >= 0"):
        traversal_costs(grid, cost_weight=-1.0)
    with pytest.raises(TypeError, match="grid must be an OccupancyGrid"):
        traversal_costs(costs)  # type: ignore[arg-type]


def test_costs_share_one_robot_radius_with_inflate() -> None:
    # robot_radius means the same in inflate, costmap and traversal_costs: the
    # inscribed (253) and lethal (254) cells are exactly the inflated mask.
    occ = np.zeros((9, 11), dtype=bool)
    occ[4, 5] = occ[1, 1] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1)
    for radius in (0.0, 0.1, 0.2, 0.25, 0.3):
        nav2 = costmap(grid, robot_radius=radius, inflation_radius=radius + 0.2)
        assert np.array_equal(nav2 >= 253, grid.inflate(radius))
        costs = traversal_costs(grid, robot_radius=radius)
        assert np.array_equal(np.isinf(costs), grid.inflate(radius))


def test_validate_costs_is_the_planners_convention() -> None:
    good = np.array([[1.0, 2.5], [np.inf, 1.0]], dtype=np.float32)
    out = validate_costs(good)
    assert out.dtype == np.float64 and out.flags.c_contiguous
    assert np.array_equal(out, good.astype(np.float64))
    ready = np.ones((2, 3))
    assert validate_costs(ready) is ready  # no copy when nothing needs converting
    assert np.array_equal(validate_costs([[1, 2]]), [[1.0, 2.0]])
    for bad, match in [
        (np.ones(3), "must be 2-D"),
        (np.ones((0, 3)), "must not be empty"),
        (np.ones((2, 2), dtype=bool), "real-valued numeric"),
        ([[1.0, np.nan]], r"NaN \(found at \(0, 1\)\)"),
        ([[1.0, -np.inf]], "must be >= 1"),
        ([[1.0], [0.5]], r"found 0\.5 at \(1, 0\)"),
    ]:
        with pytest.raises(ValueError, match=match):
            validate_costs(bad)
