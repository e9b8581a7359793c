"""Records keep their text fields as plain ``str``, not NumPy's ``np.str_`` (review 32).

A label taken from an array (``np.str_``) was stored as given, and NumPy 2 writes it
as ``np.str_('x')`` in the record's repr: ``Event(t=1.5, kind=np.str_('collision'), ...)``.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit._shared.text import as_text
from navkit.estimation import UpdateResult
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMatchResult
from navkit.mapping.io import BagImu, BagOdometry, BagScans
from navkit.planning.grid import Path2D
from navkit.sim import Event, Metrics, MovingObstacle, WarmupStep

S = np.str_


def _scan() -> LaserScan:
    return LaserScan(
        np.array([1.0, 2.0]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
    )


def _imu(topic: str, frame: str) -> BagImu:
    return BagImu(
        topic,
        frame,
        np.array([0.0]),
        np.array([0.1]),
        np.array([[0.0, 0.0, 0.0, 1.0]]),
        np.array([[0.0, 0.0, 0.2]]),
        np.array([[0.0, 0.0, 9.8]]),
        np.eye(3)[None],
        np.eye(3)[None],
        np.eye(3)[None] * -1.0,
    )


# (record built from np.str_ text, the names of its text fields)
CASES: dict[str, tuple[Callable[[], Any], tuple[str, ...]]] = {
    "ScanMatchResult": (
        lambda: ScanMatchResult(Pose2D(1.0, 2.0, 0.0), np.eye(3), 4, 0.9, True, S("converged")),
        ("reason",),
    ),
    "UpdateResult": (
        lambda: UpdateResult(False, 30.2, np.array([5.0]), S("rejected by the gate")),
        ("reason",),
    ),
    "BagScans": (
        lambda: BagScans(S("/scan"), S("laser"), np.array([1.5]), np.array([1.6]), (_scan(),)),
        ("topic", "frame_id"),
    ),
    "BagOdometry": (
        lambda: BagOdometry(
            S("/odom"),
            S("odom"),
            S("base_link"),
            np.array([0.0]),
            np.array([0.1]),
            np.array([[1.0, 2.0, 0.5]]),
            np.array([[0.0, 0.0, 0.247404, 0.968912]]),
            np.array([[0.3, 0.0, 0.1]]),
            np.eye(6)[None],
            np.eye(6)[None],
        ),
        ("topic", "frame_id", "child_frame_id"),
    ),
    "BagImu": (lambda: _imu(S("/imu"), S("imu_link")), ("topic", "frame_id")),
    "BagImu.to_base": (
        lambda: _imu("/imu", "imu_link").to_base(
            np.array([0.0, 0.0, 0.0, 1.0]), frame_id=S("base_link")
        ),
        ("frame_id",),
    ),
    "Path2D": (
        lambda: Path2D(np.array([[0.0, 0.0], [1.0, 1.0]]), S("grid"), 1.5, 1.4, 2),  # type: ignore[arg-type]
        ("frame",),
    ),
    "Event": (lambda: Event(1.5, S("collision"), S("touched")), ("kind", "message")),
    "Metrics": (
        lambda: Metrics(
            True, S("goal reached"), 1.0, 0.9, 0.05, 0.06, 0.02, 0.01, 0.03, 0.2, 0, 1.2
        ),
        ("reason",),
    ),
    "MovingObstacle": (
        lambda: MovingObstacle(
            0.2,
            np.array([[0.0, 0.0], [1.0, 0.0]]),
            np.array([0.0, 1.0]),
            after=S("loop"),  # type: ignore[arg-type]
        ),
        ("after",),
    ),
    "WarmupStep": (
        lambda: WarmupStep(S("astar"), (S("navkit.k1"),), (S("navkit.k3"),), 1.5, 1.25),
        ("name",),
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_text_fields_are_plain_str(name: str) -> None:
    make, fields = CASES[name]
    record = make()
    for field in fields:
        value = getattr(record, field)
        assert type(value) is str, (field, type(value))
    assert "np.str_" not in repr(record)
    # Copies and pickles hold the same plain text.
    for twin in (copy.copy(record), copy.deepcopy(record), pickle.loads(pickle.dumps(record))):
        assert all(type(getattr(twin, f)) is str for f in fields)


def test_warmup_step_kernel_names_are_plain_str() -> None:
    step = WarmupStep("astar", (S("navkit.k1"),), (S("navkit.k3"),), 1.5, 1.25)
    assert [type(k) for k in (*step.compiled, *step.loaded)] == [str, str]


def test_as_text_copies_a_subclass_and_names_the_argument() -> None:
    class Loud(str):
        def __str__(self) -> str:
            return "something else"

    out = as_text(Loud("scan"), "topic")
    assert type(out) is str and out == "scan"
    plain = "scan"
    assert as_text(plain, "topic") is plain
    with pytest.raises(TypeError, match="topic must be a str, got bytes"):
        as_text(b"scan", "topic")


def test_a_non_str_kind_equal_to_a_reason_is_refused() -> None:
    # A one-element array compares equal to "collision": it passed the vocabulary check.
    with pytest.raises(TypeError, match="kind must be a str"):
        Event(1.5, np.array(["collision"]), "touched")  # type: ignore[arg-type]
