"""FieldDStar.replan(start_node) interrupted part-way: the start and its point move together.

``replan(start_node)`` moves the start node, then records the start's point
(the end :meth:`FieldDStar.replan_world` links to the path). A
``KeyboardInterrupt`` is delivered as a call returns: before session 21's
review one delivered as the ``float()`` computing that point returned left the
new start node with the old start's point, so a later ``replan_world()``
returned a path from the old point through the new start node, a path of
neither plan. The interrupt is injected after each ``float()`` call and each
kernel call the replan makes in turn (a name in the module wrapped to raise once
its call returned); the next ``replan_world()`` must then be the path of the
planner before or after the move.
"""

from __future__ import annotations

import builtins
import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.errors import NoPathError
from navkit.planning import FieldDStar, Path2D
from navkit.planning.grid import _field_dstar

N = 12
START_XY = (0.3, 0.3)
GOAL_XY = (N - 0.3, N - 0.3)


def _costs(seed: int) -> np.ndarray[Any, Any]:
    rng = np.random.default_rng(seed)
    costs = rng.uniform(1.0, 4.0, (N, N))
    costs[rng.random((N, N)) < 0.2] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    return costs


@contextmanager
def _interrupt_after(name: str, real: Callable[..., Any], after: int) -> Iterator[list[int]]:
    """Make the ``after``-th call of ``name`` in the module raise once it returned."""
    calls = [0]

    def wrapped(*args: Any) -> Any:
        out = real(*args)
        calls[0] += 1
        if calls[0] == after:
            raise KeyboardInterrupt
        return out

    had = name in vars(_field_dstar)
    setattr(_field_dstar, name, wrapped)
    try:
        yield calls
    finally:
        if had:
            setattr(_field_dstar, name, real)
        else:
            delattr(_field_dstar, name)  # a builtin: the module's own name goes


def _first_and_cost(path: Path2D) -> tuple[list[float], float]:
    return path.points[0].tolist(), path.cost


def _matches(got: Path2D, want: Path2D) -> bool:
    return bool(
        np.allclose(got.points[0], want.points[0], atol=1e-9)
        and math.isclose(got.cost, want.cost, rel_tol=1e-9, abs_tol=1e-12)
    )


@settings(max_examples=25, deadline=None, database=None)
@given(
    seed=st.integers(0, 2**16),
    where=st.sampled_from(["float", "_heuristic", "extract_path"]),
    after=st.integers(1, 6),
)
def test_an_interrupted_start_move_leaves_the_plan_before_or_after_it(
    seed: int, where: str, after: int
) -> None:
    costs = _costs(seed)
    planner = FieldDStar(costs)
    try:
        planner.plan_world(START_XY, GOAL_XY)
    except NoPathError:
        return
    free = np.argwhere(np.isfinite(costs[:-1, :-1]))
    new_start = tuple(int(v) for v in free[seed % len(free)])
    if new_start == (0, 0):
        return
    real = builtins.float if where == "float" else getattr(_field_dstar, where)
    with (
        _interrupt_after(where, real, after) as calls,
        suppress(KeyboardInterrupt, NoPathError, ValueError),
    ):
        planner.replan(new_start)
    if calls[0] < after:
        return  # the replan made fewer such calls: nothing interrupted
    outcomes = []
    for start_xy in (START_XY, tuple(planner.node_to_world(new_start).tolist())):
        with suppress(NoPathError, ValueError):
            outcomes.append(FieldDStar(costs).plan_world(start_xy, GOAL_XY))
    try:
        got = planner.replan_world()
    except (NoPathError, ValueError):
        assert len(outcomes) < 2
        return
    # Before the fix: the old point linked to the new start node, matching neither.
    assert any(_matches(got, want) for want in outcomes), (
        _first_and_cost(got),
        [_first_and_cost(want) for want in outcomes],
    )


def test_the_interrupt_right_after_the_move_keeps_the_start_and_its_point_together() -> None:
    planner = FieldDStar(np.ones((N, N)))
    planner.plan((0, 0), (N, N))
    moved = [False]
    real_move = FieldDStar._move_start

    def move(self: FieldDStar, s: tuple[int, int]) -> None:
        real_move(self, s)
        moved[0] = True

    def float_after_move(value: Any) -> float:
        out = builtins.float(value)
        if moved[0]:
            raise KeyboardInterrupt
        return out

    FieldDStar._move_start = move  # type: ignore[method-assign]
    setattr(_field_dstar, "float", float_after_move)  # noqa: B010
    try:
        with suppress(KeyboardInterrupt):
            planner.replan((6, 2))
    finally:
        FieldDStar._move_start = real_move  # type: ignore[method-assign]
        delattr(_field_dstar, "float")
    point = planner._start_point
    assert planner._start is not None and point is not None
    assert (math.floor(point[0]), math.floor(point[1])) == planner._start or point == (
        float(planner._start[0]),
        float(planner._start[1]),
    )
