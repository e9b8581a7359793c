"""Copies of the mapping classes, subclasses included (seventh review)."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid

_COPIES: dict[str, Callable[[Any], Any]] = {
    "copy.copy": copy.copy,
    "copy.deepcopy": copy.deepcopy,
    "pickle": lambda obj: pickle.loads(pickle.dumps(obj)),
    "method": lambda obj: obj.copy(),
}


class _Tagged(OccupancyGrid):
    """A subclass adding an instance attribute (it has a ``__dict__``)."""

    note: list[str]


class _Slotted(OccupancyGrid):
    """A subclass adding a slot of its own."""

    __slots__ = ("label",)
    label: str


def _scan() -> LaserScan:
    return LaserScan(
        np.array([0.8]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=3.0
    )


@pytest.mark.parametrize("how", sorted(_COPIES))
def test_subclass_with_dict_copies_as_itself(how: str) -> None:
    grid = _Tagged.empty(width=2.0, height=1.0, resolution=0.25, origin=(1.0, -2.0, 0.3))
    assert isinstance(grid, _Tagged)
    grid.note = ["kept"]
    dup = _COPIES[how](grid)
    assert type(dup) is _Tagged
    assert dup.note == ["kept"]
    assert dup.origin == grid.origin and dup.resolution == grid.resolution
    assert np.array_equal(dup.logodds, grid.logodds)
    assert not dup.logodds.flags.writeable
    before = grid.logodds.copy()
    assert dup.integrate_scan(_scan(), (1.1, -1.9, 0.3)) > 0
    assert np.array_equal(grid.logodds, before)  # the copy's scan did not reach the original
    assert not np.array_equal(dup.logodds, before)


@pytest.mark.parametrize("how", sorted(_COPIES))
def test_subclass_with_own_slot_copies_as_itself(how: str) -> None:
    grid = _Slotted.from_probabilities([[0.2, 0.9]], resolution=0.5, occupied_thresh=0.8)
    assert isinstance(grid, _Slotted)
    grid.label = "walls"
    dup = _COPIES[how](grid)
    assert type(dup) is _Slotted
    assert dup.label == "walls"
    assert dup.occupied_thresh == 0.8
    assert dup.occupied().tolist() == grid.occupied().tolist()
    dup.integrate_scan(_scan(), (0.25, 0.25, 0.0))
    assert grid.logodds.tolist() == _Slotted.from_probabilities(
        [[0.2, 0.9]], resolution=0.5
    ).logodds.tolist()


def test_shallow_copy_of_subclass_shares_added_attributes_as_copy_copy_does() -> None:
    grid = _Tagged.empty(width=1.0, height=1.0, resolution=0.5)
    assert isinstance(grid, _Tagged)
    grid.note = []
    shallow, deep = copy.copy(grid), copy.deepcopy(grid)
    assert shallow.note is grid.note
    assert deep.note == grid.note and deep.note is not grid.note
