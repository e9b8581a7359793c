"""navkit's annotations as a strict user's type checker sees them (review 50, TYPING2).

``tests/typing_user_code/review50_user_code.py`` is user code written from the
docstrings: ``mypy --strict`` (and pyright, where installed) must accept it as a
user runs it. Its ``assert_type`` lines are what the checker infers and its
``# type: ignore`` lines calls the annotations refuse. The runtime tests check
that what the annotations promise is what the calls do: every overload's return
type is the type returned, every ``Literal`` holds the values the call accepts.
"""

from __future__ import annotations

import importlib.util
import inspect
import json
import math
import shutil
import subprocess
import sys
import typing
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.estimation import CompassCalibration, FusionStatus, UpdateResult, compass_to_yaw
from navkit.geometry import Pose2D, angle_diff, quaternion_to_yaw, wrap_angle
from navkit.kinematics import tick_delta, ticks_to_distance
from navkit.mapping import MapMode, OccupancyGrid, ScanMatchReason, ScanMatchResult
from navkit.mapping._scan_matcher import REASONS
from navkit.mapping.io import grid_to_msg_fields, write_map
from navkit.mapping.io._map_files import _WRITE_MODES
from navkit.sim import EndReason, Event
from navkit.sim.scenarios import IndoorNav
from navkit.sim.scenarios._indoor_nav import MapSource
from navkit.sim.scenarios._indoor_nav_mapping import MAP_SOURCES
from strict_mypy import check_strict
from test_review27_typing_user_code import (
    test_declared_init_has_the_generated_parameters as _declared_init_is_the_generated,
)

USER_CODE = Path(__file__).resolve().parent / "typing_user_code" / "review50_user_code.py"


# The user code reads messages from rosbags (navkit's "ros" extra and test dependency).
NEEDS = [name for name in ("mypy", "rosbags") if importlib.util.find_spec(name) is None]


