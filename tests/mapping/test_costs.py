"""Costs from occupancy grids: Nav2 costmap, traversal_costs and validate_costs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

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
    # Occupied cells only inflate (Nav2's default; the unknown cell 11 is just impassable).
    costs = traversal_costs(
        grid,
        robot_radius=0.1,
        inflation_radius=0.3,
        cost_scaling_factor=5.0,
        inflate_unknown=False,
    )
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


# ------------------------------------------------------------ issue 12: bad input
def unknown_corridor() -> OccupancyGrid:
    """A corridor of free cells with an occupied wall on one side, unknown on the other."""
    occupied = np.zeros((7, 9), dtype=bool)
    unknown = np.zeros((7, 9), dtype=bool)
    occupied[0, :] = True
    unknown[6, :] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)


def test_types_of_the_cost_options() -> None:
    grid = unknown_corridor()
    # unknown_cost=True used to be taken as 1.0.
    for value in (True, np.True_, "5", None, 1 + 0j, [5.0]):
        with pytest.raises(TypeError, match="unknown_cost must be a real number"):
            traversal_costs(grid, unknown_cost=value)  # type: ignore[arg-type]
    for value in (math.nan, -math.inf, 0.5, 2e9, 10**400):
        with pytest.raises(
            ValueError, match=r"unknown_cost must be (>= 1 and <= 1e9, or inf|finite)"
        ):
            traversal_costs(grid, unknown_cost=value)  # type: ignore[arg-type]
    for flag in ("no", 1, 0.0, np.array([True])):
        with pytest.raises(TypeError, match="inflate_unknown must be a bool"):
            traversal_costs(grid, inflate_unknown=flag)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match="inflate_unknown must be a bool"):
            costmap(grid, robot_radius=0.1, inflation_radius=0.1, inflate_unknown=flag)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match="inflate_around_unknown must be a bool"):
            costmap(grid, robot_radius=0.1, inflation_radius=0.1, inflate_around_unknown=flag)  # type: ignore[arg-type]
    # numpy's inf and booleans are the same values.
    assert np.array_equal(
        traversal_costs(grid, unknown_cost=np.float64(np.inf), inflate_unknown=np.True_),
        traversal_costs(grid, unknown_cost=math.inf, inflate_unknown=True),
    )


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        # OverflowError in the issue.
        (
            {"robot_radius": 0, "inflation_radius": 1e308},
            r"inflation_radius must be >= 0 and <= 1e6 m",
        ),
        ({"robot_radius": 2e6, "inflation_radius": 3e6}, r"robot_radius must be >= 0 and <= 1e6 m"),
        (
            {"robot_radius": 0.1, "inflation_radius": 0.2, "cost_scaling_factor": 1e13},
            r"cost_scaling_factor must be > 0 and <= 1e12 1/m",
        ),
        (
            {"robot_radius": 0.1, "inflation_radius": 0.2, "cost_scaling_factor": 0.0},
            r"cost_scaling_factor must be > 0",
        ),
    ],
)
def test_costmap_ranges(kwargs: dict[str, float], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        costmap(unknown_corridor(), **kwargs)  # type: ignore[arg-type]


def test_traversal_cost_ranges() -> None:
    grid = unknown_corridor()
    with pytest.raises(ValueError, match=r"robot_radius must be >= 0 and <= 1e6 m"):
        traversal_costs(grid, robot_radius=1e308)
    with pytest.raises(ValueError, match=r"cost_weight must be >= 0 and <= 1e9"):
        traversal_costs(grid, cost_weight=1e308)
    # Inside the ranges, finite costs stay finite and >= 1.
    costs = traversal_costs(
        grid,
        robot_radius=1e6,
        inflation_radius=1e6,
        cost_scaling_factor=1e12,
        cost_weight=1e9,
        unknown_cost=1e9,
    )
    assert np.array_equal(validate_costs(costs), costs)
    costs = traversal_costs(
        grid, robot_radius=0.0, inflation_radius=1e6, cost_scaling_factor=5e-324, cost_weight=1e9
    )
    finite = costs[np.isfinite(costs)]
    assert finite.size and np.all((finite >= 1.0) & (finite <= 1.0 + 1e9))


def test_inflate_unknown_keeps_the_body_clear_of_unknown_space() -> None:
    grid = unknown_corridor()  # row 0 occupied, rows 1..5 free, row 6 unknown
    old = traversal_costs(grid, robot_radius=0.1, inflate_unknown=False)
    # Only the occupied wall inflates: row 5, next to unknown space, is free.
    assert np.all(np.isinf(old[:2])) and np.all(old[2:6] == 1.0) and np.all(np.isinf(old[6]))
    new = traversal_costs(grid, robot_radius=0.1)  # unknown_cost inf: inflate_unknown True
    assert np.array_equal(new, traversal_costs(grid, robot_radius=0.1, inflate_unknown=True))
    assert np.all(np.isinf(new[:2])) and np.all(new[2:5] == 1.0) and np.all(np.isinf(new[5:]))
    # The inflation cost decays from unknown cells as from occupied ones.
    band = traversal_costs(grid, robot_radius=0.1, inflation_radius=0.3, cost_scaling_factor=5.0)
    assert band[2, 0] == band[4, 0] > band[3, 0] > 1.0
    # A robot allowed into unknown space (finite unknown_cost) is not kept away from it.
    crossing = traversal_costs(grid, robot_radius=0.1, unknown_cost=3.0)
    assert np.array_equal(
        crossing, traversal_costs(grid, robot_radius=0.1, unknown_cost=3.0, inflate_unknown=False)
    )
    assert np.all(crossing[5] == 1.0) and np.all(crossing[6] == 3.0)
    with pytest.raises(ValueError, match="inflate_unknown=True treats unknown cells as obstacles"):
        traversal_costs(grid, robot_radius=0.1, unknown_cost=3.0, inflate_unknown=True)
    # A point robot: unknown cells are impassable either way, nothing else changes.
    assert np.array_equal(traversal_costs(grid), traversal_costs(grid, inflate_unknown=False))


def test_costmap_keeps_nav2s_two_unknown_parameters_apart() -> None:
    grid = unknown_corridor()
    kw = {"robot_radius": 0.1, "inflation_radius": 0.3, "cost_scaling_factor": 5.0}
    plain = costmap(grid, **kw)
    assert np.all(plain[6] == 255) and plain[5, 0] == 0
    # inflate_unknown (Nav2): unknown cells take inflated costs > 0; not sources.
    assert np.array_equal(costmap(grid, **kw, inflate_unknown=True)[:6], plain[:6])
    # inflate_around_unknown (Nav2): unknown cells are sources and become lethal.
    around = costmap(grid, **kw, inflate_around_unknown=True)
    assert np.all(around[6] == 254) and np.all(around[5] == 253)
    assert np.all(around[4] == around[2]) and around[3, 0] < around[2, 0] < 253
    costs = traversal_costs(grid, **kw)
    assert np.array_equal(np.isinf(costs), around >= 253)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 0.35))
def test_default_costs_keep_robot_radius_from_unknown_cells(seed: int, radius: float) -> None:
    rng = np.random.default_rng(seed)
    labels = rng.choice(3, size=(12, 15), p=[0.8, 0.1, 0.1])
    grid = OccupancyGrid.from_occupancy(labels == 1, resolution=0.1, unknown=labels == 2)
    costs = traversal_costs(grid, robot_radius=radius)
    passable = np.argwhere(np.isfinite(costs))
    blocked = np.argwhere(labels > 0)
    if passable.size and blocked.size:
        gap = np.hypot(*(passable[:, None, :] - blocked[None, :, :]).transpose(2, 0, 1)).min()
        assert gap * 0.1 > radius
    assert np.array_equal(np.isinf(costs), grid.inflate(radius) | _inflate_unknown(grid, radius))


def _inflate_unknown(grid: OccupancyGrid, radius: float) -> np.ndarray:
    both = OccupancyGrid.from_occupancy(
        grid.occupied() | grid.unknown(), resolution=grid.resolution, origin=grid.origin
    )
    return both.inflate(radius)


def test_willow_garage_costs_keep_the_robot_clear_of_unknown_space(shared_data: Path) -> None:
    # The issue: on this map, whose walls are mostly unknown cells, a 0.2 m robot's
    # A* path passed 0.10 m from unknown space. Every cell its centre may use is
    # now more than 0.2 m from every unknown and occupied cell.
    folder = shared_data / "ros-map-server-maps" / "willow_garage_2010"
    grid = OccupancyGrid.load(folder / "willow-2010-02-18-0.10.yaml")
    costs = grid.traversal_costs(robot_radius=0.2)
    free_centres = grid.cell_to_world(np.argwhere(np.isfinite(costs)))
    for mask in (grid.unknown(), grid.occupied()):
        dist, _ = cKDTree(grid.cell_to_world(np.argwhere(mask))).query(free_centres)
        assert dist.min() > 0.2
    # The old behaviour (Nav2's default) is still there, asked for explicitly.
    old = grid.traversal_costs(robot_radius=0.2, inflate_unknown=False)
    dist, _ = cKDTree(grid.cell_to_world(np.argwhere(grid.unknown()))).query(
        grid.cell_to_world(np.argwhere(np.isfinite(old)))
    )
    assert dist.min() == pytest.approx(0.1)
