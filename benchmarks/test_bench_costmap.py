"""Nav2 inflation costs: :func:`navkit.mapping.costmap` against SciPy's distance transform.

Run with ``python -m pytest benchmarks/test_bench_costmap.py --benchmark-only
--benchmark-timer=time.thread_time`` (CPU time: the ratios stay meaningful on a
loaded machine; each group holds both contestants of one case, timed in the same
run).

Review 45 replaced the SciPy transform inside ``costmap``, ``inflate`` and
``traversal_costs`` with a banded exact transform of navkit's own (a numba
kernel, a band of rows at a time, so memory stays a band's at any radius).
Contestants, on the same map and radii:

* ``navkit``: :func:`costmap`, validation included;
* ``scipy``: what ``costmap`` computed before review 45, written out here:
  ``scipy.ndimage.distance_transform_edt`` of the free cells on the whole grid,
  then Nav2's costs (254 on obstacles, 253 within the robot radius, the
  truncated exponential decay up to the inflation radius, 0 beyond) in NumPy.

Maps: 200² (a small robot's local map), 1024² and 2048² with 2 % of the cells
occupied at random, 0.05 m cells, robot radius 0.2 m; inflation radius 0.55 m
(Nav2's default) and 5 m (100 cells, half the small map's rows). No unknown
cells, so both contestants compute the same thing; :func:`test_costs_agree`
checks them equal, cell for cell, before anything is timed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy import ndimage

from navkit.mapping import OccupancyGrid, costmap
from test_bench_astar import timed_fresh

RES = 0.05
ROBOT_RADIUS = 0.2
SCALING = 3.0
SIZES = (200, 1024, 2048)
RADII = (0.55, 5.0)
# Rounds of navkit's costmap (timed_fresh: a new grid each, one call each).
NAVKIT_ROUNDS = 20


def occupancy(size: int) -> np.ndarray:
    """A size × size map with 2 % of its cells occupied (seeded)."""
    return np.random.default_rng(size).random((size, size)) < 0.02


def scipy_costmap(occupied: np.ndarray, inflation_radius: float) -> np.ndarray:
    """Nav2's inflation costs from SciPy's transform of the whole grid (``costmap`` before)."""
    dist = ndimage.distance_transform_edt(~occupied)
    cost = np.zeros(occupied.shape, dtype=np.uint8)
    max_cells = math.ceil(inflation_radius / RES)
    band = (dist > 0) & (dist <= max_cells)
    metres = dist * RES
    cost[band & (metres <= ROBOT_RADIUS)] = 253
    decay = band & (metres > ROBOT_RADIUS)
    cost[decay] = (252 * np.exp(-SCALING * (metres[decay] - ROBOT_RADIUS))).astype(np.uint8)
    cost[occupied] = 254
    return cost


def navkit_costmap(grid: OccupancyGrid, inflation_radius: float) -> np.ndarray:
    return costmap(
        grid,
        robot_radius=ROBOT_RADIUS,
        inflation_radius=inflation_radius,
        cost_scaling_factor=SCALING,
    )


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("radius", RADII)
def test_costs_agree(size: int, radius: float) -> None:
    occupied = occupancy(size)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=RES)
    want = scipy_costmap(occupied, radius)
    got = navkit_costmap(grid, radius)
    assert np.array_equal(got, want)
    assert (want == 253).any() and ((want > 0) & (want < 253)).any()


@pytest.mark.parametrize("contestant", ["navkit", "scipy"])
@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("radius", RADII)
def test_costmap(benchmark: Any, contestant: str, size: int, radius: float) -> None:
    benchmark.group = f"costmap {size}² at {RES} m, inflation radius {radius} m"
    occupied = occupancy(size)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=RES)
    if contestant == "navkit":
        want = navkit_costmap(grid, radius)  # compiled (or loaded) outside the timer

        def check(_args: tuple[Any, ...], got: np.ndarray) -> None:
            assert np.array_equal(got, want)

        # Each round on a new grid (made outside the timer), every answer checked:
        # a costmap kept on the grid object cannot stand in for the inflation.
        cost = timed_fresh(
            benchmark,
            lambda g: navkit_costmap(g, radius),
            lambda: (OccupancyGrid.from_occupancy(occupied, resolution=RES),),
            check,
            rounds=NAVKIT_ROUNDS,
        )
    else:
        cost = benchmark(scipy_costmap, occupied, radius)
    benchmark.extra_info["inflated_cells"] = int((cost > 0).sum())
    assert cost.shape == (size, size)
