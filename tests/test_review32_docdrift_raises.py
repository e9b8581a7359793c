"""Bad input raises what the Raises section documents, for the calls a docs review found.

A sweep of the fuzz catalogues (``tests/fuzz``) over every public callable
compared each exception raised on hostile input with the callable's numpydoc
``Raises`` section; these calls raised a type their section did not name (or
had no section). Each case triggers the error and finds its type (or a base
of it) in the section.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import test_docstrings as docstrings
from navkit.estimation import UpdateResult
from navkit.geometry import ImuInBase, Pose2D
from navkit.kinematics import OmniDrive
from navkit.mapping import LaserScan, ScanMatcher, ScanMatchResult
from navkit.mapping.io import BagImu, BagOdometry, BagScans
from navkit.planning import CompositeField
from navkit.planning.grid import FieldDStar
from navkit.planning.reactive import BlendedAttraction
from navkit.sim import (
    CompassReading,
    EncoderReading,
    Event,
    ImuReading,
    ScanReading,
    ScenarioResult,
    Table,
    Trace,
    WarmupReport,
    WarmupStep,
)
from navkit.sim.scenarios import DiffAStar, Greedy, IndoorNav, OmniApf, Soccer


def _planned() -> FieldDStar:
    planner = FieldDStar(np.ones((5, 5)))
    planner.plan((0, 0), (5, 5))
    return planner


def _walled() -> FieldDStar:
    costs = np.ones((5, 5))
    costs[1:3, 1:3] = np.inf
    planner = FieldDStar(costs)
    planner.plan((0, 0), (5, 5))
    return planner


# (documented callable, the bad call, the exception it raises)
CASES: list[tuple[Callable[..., Any], Callable[[], Any], type[Exception]]] = [
    (FieldDStar.replan, lambda: _planned().replan(start_node=(1.5, 0)), TypeError),
    (FieldDStar.replan, lambda: _planned().replan(start_node="ab"), TypeError),
    (FieldDStar.replan, lambda: _planned().replan(start_node=(9, 9)), ValueError),
    (FieldDStar.replan, lambda: _planned().replan(start_node=(1,)), ValueError),
    (FieldDStar.replan, lambda: _walled().replan(start_node=(2, 2)), ValueError),
    (FieldDStar.replan, lambda: FieldDStar(np.ones((3, 3))).replan(), RuntimeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([1j]), TypeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma(["a"]), TypeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([np.nan]), ValueError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([np.inf]), ValueError),
    (OmniDrive.three_wheel, lambda: OmniDrive.three_wheel(wheel_radius=np.nan, base_radius=0.2),
     ValueError),
    (OmniDrive.three_wheel, lambda: OmniDrive.three_wheel(wheel_radius="a", base_radius=0.2),
     TypeError),
    (Table.render, lambda: _table().render(digits=1.5), TypeError),
    (Table.render, lambda: _table().render(digits=0), ValueError),
    (ScenarioResult.table, lambda: ScenarioResult("x", 0, (), (_table(),)).table(digits=True),
     TypeError),
    (ScenarioResult.table, lambda: ScenarioResult("x", 0, (), (_table(),)).table(digits=18),
     ValueError),
    (ScanMatcher.pyramid, lambda: ScanMatcher().pyramid(None), TypeError),  # type: ignore[arg-type]
    (Pose2D.__matmul__, lambda: Pose2D(0.0, 0.0, 0.0) @ [1.0, 2.0], ValueError),
    (Pose2D.__matmul__, lambda: Pose2D(0.0, 0.0, 0.0) @ ["a", 0.0, 0.0], TypeError),
    # Review 32 (FNF): record constructors that validated their input with no Raises section.
    (UpdateResult, lambda: UpdateResult("no", 1.0, np.zeros(1)), TypeError),  # type: ignore[arg-type]
    (BagScans, lambda: BagScans(123, "laser", [1.5], [1.6], (_scan(),)), TypeError),  # type: ignore[arg-type]
    (BagOdometry, lambda: _odometry(times=[0.0, np.nan]), ValueError),
    (BagImu, lambda: _imu(frame_id=b"imu"), TypeError),
    (ImuInBase, lambda: ImuInBase([0.0, 0.0, 0.0, 1.0], [[0.0, 0.0, 0.1]] * 2, [0.0, 0.0, 9.8]),
     ValueError),
    (CompositeField, lambda: CompositeField([None]), TypeError),  # type: ignore[list-item]
    (ScanReading, lambda: ScanReading(0.1, None), TypeError),  # type: ignore[arg-type]
    (EncoderReading, lambda: EncoderReading(0.0, np.array([[1, 2]])), ValueError),
    (CompassReading, lambda: CompassReading(np.nan, 90.0), ValueError),
    (ImuReading, lambda: ImuReading(0.0, "a", 0.0, 0.0), TypeError),  # type: ignore[arg-type]
    (Event, lambda: Event(0.0, "crashed", "x"), ValueError),
    (Trace, lambda: _trace(metrics=None), TypeError),
    (WarmupStep, lambda: WarmupStep(b"astar", (), (), 1.0, 1.0), TypeError),  # type: ignore[arg-type]
    (WarmupReport, lambda: WarmupReport((), 1.0, 0), ValueError),
    (DiffAStar, lambda: DiffAStar(parts=[]), ValueError),
    (Greedy, lambda: Greedy(noise="no"), TypeError),  # type: ignore[arg-type]
    (IndoorNav, lambda: IndoorNav(targets=0), ValueError),
    (OmniApf, lambda: OmniApf(latency=1.5), TypeError),  # type: ignore[arg-type]
    (Soccer, lambda: Soccer(max_speed=np.inf), ValueError),
    (ScanMatchResult, lambda: ScanMatchResult(Pose2D(0, 0, 0), np.eye(3), 0, 0.5, False, b"x"),
     TypeError),
    (ScanMatchResult, lambda: ScanMatchResult(Pose2D(0, 0, 0), np.eye(3), 0, 0.5, False, "x"),
     ValueError),
]  # fmt: skip


def _scan() -> LaserScan:
    return LaserScan([1.0, 2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)


def _odometry(times: Any) -> BagOdometry:
    return BagOdometry(
        "/odom", "odom", "base_link", times, [0.1, 0.2], np.zeros((2, 3)),
        np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)), np.zeros((2, 3)), np.zeros((2, 6, 6)),
        np.zeros((2, 6, 6)),
    )  # fmt: skip


def _imu(frame_id: Any) -> BagImu:
    return BagImu(
        "/imu", frame_id, [0.0], [0.1], [[0.0, 0.0, 0.0, 1.0]], [[0.0, 0.0, 0.2]],
        [[0.0, 0.0, 9.8]], np.eye(3)[None], np.eye(3)[None], np.eye(3)[None],
    )  # fmt: skip


def _trace(metrics: Any) -> Trace:
    return Trace(
        np.array([0.0, 0.1]),
        np.zeros((2, 3)),
        np.zeros((2, 3)),
        np.zeros((2, 3)),
        (),
        (),
        metrics,
    )


def _table() -> Table:
    return Table("t", ("a",), ((1.0,),))


def _documented(func: Callable[..., Any]) -> set[str]:
    """Exception names on the entry lines of ``func``'s Raises section."""
    section = docstrings._sections(docstrings._own_doc(func)).get("Raises", "")
    names: set[str] = set()
    for line in section.splitlines():
        if line and not line[0].isspace():
            names |= {name.rsplit(".", 1)[-1] for name in re.findall(r"[A-Za-z_][\w.]*", line)}
    return names


@pytest.mark.parametrize(
    ("func", "bad_call", "kind"),
    CASES,
    ids=[f"{f.__qualname__}-{k.__name__}-{i}" for i, (f, _, k) in enumerate(CASES)],
)
def test_the_raised_type_is_documented(
    func: Callable[..., Any], bad_call: Callable[[], Any], kind: type[Exception]
) -> None:
    with pytest.raises(kind) as raised:
        bad_call()
    documented = _documented(func)
    bases = {klass.__name__ for klass in inspect.getmro(type(raised.value))}
    assert documented & bases, (
        f"{func.__qualname__} raised {type(raised.value).__name__} ({raised.value}); its Raises"
        f" section names only {sorted(documented) or 'nothing'}"
    )
