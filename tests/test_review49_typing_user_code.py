"""navkit's annotations as a strict user's type checker sees them (review 49, TYPING).

``tests/typing_user_code/review49_user_code.py`` is user code written from the
docstrings; mypy ``--strict`` must accept it, run as a user runs it (their own
configuration, navkit found as the installed package) and with shapely typed: a
stub of the names navkit uses stands in for ``types-shapely``, since with shapely
untyped its ``Polygon`` is ``Any`` and ``float | Polygon`` took anything. The
runtime tests check that what the annotations now promise is what the calls do.
"""

from __future__ import annotations

import importlib.util
import math
import typing
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray
from shapely.geometry import Polygon

from navkit.behaviours import GameState
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping.io import MovingAIScenarios
from navkit.planning import AStarPlanner, AttractiveField
from navkit.sim import (
    EncoderReading,
    EndReason,
    Metrics,
    MovingObstacle,
    Robot,
    Simulation,
    World,
    sweep,
)
from strict_mypy import check_strict

USER_CODE = Path(__file__).resolve().parent / "typing_user_code" / "review49_user_code.py"

# The shapely names navkit imports, typed; anything else stays Any.
SHAPELY_STUBS = {
    "shapely/__init__.pyi": "from typing import Any\ndef __getattr__(name: str) -> Any: ...\n",
    "shapely/ops.pyi": "from typing import Any\ndef __getattr__(name: str) -> Any: ...\n",
    "shapely/geometry/__init__.pyi": (
        "from typing import Any\n"
        "from shapely.geometry.base import BaseGeometry as BaseGeometry\n"
        "from shapely.geometry.polygon import Polygon as Polygon\n"
        "class LineString(BaseGeometry): ...\n"
        "def box(minx: float, miny: float, maxx: float, maxy: float, ccw: bool = ...)"
        " -> Polygon: ...\n"
        "def __getattr__(name: str) -> Any: ...\n"
    ),
    "shapely/geometry/base.pyi": (
        "from typing import Any\n"
        "class BaseGeometry:\n"
        "    def __getattr__(self, name: str) -> Any: ...\n"
    ),
    "shapely/geometry/polygon.pyi": (
        "from typing import Any\n"
        "from shapely.geometry.base import BaseGeometry\n"
        "class Polygon(BaseGeometry):\n"
        "    def __init__(self, shell: Any = ..., holes: Any = ...) -> None: ...\n"
        "def orient(polygon: Polygon, sign: float = ...) -> Polygon: ...\n"
    ),
}


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_user_code_type_checks_under_mypy_strict_with_shapely_typed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    stubs = tmp_path / "stubs"
    for name, text in SHAPELY_STUBS.items():
        (stubs / name).parent.mkdir(parents=True, exist_ok=True)
        (stubs / name).write_text(text)
    check_strict(USER_CODE, tmp_path, monkeypatch, mypy_path=stubs)


DASK_USER_CODE = """
from __future__ import annotations

from distributed import Client

from navkit.sim import sweep
from navkit.sim.scenarios import Demo


def on_a_cluster(client: Client) -> None:
    sweep("demo", trials=1, executor=client)
    Demo().run(1, executor=client)
"""


@pytest.mark.slow  # mypy reads dask and distributed: about 25 s cold
@pytest.mark.skipif(
    importlib.util.find_spec("mypy") is None or importlib.util.find_spec("distributed") is None,
    reason="mypy or distributed is not installed",
)
def test_a_typed_dask_client_is_an_executor(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # distributed ships py.typed: its Client's own signatures must satisfy the
    # executor type (a protocol of submit, gather and cancel).
    code = tmp_path / "on_a_cluster.py"
    code.write_text(DASK_USER_CODE)
    check_strict(code, tmp_path, monkeypatch)


def test_sweep_refuses_a_non_executor_as_typed() -> None:
    # What the annotation refuses, the run refuses too.
    with pytest.raises(TypeError, match="executor must be"):
        sweep("demo", trials=1, executor=3)  # type: ignore[arg-type]


SQUARE = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]


