"""FieldDStar driven as a robot drives it: long random runs of world-point calls.

A hypothesis state machine plans between world points, then, in random order,
moves the robot along (and a little off) the current path and replans from there
(``replan_world`` with ``start_tolerance``, so that a robot in the inflation
escapes), blocks rectangles (obstacles, with a ring of inflation marked
``obstacles=False``), frees rectangles, raises and lowers costs on the path, plans
to new goals and swaps the planner for a copy or a pickle round trip. Every plan
from scratch must be a fresh planner's, bit for bit (points, cost, length,
expansions: a reused planner searches on its own arrays, the same search); every
replan must be a fresh planner's ``plan_world`` on the current costs and obstacle
mask from the same start to the same goal (cost to a relative 1e-9, points to
1e-9 m: the repair reads the values a fresh search reads), or fail as it fails.
The planner's costs must stay the model's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, precondition, rule

from navkit.errors import NoPathError
from navkit.planning import FieldDStar, Path2D
from stateful_runs import COPIERS, run_machine

RES = 0.25
ORIGIN = (1.0, -2.0, 0.0)
_COPIERS: tuple[Callable[[FieldDStar], FieldDStar], ...] = COPIERS
Outcome = Path2D | type[Exception]


def _outcome(call: Callable[[], Path2D]) -> Outcome:
    try:
        return call()
    except (NoPathError, ValueError, RuntimeError) as exc:
        return type(exc)


def _machine(rows: int, cols: int) -> type[RuleBasedStateMachine]:
    cell = st.tuples(st.integers(0, rows - 1), st.integers(0, cols - 1))
    inside = st.tuples(st.floats(0.05, 0.95), st.floats(0.05, 0.95))

    class FollowMachine(RuleBasedStateMachine):
        costs: np.ndarray[Any, np.dtype[np.float64]]
        obstacles: np.ndarray[Any, np.dtype[np.bool_]]
        planner: FieldDStar
        options: dict[str, Any]
        goal: tuple[float, float] | None
        start_xy: tuple[float, float] | None  # the start point the planner keeps
        path: Path2D | None

        @initialize(
            seed=st.integers(0, 2**32 - 1),
            density=st.sampled_from([0.0, 0.1, 0.2]),
            interpolate=st.booleans(),
        )
        def start(self, seed: int, density: float, interpolate: bool) -> None:
            rng = np.random.default_rng(seed)
            self.costs = rng.choice([1.0, 1.0, 1.0, 2.0, 5.0], size=(rows, cols))
            blocked = rng.random((rows, cols)) < density
            self.costs[blocked] = np.inf
            # Some impassable cells are inflation, which a start may escape from.
            self.obstacles = blocked & (rng.random((rows, cols)) < 0.5)
            self.options = {"interpolate": interpolate, "resolution": RES, "origin": ORIGIN}
            self.planner = FieldDStar(self.costs, obstacles=self.obstacles, **self.options)
            self.goal = None
            self.start_xy = None
            self.path = None

        def _fresh(self) -> FieldDStar:
            return FieldDStar(self.costs, obstacles=self.obstacles, **self.options)

        def _world(self, c: tuple[int, int], frac: tuple[float, float]) -> tuple[float, float]:
            return (ORIGIN[0] + (c[1] + frac[1]) * RES, ORIGIN[1] + (c[0] + frac[0]) * RES)

        def _set(self, cells: list[tuple[int, int]], value: float, obstacles: bool | None) -> None:
            if not cells:
                return
            arr = np.array(cells, dtype=np.int64).reshape(-1, 2)
            if obstacles is None:
                self.planner.update_costs(arr, value)
            else:
                self.planner.update_costs(arr, value, obstacles=obstacles)
            for c in cells:
                was_open = math.isfinite(self.costs[c])
                self.costs[c] = value
                if obstacles is not None:
                    self.obstacles[c] = obstacles
                elif math.isfinite(value):
                    self.obstacles[c] = False
                elif was_open:
                    self.obstacles[c] = True  # closed here: an obstacle

        @rule(a=cell, fa=inside, b=cell, fb=inside, tol=st.sampled_from([0.0, 0.3, 1.0]))
        def plan_world(
            self,
            a: tuple[int, int],
            fa: tuple[float, float],
            b: tuple[int, int],
            fb: tuple[float, float],
            tol: float,
        ) -> None:
            start, goal = self._world(a, fa), self._world(b, fb)
            got = _outcome(lambda: self.planner.plan_world(start, goal, start_tolerance=tol))
            want = _outcome(lambda: self._fresh().plan_world(start, goal, start_tolerance=tol))
            if isinstance(got, type) or isinstance(want, type):
                assert got == want
            else:
                assert got.points.tobytes() == want.points.tobytes()
                assert (got.cost, got.length, got.expanded) == (
                    want.cost,
                    want.length,
                    want.expanded,
                )
            if got is ValueError or got is RuntimeError:
                return  # refused: the planner keeps its previous ends
            self.goal, self.start_xy = goal, start
            self.path = None if isinstance(got, type) else got

        @precondition(lambda self: self.goal is not None)
        @rule(
            along=st.floats(0.0, 1.0),
            dx=st.floats(-0.6, 0.6),
            dy=st.floats(-0.6, 0.6),
            tol=st.sampled_from([0.0, 0.3, 1.0]),
            off=st.booleans(),
        )
        def drive_and_replan(
            self, along: float, dx: float, dy: float, tol: float, off: bool
        ) -> None:
            assert self.goal is not None
            if self.path is not None:
                pts = self.path.points
                i = min(int(along * (len(pts) - 1)), len(pts) - 1)
                j = min(i + 1, len(pts) - 1)
                here = pts[i] + (along * (len(pts) - 1) - i) * (pts[j] - pts[i])
            else:
                here = np.array(self._world((rows // 2, cols // 2), (0.5, 0.5)))
            # Off the path: a localisation error that may put the robot in the inflation.
            start = (
                float(here[0] + (dx if off else 0.0) * RES),
                float(here[1] + (dy if off else 0.0) * RES),
            )
            self._replan(start, tol)

        @precondition(lambda self: self.goal is not None)
        @rule(data=st.data(), frac=inside, tol=st.sampled_from([0.3, 1.0]))
        def drift_into_the_inflation(
            self, data: st.DataObject, frac: tuple[float, float], tol: float
        ) -> None:
            # The robot's estimate in the band drawn around an obstacle: it escapes.
            band = np.argwhere(np.isinf(self.costs) & ~self.obstacles)
            if len(band):
                r, c = band[data.draw(st.integers(0, len(band) - 1))]
                self._replan(self._world((int(r), int(c)), frac), tol)

        @precondition(lambda self: self.goal is not None)
        @rule(tol=st.sampled_from([0.0, 0.3, 1.0]))
        def replan_from_the_kept_start(self, tol: float) -> None:
            self._replan(None, tol)

        def _replan(self, given: tuple[float, float] | None, tol: float) -> None:
            goal, start = self.goal, self.start_xy if given is None else given
            assert goal is not None and start is not None
            got = _outcome(lambda: self.planner.replan_world(given, start_tolerance=tol))
            want = _outcome(lambda: self._fresh().plan_world(start, goal, start_tolerance=tol))
            if isinstance(got, type) or isinstance(want, type):
                assert got == want, (got, want)
            else:
                assert got.frame == want.frame
                assert math.isclose(got.cost, want.cost, rel_tol=1e-9, abs_tol=1e-12), (
                    got.cost,
                    want.cost,
                )
                assert got.points.shape == want.points.shape
                np.testing.assert_allclose(got.points, want.points, atol=1e-9)
            if got is not ValueError:  # refused: the planner keeps its previous start
                self.start_xy = start
            if not isinstance(got, type):
                self.path = got

        @rule(
            corner=cell,
            h=st.integers(1, 4),
            w=st.integers(1, 4),
            ring=st.booleans(),
        )
        def block_rectangle(self, corner: tuple[int, int], h: int, w: int, ring: bool) -> None:
            r0, c0 = corner
            core = [
                (r, c) for r in range(r0, min(r0 + h, rows)) for c in range(c0, min(c0 + w, cols))
            ]
            self._set(core, math.inf, None)
            if ring:
                band = [
                    (r, c)
                    for r in range(max(r0 - 1, 0), min(r0 + h + 1, rows))
                    for c in range(max(c0 - 1, 0), min(c0 + w + 1, cols))
                    if (r, c) not in core and not self.obstacles[r, c]
                ]
                self._set(band, math.inf, False)

        @rule(
            corner=cell,
            h=st.integers(1, 6),
            w=st.integers(1, 6),
            value=st.sampled_from([1.0, 2.0, 5.0]),
        )
        def free_rectangle(self, corner: tuple[int, int], h: int, w: int, value: float) -> None:
            r0, c0 = corner
            self._set(
                [
                    (r, c)
                    for r in range(r0, min(r0 + h, rows))
                    for c in range(c0, min(c0 + w, cols))
                ],
                value,
                None,
            )

        @precondition(lambda self: self.path is not None)
        @rule(data=st.data(), value=st.sampled_from([1.0, 3.0, 9.0, math.inf]), k=st.integers(1, 3))
        def change_on_path(self, data: st.DataObject, value: float, k: int) -> None:
            assert self.path is not None
            # Cells under the path's points (world to cell), not the ends' cells.
            pts = self.path.points
            rc = np.floor((pts[:, ::-1] - np.array(ORIGIN[1::-1])) / RES).astype(int)
            cells = sorted(
                {(int(r), int(c)) for r, c in rc[1:-1] if 0 <= r < rows and 0 <= c < cols}
            )
            if cells:
                chosen = data.draw(st.lists(st.sampled_from(cells), min_size=1, max_size=k))
                self._set(chosen, value, None)

        @rule(how=st.integers(0, len(_COPIERS) - 1), c=cell)
        def swap_for_copy(self, how: int, c: tuple[int, int]) -> None:
            old, self.planner = self.planner, _COPIERS[how](self.planner)
            # The original changing must not reach the copy (checked by the invariant).
            old.update_costs(c, 3.0 if self.costs[c] != 3.0 else 4.0)
            _outcome(lambda: old.replan_world())

        @invariant()
        def costs_are_the_model(self) -> None:
            np.testing.assert_array_equal(self.planner.costs, self.costs)

    return FollowMachine


_SMALL = _machine(8, 10)
_LARGE = _machine(40, 50)  # large enough for repairs to be cut short and boxes to matter


@pytest.mark.parametrize("machine", [_SMALL, _LARGE], ids=["8x10", "40x50"])
def test_driving_replans_equal_fresh_plans(machine: type[RuleBasedStateMachine]) -> None:
    run_machine(machine, examples=60, steps=20)


@pytest.mark.slow
@pytest.mark.parametrize("machine", [_SMALL, _LARGE], ids=["8x10", "40x50"])
def test_driving_replans_equal_fresh_plans_long(machine: type[RuleBasedStateMachine]) -> None:
    run_machine(machine, examples=300, steps=40)
