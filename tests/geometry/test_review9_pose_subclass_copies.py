"""Copies and pickles of Pose2D / Twist2D subclasses keep the subclass's own attributes.

The slotted dataclass's generated state is the field values only, so a user's
subclass lost what it added (``copy.copy(tagged).note`` raised AttributeError).
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import pytest

from navkit.geometry import Pose2D, Twist2D


class TaggedPose(Pose2D):
    pass


class SlottedTwist(Twist2D):
    __slots__ = ("source",)


COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda value: pickle.loads(pickle.dumps(value)),
]


@pytest.mark.parametrize("duplicate", COPIES)
def test_subclass_attributes_survive(duplicate: Callable[[Any], Any]) -> None:
    pose = TaggedPose(1.0, -2.0, 3.0)
    pose.note = {"frame": "odom"}  # type: ignore[attr-defined]
    copied = duplicate(pose)
    assert type(copied) is TaggedPose
    assert (copied.x, copied.y, copied.theta) == (pose.x, pose.y, pose.theta)
    assert copied.note == {"frame": "odom"}
    twist = SlottedTwist(0.5, 0.1, -0.2)
    object.__setattr__(twist, "source", "wheels")
    copied_twist = duplicate(twist)
    assert type(copied_twist) is SlottedTwist
    assert copied_twist.as_array().tolist() == [0.5, 0.1, -0.2]
    assert copied_twist.source == "wheels"


@pytest.mark.parametrize("duplicate", COPIES)
def test_plain_records_copy_equal(duplicate: Callable[[Any], Any]) -> None:
    pose, twist = Pose2D(0.25, 4.0, -1.0), Twist2D(1.0, 0.0, 0.5)
    assert duplicate(pose) == pose and type(duplicate(pose)) is Pose2D
    assert duplicate(twist) == twist and type(duplicate(twist)) is Twist2D
