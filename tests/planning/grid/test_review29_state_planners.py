"""AStarPlanner and MapPlanner queried many times in random order, against fresh planners.

Both prepare once and answer many queries: AStarPlanner keeps its validated costs
and search tables (and borrows per-thread scratch arrays), MapPlanner its costs,
a snapshot of the map and, with ``"field_dstar"``, a planner that keeps search
state between queries. A hypothesis state machine asks random queries (cells and
world points, blocked and outside ends, start tolerances), changes the caller's
cost array and map after construction (which must not reach the planner: both
copy), and swaps the planner for a copy or a pickle round trip. Every answer must
be a fresh planner's on the construction-time inputs: the same path bit for bit,
or the same error type.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.errors import NoPathError
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import AStarPlanner, MapPlanner, Path2D
from stateful_runs import COPIERS, run_machine

ROWS, COLS, RES = 14, 18, 0.2
Outcome = Path2D | type[Exception]


def _outcome(call: Callable[[], Path2D]) -> Outcome:
    try:
        return call()
    except (NoPathError, ValueError) as exc:
        return type(exc)


def _same(got: Outcome, want: Outcome) -> None:
    if isinstance(got, type) or isinstance(want, type):
        assert got == want
        return
    assert got.frame == want.frame
    assert got.points.tobytes() == want.points.tobytes()
    assert (got.cost, got.length) == (want.cost, want.length)


_CELL = st.tuples(st.integers(-1, ROWS), st.integers(-1, COLS))
_POINT = st.tuples(st.floats(-0.1, COLS * RES + 0.1), st.floats(-0.1, ROWS * RES + 0.1))


class PlannersMachine(RuleBasedStateMachine):
    costs: np.ndarray[Any, np.dtype[np.float64]]  # the caller's array, changed later
    snapshot: np.ndarray[Any, np.dtype[np.float64]]
    astar_options: dict[str, Any]
    astar: AStarPlanner
    grid: OccupancyGrid  # the caller's map, changed later
    grid_snapshot: OccupancyGrid
    map_options: dict[str, Any]
    mapper: MapPlanner

    @initialize(
        seed=st.integers(0, 2**32 - 1),
        connectivity=st.sampled_from([4, 8]),
        corner_cutting=st.booleans(),
        weight=st.sampled_from([1.0, 1.5]),
        method=st.sampled_from(["astar", "jps"]),
        which=st.sampled_from(["astar", "field_dstar"]),
        radius=st.sampled_from([0.0, 0.2, 0.3]),
    )
    def start(
        self,
        seed: int,
        connectivity: int,
        corner_cutting: bool,
        weight: float,
        method: str,
        which: str,
        radius: float,
    ) -> None:
        rng = np.random.default_rng(seed)
        uniform = method == "jps"  # JPS plans on uniform costs only
        self.costs = (
            np.ones((ROWS, COLS)) if uniform else rng.choice([1.0, 1.0, 2.0, 4.0], (ROWS, COLS))
        )
        self.costs[rng.random((ROWS, COLS)) < 0.2] = np.inf
        self.snapshot = self.costs.copy()
        self.astar_options = {
            "connectivity": connectivity,
            "corner_cutting": corner_cutting,
            "heuristic_weight": weight,
            "method": method,
        }
        if method == "jps" and (connectivity != 8 or weight != 1.0):
            self.astar_options.update(connectivity=8, heuristic_weight=1.0)
        self.astar = AStarPlanner(self.costs, **self.astar_options)
        probabilities = rng.choice([0.05, 0.05, 0.05, 0.95, 0.5], (ROWS, COLS))
        self.grid = OccupancyGrid.from_probabilities(probabilities, resolution=RES)
        self.grid_snapshot = self.grid.copy()
        self.map_options = {"robot_radius": radius, "planner": which}
        self.mapper = MapPlanner(self.grid, **self.map_options)

    @rule(a=_CELL, b=_CELL)
    def plan_cells(self, a: tuple[int, int], b: tuple[int, int]) -> None:
        fresh = AStarPlanner(self.snapshot, **self.astar_options)
        _same(_outcome(lambda: self.astar.plan(a, b)), _outcome(lambda: fresh.plan(a, b)))

    @rule(a=_POINT, b=_POINT, tol=st.sampled_from([0.0, 0.25, 1.0]))
    def plan_world(self, a: tuple[float, float], b: tuple[float, float], tol: float) -> None:
        fresh = MapPlanner(self.grid_snapshot, **self.map_options)
        _same(
            _outcome(lambda: self.mapper.plan(a, b, start_tolerance=tol)),
            _outcome(lambda: fresh.plan(a, b, start_tolerance=tol)),
        )

    @rule(
        cell=st.tuples(st.integers(0, ROWS - 3), st.integers(0, COLS - 3)),
        x=st.floats(0.3, COLS * RES - 0.3),
        y=st.floats(0.3, ROWS * RES - 0.3),
        heading=st.floats(-3.0, 3.0),
        a=_CELL,
        b=_CELL,
        pa=_POINT,
        pb=_POINT,
    )
    def change_callers_inputs(
        self,
        cell: tuple[int, int],
        x: float,
        y: float,
        heading: float,
        a: tuple[int, int],
        b: tuple[int, int],
        pa: tuple[float, float],
        pb: tuple[float, float],
    ) -> None:
        # The caller's cost array and map change (a 3 x 3 block flipped; the map as a
        # mapper changes it); the planners planned on their own copies, as the next
        # queries show.
        r, c = cell
        block = self.costs[r : r + 3, c : c + 3]
        block[...] = np.where(np.isfinite(block), math.inf, 1.0)
        scan = LaserScan(
            np.full(16, 0.7), angle_min=-math.pi, angle_increment=math.pi / 8,
            range_min=0.05, range_max=5.0,
        )  # fmt: skip
        self.grid.integrate_scan(scan, (x, y, heading), hit=5.0, miss=-5.0)
        self.plan_cells(a, b)
        self.plan_world(pa, pb, 0.0)

    @rule(how=st.integers(0, len(COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old_a, self.astar = self.astar, COPIERS[how](self.astar)
        old_m, self.mapper = self.mapper, COPIERS[how](self.mapper)
        # The originals going on must not reach the copies.
        _outcome(lambda: old_a.plan((0, 0), (ROWS - 1, COLS - 1)))
        _outcome(lambda: old_m.plan((0.1, 0.1), (COLS * RES - 0.1, ROWS * RES - 0.1)))

    @invariant()
    def costs_are_the_snapshot(self) -> None:
        np.testing.assert_array_equal(self.astar.costs, self.snapshot)


def test_repeated_queries_equal_fresh_planners() -> None:
    run_machine(PlannersMachine, examples=60, steps=20)


@pytest.mark.slow
def test_repeated_queries_equal_fresh_planners_long() -> None:
    run_machine(PlannersMachine, examples=300, steps=40)
