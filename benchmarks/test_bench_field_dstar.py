"""Field D* speed on 1024 x 1024 maps: full plans against navkit's A*, local replans.

Run with ``python -m pytest benchmarks/test_bench_field_dstar.py --benchmark-only``.

The maps are those of ``test_bench_astar.py`` (random 20 % / 35 % blocked and
rooms-and-corridors, corner to corner). Field D* plans between the corner nodes
``(0, 0)`` and ``(1024, 1024)``; navkit's A* between the corner cells on the same
costs (``corner_cutting=False``), in the same group for a direct comparison.

The replan benchmark blocks a 2 x 2 block of cells straddling the current path
5 cells ahead of the robot and times :meth:`FieldDStar.replan`, alternately with
the robot at the start and moved 2 cells along its path. Each round starts from
a freshly planned (untimed) planner. Expansions are in ``extra_info``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
import shapely

from navkit.planning import FieldDStar, astar
from test_bench_astar import GOAL, MAPS, SIZE, START, benchmark_map

NODE_START = (0, 0)
NODE_GOAL = (SIZE, SIZE)


@pytest.mark.parametrize("name", MAPS)
def test_field_dstar_plan(benchmark: Any, name: str) -> None:
    costs = benchmark_map(name)
    benchmark.group = f"plan-{name}"
    path = benchmark.pedantic(
        lambda: FieldDStar(costs).plan(NODE_START, NODE_GOAL), rounds=5, warmup_rounds=1
    )
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost, points=len(path.points))


@pytest.mark.parametrize("name", MAPS)
def test_dstar_lite_8connected_plan(benchmark: Any, name: str) -> None:
    costs = benchmark_map(name)
    benchmark.group = f"plan-{name}"
    path = benchmark.pedantic(
        lambda: FieldDStar(costs, interpolate=False).plan(NODE_START, NODE_GOAL),
        rounds=5,
        warmup_rounds=1,
    )
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


@pytest.mark.parametrize("name", MAPS)
def test_navkit_astar_same_map(benchmark: Any, name: str) -> None:
    costs = benchmark_map(name)
    benchmark.group = f"plan-{name}"
    path = benchmark.pedantic(lambda: astar(costs, START, GOAL), rounds=5, warmup_rounds=1)
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


def _blocking_cells(nodes: np.ndarray, distance: float) -> list[tuple[int, int]]:
    """The 2 x 2 cells around the point ``distance`` along a path in node coordinates."""
    ahead = shapely.LineString(nodes).interpolate(distance)
    r = min(max(math.floor(ahead.x), 1), SIZE - 1)
    c = min(max(math.floor(ahead.y), 1), SIZE - 1)
    return [(r - 1, c - 1), (r - 1, c), (r, c - 1), (r, c)]


@pytest.mark.parametrize("moved", [False, True], ids=["same-start", "moved-2"])
@pytest.mark.parametrize("name", MAPS)
def test_field_dstar_local_replan(benchmark: Any, name: str, moved: bool) -> None:
    costs = benchmark_map(name)
    base = FieldDStar(costs).plan(NODE_START, NODE_GOAL)
    nodes = base.points + 0.5  # node coordinates (the path's points are node - 0.5)
    if moved:
        step = shapely.LineString(nodes).interpolate(2.0)
        new_start: tuple[int, int] | None = (round(step.x), round(step.y))
    else:
        new_start = None
    cells = _blocking_cells(nodes, 5.0 + (2.0 if moved else 0.0))
    keep = [cell for cell in cells if cell not in {(0, 0), (SIZE - 1, SIZE - 1)}]

    def setup() -> tuple[tuple[FieldDStar], dict[str, Any]]:
        planner = FieldDStar(costs)
        planner.plan(NODE_START, NODE_GOAL)
        planner.update_costs(keep, np.inf)
        return (planner,), {}

    def run(planner: FieldDStar) -> Any:
        return planner.replan(new_start)

    benchmark.group = f"replan-{name}"
    path = benchmark.pedantic(run, setup=setup, rounds=5)
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)
