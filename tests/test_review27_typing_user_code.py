"""navkit's annotations as a user's type checker sees them (review 27).

``tests/typing_user_code/user_code.py`` is user code written from the docstrings and
docs/: mypy ``--strict`` must accept it, run as a user runs it (their own working
folder and configuration, navkit found as the installed, ``py.typed`` package). The
declarations for type checkers of the records it builds must keep the signatures
of the ``__init__`` the dataclasses generate at run time, and the annotated results
must be what the calls return.
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import math
import textwrap
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import MeasurementLog
from navkit.kinematics import DiffDrive
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import AttractiveField, FieldDStar, MapPlanner
from navkit.sim import EncoderReading, Lidar, Metrics, RangeNoise, Robot, WheelEncoders
from strict_mypy import check_strict

USER_CODE = Path(__file__).resolve().parent / "typing_user_code" / "user_code.py"


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_user_code_type_checks_under_mypy_strict(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    check_strict(USER_CODE, tmp_path, monkeypatch)


def _declared_init(cls: type) -> ast.FunctionDef:
    tree = ast.parse(textwrap.dedent(inspect.getsource(cls)))
    body = tree.body[0]
    assert isinstance(body, ast.ClassDef)
    for node in body.body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for inner in node.body:
                if isinstance(inner, ast.FunctionDef) and inner.name == "__init__":
                    return inner
    raise AssertionError(f"{cls.__name__} declares no __init__ for type checkers")


@pytest.mark.parametrize(
    "cls",
    # EncoderReading, AttractiveField and Metrics: declared by review 49.
    [
        Robot,
        Lidar,
        RangeNoise,
        MeasurementLog,
        LocalGrid,
        EncoderReading,
        AttractiveField,
        Metrics,
    ],
    ids=lambda c: c.__name__,
)
def test_declared_init_has_the_generated_parameters(cls: type) -> None:
    declared = _declared_init(cls).args
    positional = [a.arg for a in declared.args][1:]  # drop self
    keyword = [a.arg for a in declared.kwonlyargs]
    defaults = [False] * (len(positional) - len(declared.defaults)) + [True] * len(
        declared.defaults
    )
    defaults += [d is not None for d in declared.kw_defaults]
    # What the dataclass generates (RangeNoise's positional-deprecated wrapper keeps it).
    runtime = inspect.signature(cls)
    kinds = inspect.Parameter
    assert positional == [
        p.name for p in runtime.parameters.values() if p.kind is kinds.POSITIONAL_OR_KEYWORD
    ]
    assert keyword == [p.name for p in runtime.parameters.values() if p.kind is kinds.KEYWORD_ONLY]
    has_default = dict(zip(positional + keyword, defaults, strict=True))
    for p in runtime.parameters.values():
        assert has_default[p.name] == (p.default is not p.empty), p.name


def test_annotated_results_are_what_the_calls_return() -> None:
    planner = FieldDStar(np.ones((4, 4)), resolution=0.5, origin=(1.0, 0.0, 0.0))
    assert planner.world_to_node((1.6, 1.2)).dtype == np.int64
    assert planner.world_to_node([[1.6, 1.2]], continuous=True).dtype == np.float64
    # A list, as the annotation now allows (it always was converted).
    ticks = WheelEncoders(ticks_per_rev=1024, bits=16).ticks([0.5 * math.pi, 0.0])
    assert ticks.dtype == np.int64
    assert ticks.tolist() == [256, 0]
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    for footprint, error in ((0.2, 0.02), ([[0.2, 0.0], [-0.1, 0.1], [-0.1, -0.1]], [0.01, 0.0])):
        robot = Robot(drive=drive, footprint=footprint, wheel_radius_error=error)
        # Annotated FloatArray: an array even for the float (or default) error.
        assert isinstance(robot.wheel_radius_error, np.ndarray)
        assert robot.wheel_radius_error.dtype == np.float64
        # Annotated float | FloatArray.
        assert isinstance(robot.footprint, (float, np.ndarray))
    assert isinstance(Robot(drive=drive, footprint=0.2).wheel_radius_error, np.ndarray)
    assert Lidar(mount=(0.1, 0.0, 0.0)).mount.x == 0.1
    assert RangeNoise(limits=[3.0, math.inf], sigma=np.array([0.02, 0.05])).sigma == (0.02, 0.05)
    # The planner a MapPlanner reports is one its constructor takes back.
    old = MapPlanner(OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1))
    assert old.planner in ("astar", "field_dstar")
    assert MapPlanner(old.grid, planner=old.planner).planner == old.planner
