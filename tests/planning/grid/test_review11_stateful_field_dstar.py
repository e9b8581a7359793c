"""FieldDStar under long random sequences of operations, checked against fresh planners.

A hypothesis state machine plans (nodes, cells, world points), changes cell costs
(blocks, unblocks, repeats), moves the start, replans, and swaps the planner for a
copy or a pickle round trip, in random order. After every replan the promise of
:meth:`FieldDStar.replan` / :meth:`FieldDStar.replan_world` is checked: the path
(points and cost) or the error equals what a fresh planner on the current costs
returns for the same ends (the last from-scratch plan, then the last start move).
Every from-scratch plan equals a fresh planner's too, and the planner's costs always
equal the model's. Errors leave the planner usable: the sequence continues.
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
from navkit.planning import FieldDStar, Path2D
from stateful_runs import COPIERS, run_machine

RES = 0.5
_COPIERS: tuple[Callable[[FieldDStar], FieldDStar], ...] = COPIERS
Outcome = Path2D | type[Exception]


def _outcome(call: Callable[[], Path2D]) -> Outcome:
    try:
        return call()
    except (NoPathError, ValueError, RuntimeError) as exc:
        return type(exc)


def _machine(rows: int, cols: int) -> type[RuleBasedStateMachine]:
    cost = st.sampled_from([1.0, 1.0, 2.0, 7.0, math.inf])
    node = st.tuples(st.integers(0, rows), st.integers(0, cols))
    cell = st.tuples(st.integers(0, rows - 1), st.integers(0, cols - 1))
    xy = st.tuples(st.floats(0.01, cols * RES - 0.01), st.floats(0.01, rows * RES - 0.01))

    class FieldDStarMachine(RuleBasedStateMachine):
        costs: np.ndarray[Any, np.dtype[np.float64]]
        planner: FieldDStar
        options: dict[str, Any]
        # The last from-scratch plan and the last start move: (method, arguments).
        origin: tuple[str, tuple[Any, ...]] | None
        moved: tuple[str, Any] | None
        # Cells near the last path found: changing them makes the repair work.
        near_path: list[tuple[int, int]]

        @initialize(
            seed=st.integers(0, 2**32 - 1),
            density=st.sampled_from([0.0, 0.15, 0.3]),
            interpolate=st.booleans(),
            lookahead=st.booleans(),
            smooth=st.booleans(),
        )
        def start(
            self, seed: int, density: float, interpolate: bool, lookahead: bool, smooth: bool
        ) -> None:
            rng = np.random.default_rng(seed)
            self.costs = rng.choice([1.0, 1.0, 2.0, 7.0], size=(rows, cols))
            self.costs[rng.random((rows, cols)) < density] = np.inf
            self.options = {
                "interpolate": interpolate,
                "lookahead": lookahead,
                "smooth": smooth,
                "resolution": RES,
            }
            self.planner = FieldDStar(self.costs, **self.options)
            self.origin = None
            self.moved = None
            self.near_path = []

        def _fresh(self) -> FieldDStar:
            return FieldDStar(self.costs, **self.options)

        def _same(self, got: Outcome, want: Outcome) -> None:
            if isinstance(got, type) or isinstance(want, type):
                assert got == want
                return
            grid_rc = got.points if got.frame == "grid" else got.points[:, ::-1] / RES - 0.5
            t = np.linspace(0.0, 1.0, 9)[:, None, None]
            along = (grid_rc[:-1] + t * (grid_rc[1:] - grid_rc[:-1])).reshape(-1, 2)
            cells = {(int(r), int(c)) for r, c in np.rint(along)}
            # Not the end cells: a blocked end is refused, and there is nothing to repair.
            ends = {(int(r), int(c)) for r, c in np.rint(grid_rc[[0, -1]])}
            self.near_path = sorted(
                (r, c) for r, c in cells - ends if 0 <= r < rows and 0 <= c < cols
            )
            assert got.frame == want.frame
            assert math.isclose(got.cost, want.cost, rel_tol=1e-9, abs_tol=1e-12)
            assert got.points.shape == want.points.shape
            np.testing.assert_allclose(got.points, want.points, atol=1e-9)

        def _plan(self, method: str, a: Any, b: Any) -> None:
            got = _outcome(lambda: getattr(self.planner, method)(a, b))
            self._same(got, _outcome(lambda: getattr(self._fresh(), method)(a, b)))
            if got in (ValueError, RuntimeError):
                return  # refused: the planner keeps its previous ends
            self.origin, self.moved = (method, (a, b)), None

        @rule(a=node, b=node)
        def plan(self, a: tuple[int, int], b: tuple[int, int]) -> None:
            self._plan("plan", a, b)

        @rule(a=cell, b=cell)
        def plan_cells(self, a: tuple[int, int], b: tuple[int, int]) -> None:
            self._plan("plan_cells", a, b)

        @rule(a=xy, b=xy)
        def plan_world(self, a: tuple[float, float], b: tuple[float, float]) -> None:
            self._plan("plan_world", a, b)

        @rule(cells=st.lists(cell, max_size=8), data=st.data())
        def update_costs(self, cells: list[tuple[int, int]], data: st.DataObject) -> None:
            values = data.draw(st.lists(cost, min_size=len(cells), max_size=len(cells)))
            self.planner.update_costs(
                np.array(cells, dtype=np.int64).reshape(-1, 2), np.array(values)
            )
            for c, v in zip(cells, values, strict=True):  # repeats: the last wins
                self.costs[c] = v

        @rule(data=st.data(), value=cost, method=st.sampled_from(["replan", "replan_world"]))
        def change_path_and_replan(self, data: st.DataObject, value: float, method: str) -> None:
            if self.near_path:
                target = data.draw(st.sampled_from(self.near_path))
                self.planner.update_costs(target, value)
                self.costs[target] = value
            self._replan(method, None)

        def _replan(self, method: str, start: Any) -> None:
            got = _outcome(lambda: getattr(self.planner, method)(start))
            moved = self.moved
            if start is not None and got not in (ValueError, RuntimeError):
                self.moved = (method, start)  # moved, even when no path was found
            if self.origin is None:
                assert got is RuntimeError
                return
            twin = self._fresh()
            method0, ends = self.origin
            first = _outcome(lambda: getattr(twin, method0)(*ends))
            if first is ValueError or first is NoPathError:
                return  # the first ends have no fresh plan on the current costs
            if (
                moved is not None
                and start is None
                and _outcome(lambda: getattr(twin, moved[0])(moved[1])) is ValueError
            ):
                return
            self._same(got, _outcome(lambda: getattr(twin, method)(start)))

        @rule(start=st.none() | node)
        def replan(self, start: tuple[int, int] | None) -> None:
            self._replan("replan", start)

        @rule(start=st.none() | xy)
        def replan_world(self, start: tuple[float, float] | None) -> None:
            self._replan("replan_world", start)

        @rule(how=st.integers(0, len(_COPIERS) - 1), cell=cell)
        def swap_for_copy(self, how: int, cell: tuple[int, int]) -> None:
            old, self.planner = self.planner, _COPIERS[how](self.planner)
            # The original changing must not reach the copy (checked by the invariant).
            old.update_costs(cell, 3.0 if self.costs[cell] != 3.0 else 4.0)
            _outcome(lambda: old.replan())

        @invariant()
        def costs_are_the_model(self) -> None:
            np.testing.assert_array_equal(self.planner.costs, self.costs)

    return FieldDStarMachine


_SMALL = _machine(5, 6)
_LARGE = _machine(30, 40)  # large enough for the repair bounds to cut repairs short


@pytest.mark.parametrize("machine", [_SMALL, _LARGE], ids=["5x6", "30x40"])
def test_replans_equal_fresh_plans(machine: type[RuleBasedStateMachine]) -> None:
    run_machine(machine, examples=30, steps=15)


@pytest.mark.slow
@pytest.mark.parametrize("machine", [_SMALL, _LARGE], ids=["5x6", "30x40"])
def test_replans_equal_fresh_plans_long(machine: type[RuleBasedStateMachine]) -> None:
    run_machine(machine, examples=400, steps=30)
