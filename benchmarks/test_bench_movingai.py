"""A* on MovingAI maps and whole-grid distance fields against pyastar2d, tcod, scikit-image, SciPy.

Run with ``python -m pytest benchmarks/test_bench_movingai.py --benchmark-only``.
The MovingAI maps come from ``../shared/data/movingai-grid-benchmarks`` (N.
Sturtevant, "Benchmarks for Grid-Based Pathfinding", IEEE TCIAIG 4(2), 2012; see
its README); tests on them skip when the folder is absent. The ``.map`` and
``.scen`` readers are those of ``tests/planning/grid/test_movingai.py``.

Routes: on each map of :data:`MAPS`, :data:`N_SCENARIOS` scenarios of the
map's ``.scen`` file, spread evenly over the sorted optimal lengths (shortest
to longest), planned one after the other by every contestant per call:

* ``navkit``: :func:`navkit.planning.astar` with ``corner_cutting=True``, the
  peers' graph (octile moves, a diagonal may pass an obstacle's corner);
* ``tcod``: ``tcod.path.AStar(passable, diagonal=√2)``, built per query;
* ``mcp``: scikit-image ``MCP_Geometric`` (Dijkstra with geometric move costs,
  ``√2·(c_u + c_v)/2`` on diagonals: navkit's costs), built per query, stopped
  when the goal is reached;
* ``pyastar2d``: Chebyshev moves (a diagonal costs as much as a straight
  step), so its routes are valid but up to a few per cent longer in octile
  length than the optimum;
* ``pure_python``: the heapq A* of ``test_bench_astar.py``.

:func:`check_routes` checks every contestant's routes, in ``test_routes_agree``
and on the result of each timed test's first call (the pure-Python A*'s: of its
one timed round): navkit's costs must equal tcod's, scikit-image's and the
pure-Python ones (1e-9 relative), pyastar2d's paths must be valid
(``grid_oracle.assert_valid_path``) and no shorter than navkit's, and navkit
without corner cutting (the MovingAI rules) must reproduce the published
optimal lengths (1e-6). A peer that is not installed skips its own tests and
checks only.

Distance fields (cost-to-go from one goal to every cell, corner cutting on) on
the 1024² ``random20`` map of ``test_bench_astar.py`` (goal: its corner) and
on ``Berlin_0_1024`` (goal: that of its longest scenario):

* ``navkit``: :func:`navkit.planning.distance_field`;
* ``csgraph``: ``scipy.sparse.csgraph.dijkstra`` on the same graph as a CSR
  matrix (:func:`grid_graph`, built once outside the timer);
* ``mcp``: ``MCP_Geometric.find_costs`` from the goal over the whole grid.

All three fields must be equal (same reachable cells, costs to 1e-9 relative).

``benchmarks/compare_peers.py`` runs the same workloads (``movingai-*``,
``distance-field-*``).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.sparse
from scipy.sparse.csgraph import dijkstra

from navkit.planning import astar, distance_field
from test_bench_astar import GOAL, benchmark_map, octile_length, python_astar, shared_data

ROOT = Path(__file__).resolve().parents[1]
DATA = "movingai-grid-benchmarks"
sys.path.insert(0, str(ROOT / "tests" / "planning" / "grid"))

from grid_oracle import assert_valid_path  # type: ignore[import-not-found]  # noqa: E402
from test_movingai import (  # type: ignore[import-not-found]  # noqa: E402
    Scenario,
    read_map,
    read_scenarios,
)

MAPS = [
    "dao/arena2",
    "maze/maze512-1-0",
    "random/random512-10-0",
    "room/8room_000",
    "street/Berlin_0_1024",
]
N_SCENARIOS = 10
FIELD_MAPS = ["random20", "street/Berlin_0_1024"]
ROUTERS = ["navkit", "tcod", "mcp", "pyastar2d", "pure_python"]
FIELDS = ["navkit", "csgraph", "mcp"]
SQRT2 = math.sqrt(2.0)

Routes = Callable[[], list[Any]]


@cache
def movingai(name: str) -> tuple[np.ndarray, tuple[Scenario, ...]]:
    """A MovingAI map as costs (1 or inf, read-only) and its scenarios, sorted by length."""
    base = shared_data(f"{DATA}/{name}.map").with_suffix("")
    costs = read_map(base.with_name(base.name + ".map"))
    costs.flags.writeable = False
    scenarios = read_scenarios(base.with_name(base.name + ".map.scen"))
    return costs, tuple(sorted(scenarios, key=lambda sc: sc.optimal))


def scenario_sample(name: str, n: int = N_SCENARIOS) -> tuple[Scenario, ...]:
    """``n`` scenarios spread evenly over the sorted optimal lengths (start ≠ goal), the longest
    included."""
    scenarios = [sc for sc in movingai(name)[1] if sc.optimal > 0.0]
    picks = np.linspace(0, len(scenarios) - 1, n).round().astype(int)
    return tuple(scenarios[i] for i in picks)


# ------------------------------------------------------------------ routes
def navkit_routes(costs: np.ndarray, scenarios: Sequence[Scenario]) -> Routes:
    """navkit's one-shot A* (corner cutting: the peers' graph) over the scenarios; costs."""

    def run() -> list[float]:
        return [astar(costs, sc.start, sc.goal, corner_cutting=True).cost for sc in scenarios]

    return run


def tcod_routes(costs: np.ndarray, scenarios: Sequence[Scenario]) -> Routes:
    """tcod's octile A* (built per query, as in ``test_bench_astar``); octile costs."""
    import tcod.path

    passable = np.isfinite(costs).astype(np.int8)

    def run() -> list[float]:
        out = []
        for sc in scenarios:
            steps = tcod.path.AStar(passable, diagonal=SQRT2).get_path(*sc.start, *sc.goal)
            out.append(octile_length(np.array([sc.start, *steps])))
        return out

    return run