@pytest.mark.skipif(bool(NEEDS), reason=f"not installed: {NEEDS}")
def test_user_code_type_checks_under_mypy_strict(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    check_strict(USER_CODE, tmp_path, monkeypatch)


@pytest.mark.skipif(
    shutil.which("pyright") is None or "rosbags" in NEEDS,
    reason="pyright or rosbags is not installed",
)
def test_user_code_type_checks_under_pyright_strict(tmp_path: Path) -> None:
    # An unneeded "type: ignore" is an error here too: the refused calls are refused.
    config = {"typeCheckingMode": "strict", "reportUnnecessaryTypeIgnoreComment": "error"}
    (tmp_path / "pyrightconfig.json").write_text(json.dumps(config))
    code = tmp_path / USER_CODE.name
    code.write_text(USER_CODE.read_text())
    pyright = shutil.which("pyright")
    assert pyright is not None
    run = subprocess.run(
        [pyright, "--pythonpath", sys.executable, str(code)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert run.returncode == 0, run.stdout + run.stderr


# One number of each kind NumPy has, and Python's: the scalar overloads' RealScalar.
SCALARS = [
    np.float64(4.0),
    np.float32(4.0),
    np.float16(4.0),
    np.longdouble(4.0),
    np.int64(4),
    np.int8(4),
    np.uint64(4),
    4,
    4.0,
]


@pytest.mark.parametrize("value", SCALARS, ids=lambda v: type(v).__name__)
def test_a_numpy_scalar_gives_a_python_float(value: Any) -> None:
    results = [
        wrap_angle(value),
        angle_diff(value, 0.5),
        angle_diff(0.5, value),
        angle_diff(value, value),
        ticks_to_distance(value, ticks_per_rev=2048, wheel_radius=0.1),
        compass_to_yaw(value),
        CompassCalibration()(value),
        CompassCalibration(unwrap=True)(value),
    ]
    assert [type(r) for r in results] == [float] * len(results)
    assert results[0] == pytest.approx(4.0 - 2 * math.pi)


@pytest.mark.parametrize(
    "value",
    [np.int64(4), np.int8(4), np.uint16(4), np.uint64(4), 4],
    ids=lambda v: type(v).__name__,
)
def test_a_numpy_integer_tick_delta_is_a_python_int(value: Any) -> None:
    assert type(tick_delta(value, 2, bits=16)) is int
    assert tick_delta(np.uint16(65535), value, bits=16) == 5


def test_sequences_give_arrays_and_a_0d_array_a_float() -> None:
    # What the Sequence overloads promise, empty and nested too; and why an ndarray's
    # overload stays the union: a 0-d array gives a float.
    for value in ([1.0, 7.0], (1.0,), [], [[1.0], [7.0]]):
        assert type(wrap_angle(value)) is np.ndarray
        assert type(angle_diff(value, 0.0)) is np.ndarray
        assert type(angle_diff(0.0, value)) is np.ndarray
        assert type(compass_to_yaw(value)) is np.ndarray
        assert type(ticks_to_distance(value, ticks_per_rev=10, wheel_radius=1.0)) is np.ndarray
    assert type(tick_delta([1, 2], 3, bits=8)) is np.ndarray
    assert type(quaternion_to_yaw([0.0, 0.0, 0.0, 1.0])) is float
    assert type(quaternion_to_yaw([[0.0, 0.0, 0.0, 1.0]])) is np.ndarray
    assert type(wrap_angle(np.array(7.0))) is float
    assert type(wrap_angle(np.array([7.0]))) is np.ndarray


def _literal_default(function: Any, name: str) -> object:
    return inspect.signature(function).parameters[name].default


def test_map_mode_is_what_the_writers_take(tmp_path: Path) -> None:
    assert typing.get_args(MapMode) == _WRITE_MODES
    for function in (write_map, OccupancyGrid.save, grid_to_msg_fields):
        assert _literal_default(function, "mode") in typing.get_args(MapMode)
    grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1)
    assert write_map(grid, tmp_path / "a.yaml", mode="trinary").suffix == ".pgm"
    assert grid_to_msg_fields(grid, mode="trinary").data.tolist() == [100, 0]
    with pytest.raises(ValueError, match="mode must be"):
        write_map(grid, tmp_path / "b.yaml", mode="raw")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="mode must be"):
        grid_to_msg_fields(grid, mode="raw")  # type: ignore[arg-type]


def test_map_source_is_what_indoor_nav_takes() -> None:
    assert typing.get_args(MapSource) == MAP_SOURCES
    assert _literal_default(IndoorNav, "map_source") in MAP_SOURCES
    for source in MAP_SOURCES:
        scenario = IndoorNav(targets=1, paths=1, map_source=source)
        assert type(scenario.map_source) is str
        assert scenario.map_source == source
    with pytest.raises(ValueError, match="map_source must be"):
        IndoorNav(map_source="scan")  # type: ignore[arg-type]


def test_event_kind_is_one_of_end_reason() -> None:
    for reason in typing.get_args(EndReason):
        assert Event(1.0, reason, "").kind == reason
    with pytest.raises(ValueError, match="kind must be"):
        Event(1.0, "colision", "")


def test_scan_match_result_converts_what_its_constructor_is_typed_to_take() -> None:
    assert typing.get_args(ScanMatchReason) == REASONS
    result = ScanMatchResult(
        (1.0, 2.0, 0.5), [[1, 0, 0], [0, 1, 0], [0, 0, 1]], 4, 0.9, True, "converged"
    )
    assert result.pose == Pose2D(1.0, 2.0, 0.5)
    assert result.covariance.dtype == np.float64
    assert result.covariance.tolist() == np.eye(3).tolist()
    with pytest.raises(ValueError, match="reason must be"):
        ScanMatchResult(result.pose, np.eye(3), 4, 0.9, True, "max iterations")


def test_update_result_status_is_none_only_when_rejected_without_one() -> None:
    # Why UpdateResult.status keeps "| None": a rejected result built without a code.
    rejected = UpdateResult(False, 30.2, np.array([5.0]), "rejected by the gate")
    assert rejected.status is None
    assert UpdateResult(True, 0.5, np.array([0.1])).status is FusionStatus.ACCEPTED


@pytest.mark.parametrize("cls", [Event, ScanMatchResult], ids=lambda c: c.__name__)
def test_declared_init_has_the_generated_parameters(cls: type) -> None:
    # The __init__ declared for type checkers (review 50) keeps the generated one's
    # parameters, names, order and defaults (review 27's check).
    _declared_init_is_the_generated(cls)