def test_moving_obstacle_constructors_take_vertices() -> None:
    moving = MovingObstacle.constant_velocity(SQUARE, start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.0))
    scripted = MovingObstacle.scripted(np.array(SQUARE), [(0.0, 0.0), (1.0, 0.0)], speed=0.5)
    for ob in (moving, scripted):
        assert isinstance(ob.shape, Polygon)
        assert ob.shape.area == pytest.approx(0.04)
    assert moving.position_at(2.0).tolist() == [2.0, 0.0]


@pytest.mark.parametrize(
    "ticks",
    [[10, 12], (10, 12), np.array([10, 12], dtype=np.int32), np.array([10, 12], dtype=np.uint64)],
    ids=["list", "tuple", "int32", "uint64"],
)
def test_encoder_reading_takes_integers_of_any_kind(ticks: object) -> None:
    reading = EncoderReading(0.02, ticks)  # type: ignore[arg-type]  # object: any of them
    assert reading.ticks.dtype == np.int64
    assert reading.ticks.tolist() == [10, 12]


@pytest.mark.parametrize("given", [None, True, False, np.True_], ids=repr)
def test_game_state_has_ball_is_always_a_bool(given: bool | None) -> None:
    state = GameState(
        robot_xy=(0.0, 0.0),
        ball_xy=(0.1, 0.0),
        own_goal_xy=(-4.0, 0.0),
        opponent_goal_xy=(4.0, 0.0),
        has_ball=given,
    )
    assert type(state.has_ball) is bool
    assert state.has_ball is (True if given is None else bool(given))


class _Pull(AttractiveField):
    def _potential(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
        return -pts[:, 0]

    def _force(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.tile([1.0, 0.0], (len(pts), 1))


def test_attractive_field_subclass_takes_the_goal_as_array_like() -> None:
    pull = _Pull((1, 2))
    assert pull.goal_xy.dtype == np.float64
    assert pull.goal_xy.tolist() == [1.0, 2.0]
    assert pull.force([0.0, 0.0]).tolist() == [[1.0, 0.0]]


@pytest.mark.parametrize(
    "names",
    [["arena.map"], ("arena.map",), np.array(["arena.map"])],
    ids=["list", "tuple", "array"],
)
def test_movingai_scenarios_take_any_iterable_of_names(names: object) -> None:
    problems = MovingAIScenarios([0], names, [[49, 49]], [[1, 2]], [[3, 2]], [2.0])  # type: ignore[arg-type]  # object: any of them
    assert problems.map_names == ("arena.map",)
    with pytest.raises(TypeError, match="map_names must hold str"):
        MovingAIScenarios([0], [49], [[49, 49]], [[1, 2]], [[3, 2]], [2.0])  # type: ignore[list-item]


def test_metrics_reason_is_one_of_end_reason() -> None:
    # What the EndReason annotation promises: the field holds one of its values only.
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    robot = Robot(drive=drive, footprint=0.2)
    trace = Simulation(
        World(), robot, lambda obs: Twist2D(0.0, 0.0, 0.0), start=(0.0, 0.0, 0.0), duration=0.05
    ).run()
    assert trace.metrics.reason == "timeout"
    assert trace.metrics.reason in typing.get_args(EndReason)
    figures = (1.0, math.nan, 0.5, math.nan, math.nan, math.nan, math.nan, 1.0, 0, 0.0)
    with pytest.raises(ValueError, match="reason"):
        Metrics(False, "goal", *figures)


@pytest.mark.parametrize(
    ("method", "resolved"), [("astar", "astar"), ("jps", "jps"), ("auto", "jps")]
)
def test_astar_methods_are_the_literal(method: str, resolved: str) -> None:
    # "auto" on a uniform 8-connected grid is JPS; the property never says "auto".
    planner = AStarPlanner(np.ones((4, 4)), method=method)  # type: ignore[arg-type]  # str
    assert planner.method == resolved
    assert AStarPlanner(np.ones((4, 4)), method=planner.method).method == resolved
    with pytest.raises(ValueError, match="method must be"):
        AStarPlanner(np.ones((4, 4)), method="jsp")  # type: ignore[arg-type]
