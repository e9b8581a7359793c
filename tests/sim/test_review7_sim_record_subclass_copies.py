"""Subclasses of the simulator's frozen records copy and pickle whole, arrays read-only."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
import pytest

from navkit.kinematics import DiffDrive
from navkit.sim import Circle, MovingObstacle, Robot
from navkit.sim._sensors import EncoderReading

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]


class TaggedCircle(Circle):
    pass


@dataclass(frozen=True, slots=True)
class NamedCircle(Circle):
    name: str = ""


class TaggedObstacle(MovingObstacle):
    __slots__ = ("tag",)


class TaggedRobot(Robot):
    pass


@dataclass(frozen=True, slots=True)
class NamedReading(EncoderReading):
    name: str = ""


def _arrays(record: Any) -> dict[str, np.ndarray]:
    return {
        f.name: value
        for f in fields(record)
        if isinstance(value := getattr(record, f.name), np.ndarray)
    }


def _records() -> list[tuple[Any, str | None]]:
    """(record, name of an attribute its class adds outside the fields, or None)."""
    tagged = TaggedCircle((1.0, 2.0), 0.5)
    object.__setattr__(tagged, "note", [1])
    obstacle = TaggedObstacle.scripted(0.2, [(0.0, 0.0), (1.0, 0.0)], times=[0.0, 1.0])
    object.__setattr__(obstacle, "tag", "t")
    robot = TaggedRobot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    object.__setattr__(robot, "note", "r")
    return [
        (tagged, "note"),
        (NamedCircle((1.0, 2.0), 0.5, name="c"), None),
        (obstacle, "tag"),
        (robot, "note"),
        (NamedReading(0.5, np.array([1, 2]), name="e"), None),
    ]


@pytest.mark.parametrize("make_copy", COPIES)
@pytest.mark.parametrize("index", range(5))
def test_subclass_copies_keep_class_attributes_and_read_only_arrays(
    make_copy: Callable[[Any], Any], index: int
) -> None:
    record, extra = _records()[index]
    copied = make_copy(record)
    assert type(copied) is type(record)
    for f in fields(record):
        if f.name in _arrays(record):
            np.testing.assert_array_equal(getattr(copied, f.name), getattr(record, f.name))
        else:
            assert repr(getattr(copied, f.name)) == repr(getattr(record, f.name))
    for name, array in _arrays(copied).items():
        assert not array.flags.writeable, name
    if extra is not None:
        assert getattr(copied, extra) == getattr(record, extra)
