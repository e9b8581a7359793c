"""Copies and pickles of OmniDrive subclasses keep what the subclass adds."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.kinematics import OmniDrive

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]
COPY_IDS = ["copy", "deepcopy", "pickle"]


class _Labelled(OmniDrive):
    """A subclass with an instance dict."""

    label: str


class _Tagged(OmniDrive):
    """A subclass with a slot of its own."""

    __slots__ = ("tag",)
    tag: int


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_a_subclass_keeps_its_attributes(make_copy: Callable[[Any], Any]) -> None:
    # They were dropped: the state held only OmniDrive's slots.
    drive = _Labelled(np.radians([0.0, 120.0, 240.0]), wheel_radius=0.05, base_radius=0.2)
    drive.label = "y"
    twin = make_copy(drive)
    assert type(twin) is _Labelled
    assert twin.label == "y"
    assert not twin.jacobian.flags.writeable


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_a_subclass_with_slots_copies_whole(make_copy: Callable[[Any], Any]) -> None:
    # Copying raised AttributeError: the state held only the subclass's own slots.
    drive = _Tagged(np.radians([0.0, 120.0, 240.0]), wheel_radius=0.05, base_radius=0.2)
    drive.tag = 3
    twin = make_copy(drive)
    assert twin.tag == 3
    np.testing.assert_array_equal(twin.forward_matrix, drive.forward_matrix)
    assert not twin.forward_matrix.flags.writeable
    speeds = drive.inverse([0.3, -0.2, 0.5])
    assert twin.forward(speeds) == drive.forward(speeds)
