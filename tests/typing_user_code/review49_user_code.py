"""User code typed against navkit's public annotations (review 49).

Not collected by pytest: ``tests/test_review49_typing_user_code.py`` runs ``mypy
--strict`` on it, with shapely typed (a stub of the names used; shapely itself ships
no annotations, so its ``Polygon`` was ``Any`` and hid a missing ``ArrayLike``). Each
function calls the API as its docstrings document it.
"""

from __future__ import annotations

import concurrent.futures
import math
from typing import Literal, assert_type

import numpy as np
from numpy.typing import NDArray

from navkit.behaviours import GameState
from navkit.mapping.io import MovingAIScenarios
from navkit.planning import AStarPlanner, AttractiveField, astar
from navkit.sim import EncoderReading, EndReason, Metrics, MovingObstacle, Trace, sweep
from navkit.sim.scenarios import Demo


def moving_obstacle_from_vertices() -> None:
    # "shape : float, shapely Polygon or array_like (V, 2)" in all three constructors.
    square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
    MovingObstacle(square, [[0.0, 0.0]], [0.0])
    MovingObstacle.constant_velocity(square, start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.0))
    MovingObstacle.scripted(np.array(square), [(0.0, 0.0), (1.0, 0.0)], speed=0.5)


def encoder_readings_of_any_integers() -> None:
    # "Integers of any NumPy dtype, or Python ints": a driver's uint64 counters, a list.
    EncoderReading(0.0, [10, 12])
    EncoderReading(0.02, np.array([2**63 + 3], dtype=np.uint64))
    EncoderReading(0.02, np.array([1, 2], dtype=np.int32))
    assert_type(EncoderReading(0.0, [1, 2]).ticks, NDArray[np.int64])


def game_state_has_ball_is_a_bool() -> None:
    # Inferred on construction when omitted: "after it has_ball is always a bool".
    state = GameState(robot_xy=(0, 0), ball_xy=(1, 0), own_goal_xy=(-4, 0), opponent_goal_xy=(4, 0))
    holds: bool = state.has_ball
    assert_type(state.opponent_with_ball, int | None)
    GameState(
        robot_xy=(0, 0),
        ball_xy=(1, 0),
        own_goal_xy=(-4, 0),
        opponent_goal_xy=(4, 0),
        has_ball=None if holds else True,
    )


class Pull(AttractiveField):
    """A field of the user's own: a constant pull along +x (no fields of its own)."""

    def _potential(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
        return -pts[:, 0]

    def _force(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.tile([1.0, 0.0], (len(pts), 1))


def attractive_field_subclass_takes_a_tuple() -> None:
    # AttractiveField's goal_xy is array_like, as in every navkit subclass.
    assert_type(Pull((1.0, 2.0)).with_goal([3.0, 4.0]), Pull)


def sweep_executors() -> None:
    # "executor : concurrent.futures.Executor or dask.distributed.Client": was Any, so a
    # mistake such as an int (meant as workers) went unchecked until run time.
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        sweep("demo", trials=1, executor=pool)
        Demo().run(1, executor=pool)
    sweep("demo", trials=1, executor=3)  # type: ignore[arg-type]
    Demo().run(1, executor=2)  # type: ignore[arg-type]


def movingai_problems_named_by_strings() -> None:
    # "map_names : sequence of str": was Any, so numbers where names belong went unchecked.
    cells = [[1, 2]], [[3, 2]]
    MovingAIScenarios([0], ["arena.map"], [[49, 49]], *cells, [2.0])
    MovingAIScenarios([0], ("arena.map",), [[49, 49]], *cells, [2.0])
    MovingAIScenarios([0], [49], [[49, 49]], *cells, [2.0])  # type: ignore[list-item]


def end_reasons_are_the_literal(trace: Trace, why: str) -> None:
    # Metrics.reason is always one of EndReason (checked on construction): a typo in a
    # comparison is now a type error (--strict's strict equality), a match can be total.
    reason = trace.metrics.reason
    assert_type(reason, EndReason)
    if reason == "goal reachd":  # type: ignore[comparison-overlap]
        pass
    # Built from any str, as Simulation does (the value is checked at run time).
    Metrics(False, why, 1.0, math.nan, 0.5, math.nan, math.nan, math.nan, math.nan, 1.0, 0, 0.0)


def astar_methods_are_the_literal() -> None:
    # "method : {"astar", "jps", "auto"}": a misspelt one is now a type error, and the
    # planner's resolved method ("auto" never) goes back into the constructor.
    costs = np.ones((4, 4))
    jps = AStarPlanner(costs, method="jps")
    assert_type(jps.method, Literal["astar", "jps"])
    AStarPlanner(costs, method=jps.method)
    astar(costs, (0, 0), (3, 3), method="auto")
    astar(costs, (0, 0), (3, 3), method="jsp")  # type: ignore[arg-type]