def mcp_cost(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> float:
    """Least cost from ``start`` to ``goal`` by scikit-image's ``MCP_Geometric``."""
    from skimage.graph import MCP_Geometric

    cumulative, _ = MCP_Geometric(costs, fully_connected=True).find_costs([start], [goal])
    return float(cumulative[goal])


def mcp_routes(costs: np.ndarray, scenarios: Sequence[Scenario]) -> Routes:
    """scikit-image ``MCP_Geometric`` per scenario; costs."""

    def run() -> list[float]:
        return [mcp_cost(costs, sc.start, sc.goal) for sc in scenarios]

    return run


def pyastar2d_routes(costs: np.ndarray, scenarios: Sequence[Scenario]) -> Routes:
    """pyastar2d with diagonal moves (Chebyshev metric); the cell paths."""
    import pyastar2d

    weights = np.where(np.isfinite(costs), 1.0, np.inf).astype(np.float32)

    def run() -> list[np.ndarray]:
        return [
            pyastar2d.astar_path(weights, sc.start, sc.goal, allow_diagonal=True)
            for sc in scenarios
        ]

    return run


def python_routes(costs: np.ndarray, scenarios: Sequence[Scenario]) -> Routes:
    """The pure-Python heapq A* of ``test_bench_astar`` (corner cutting); costs."""

    def run() -> list[float]:
        return [python_astar(costs, sc.start, sc.goal, True) for sc in scenarios]

    return run


ROUTE_MAKERS: dict[str, Callable[[np.ndarray, Sequence[Scenario]], Routes]] = {
    "navkit": navkit_routes,
    "tcod": tcod_routes,
    "mcp": mcp_routes,
    "pyastar2d": pyastar2d_routes,
    "pure_python": python_routes,
}


def check_routes(
    costs: np.ndarray, scenarios: Sequence[Scenario], navkit: list[float], peer: str, result: Any
) -> str:
    """Check one contestant's routes against navkit's costs; a one-line verdict."""
    if peer == "pyastar2d":
        excess = 0.0
        for sc, path, best in zip(scenarios, result, navkit, strict=True):
            cost, _ = assert_valid_path(costs, path, sc.start, sc.goal, corner_cutting=True)
            assert cost >= best * (1.0 - 1e-12), f"{sc}: pyastar2d {cost} < optimum {best}"
            excess = max(excess, cost / best - 1.0)
        return f"valid paths, ≤ {100.0 * excess:.1f} % longer (Chebyshev moves)"
    np.testing.assert_allclose(result, navkit, rtol=1e-9)
    return "same costs" if peer != "navkit" else ""


def check_published(costs: np.ndarray, scenarios: Sequence[Scenario]) -> str:
    """navkit without corner cutting against the published optimal lengths."""
    got = [astar(costs, sc.start, sc.goal).cost for sc in scenarios]
    np.testing.assert_allclose(got, [sc.optimal for sc in scenarios], rtol=1e-6, atol=1e-6)
    return "no-cut costs = published optima"


# ------------------------------------------------------------------ fields
@cache
def field_case(name: str) -> tuple[np.ndarray, tuple[int, int]]:
    """Costs and goal cell of a distance-field workload."""
    if name in ("random20", "random35", "rooms"):
        return benchmark_map(name), GOAL
    costs, scenarios = movingai(name)
    return costs, scenarios[-1].goal


def grid_graph(costs: np.ndarray) -> scipy.sparse.csr_matrix:
    """navkit's 8-connected corner-cutting graph (both directions) as a CSR matrix, vectorised.

    Edge weights are ``step · (c_u + c_v) / 2`` between traversable cells
    (``tests/planning/grid/grid_oracle.grid_graph`` is the cell-by-cell model).
    """
    rows, cols = costs.shape
    index = np.arange(rows * cols).reshape(rows, cols)
    src, dst, weight = [], [], []
    for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
        here = (slice(0, rows - dr), slice(max(0, -dc), cols - max(0, dc)))
        there = (slice(dr, rows), slice(max(0, dc), cols - max(0, -dc)))
        a, b = costs[here], costs[there]
        ok = np.isfinite(a) & np.isfinite(b)
        w = math.hypot(dr, dc) * 0.5 * (a[ok] + b[ok])
        src += [index[here][ok], index[there][ok]]
        dst += [index[there][ok], index[here][ok]]
        weight += [w, w]
    n = rows * cols
    return scipy.sparse.csr_matrix(
        (np.concatenate(weight), (np.concatenate(src), np.concatenate(dst))), shape=(n, n)
    )


def navkit_field(costs: np.ndarray, goal: tuple[int, int]) -> Callable[[], np.ndarray]:
    return lambda: distance_field(costs, goal, corner_cutting=True)


def csgraph_field(costs: np.ndarray, goal: tuple[int, int]) -> Callable[[], np.ndarray]:
    graph = grid_graph(costs)
    source = goal[0] * costs.shape[1] + goal[1]

    def run() -> np.ndarray:
        field: np.ndarray = dijkstra(graph, directed=True, indices=source)
        return field.reshape(costs.shape)

    return run


def mcp_field(costs: np.ndarray, goal: tuple[int, int]) -> Callable[[], np.ndarray]:
    from skimage.graph import MCP_Geometric

    def run() -> np.ndarray:
        field: np.ndarray = MCP_Geometric(costs, fully_connected=True).find_costs([goal])[0]
        return field

    return run


FIELD_MAKERS: dict[str, Callable[[np.ndarray, tuple[int, int]], Callable[[], np.ndarray]]] = {
    "navkit": navkit_field,
    "csgraph": csgraph_field,
    "mcp": mcp_field,
}


def check_field(navkit: np.ndarray, other: np.ndarray) -> str:
    """Same reachable cells and costs (1e-9 relative); a one-line verdict."""
    reach = np.isfinite(navkit)
    assert np.array_equal(reach, np.isfinite(other)), "different reachable cells"
    np.testing.assert_allclose(other[reach], navkit[reach], rtol=1e-9)
    return f"same field ({int(reach.sum()):,} cells)"


# ------------------------------------------------------------------ tests
def _peer(name: str) -> None:
    """Skip the calling test, saying why, when contestant ``name``'s library is absent."""
    module = {"tcod": "tcod", "mcp": "skimage", "pyastar2d": "pyastar2d"}.get(name)
    if module is not None:
        pytest.importorskip(
            module, reason=f"peer {module} is not installed (pip install -e '.[bench]')"
        )


@pytest.mark.parametrize("contestant", ROUTERS)
@pytest.mark.parametrize("name", MAPS)
def test_routes(benchmark: Any, name: str, contestant: str) -> None:
    _peer(contestant)
    costs = movingai(name)[0]
    scenarios = scenario_sample(name)
    run = ROUTE_MAKERS[contestant](costs, scenarios)
    benchmark.group = f"MovingAI {name}, {N_SCENARIOS} routes"
    if contestant == "pure_python":
        # One 10-30 s round, checked after it (a checked run first would double it).
        result = benchmark.pedantic(run, rounds=1, iterations=1)
    else:
        result = run()
        benchmark(run)
    ours = result if contestant == "navkit" else navkit_routes(costs, scenarios)()
    check_routes(costs, scenarios, ours, contestant, result)


@pytest.mark.parametrize("check", ["published", "tcod", "mcp", "pyastar2d"])
@pytest.mark.parametrize("name", MAPS)
def test_routes_agree(name: str, check: str) -> None:
    """navkit against the published optima, and each peer against navkit (a missing peer
    skips its own check only)."""
    _peer(check)
    costs = movingai(name)[0]
    scenarios = scenario_sample(name)
    if check == "published":
        check_published(costs, scenarios)
        return
    ours = navkit_routes(costs, scenarios)()
    check_routes(costs, scenarios, ours, check, ROUTE_MAKERS[check](costs, scenarios)())


@pytest.mark.parametrize("contestant", FIELDS)
@pytest.mark.parametrize("name", FIELD_MAPS)
def test_field(benchmark: Any, name: str, contestant: str) -> None:
    _peer(contestant)
    run = FIELD_MAKERS[contestant](*field_case(name))
    benchmark.group = f"distance field {name}"
    benchmark.pedantic(run, rounds=5, warmup_rounds=1)


@pytest.mark.parametrize("peer", ["csgraph", "mcp"])
@pytest.mark.parametrize("name", FIELD_MAPS)
def test_fields_agree(name: str, peer: str) -> None:
    _peer(peer)
    case = field_case(name)
    check_field(navkit_field(*case)(), FIELD_MAKERS[peer](*case)())
