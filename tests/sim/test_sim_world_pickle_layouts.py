"""Worlds saved before they had ``__getstate__``, and subclasses of World, copy whole."""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from shapely.geometry import LineString, box

from navkit.sim import Circle, MovingObstacle, World

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]
COPY_IDS = ["copy", "deepcopy", "pickle"]


class _DefaultLayout:
    """Pickles as Python's default reduction of a slotted object: (None, slots).

    That is what navkit wrote for a World before World defined ``__getstate__``.
    """

    def __init__(self, obj: object, slots: dict[str, Any]) -> None:
        self._obj = obj
        self._slots = slots

    def __reduce__(self) -> tuple[Any, ...]:
        return object.__new__, (type(self._obj),), (None, self._slots)


def _world() -> World:
    path = np.array([[3.0, 0.0], [5.0, 0.0]])
    ball = MovingObstacle(0.5, path, np.array([0.0, 2.0]), after="loop")
    runner = MovingObstacle.constant_velocity(0.2, start_xy=(0.0, 3.0), velocity_xy=(0.5, 0.0))
    static = [box(-1.0, -3.0, 1.0, -2.0), LineString([(-4.0, -1.0), (-4.0, 1.0)])]
    return World([*static, Circle(np.array([0.0, 5.0]), 0.5)], moving=[ball, runner])


def _answers(world: World) -> list[float]:
    angles = np.linspace(-math.pi, math.pi, 16, endpoint=False)
    out = [float(world.clearance(0.1, (0.0, 0.0, 0.0), t=t)) for t in (0.0, 1.0, 3.3)]
    for t in (0.0, 1.0, 3.3):
        out.extend(world.raycast((0.0, 0.0, 0.0), angles, range_max=20.0, t=t).tolist())
    return out


def test_a_world_pickled_in_the_default_slot_layout_loads() -> None:
    # Loading it raised "AttributeError: 'tuple' object has no attribute 'items'".
    world = _world()
    slots = {name: getattr(world, name) for name in World.__slots__}
    loaded = pickle.loads(pickle.dumps(_DefaultLayout(world, slots)))
    assert isinstance(loaded, World)
    assert _answers(loaded) == _answers(world)
    assert not loaded.segments.flags.writeable


class _LabelledWorld(World):
    """A subclass with an instance dict."""

    label: str


class _TaggedWorld(World):
    """A subclass with a slot of its own."""

    __slots__ = ("tag",)
    tag: int


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_a_subclass_with_attributes_copies_them(make_copy: Callable[[Any], Any]) -> None:
    # Its attributes were dropped: World's state held only World's own slots.
    world = _LabelledWorld([box(-1.0, 2.0, 1.0, 3.0)])
    world.label = "arena"
    twin = make_copy(world)
    assert type(twin) is _LabelledWorld
    assert twin.label == "arena"
    assert twin.clearance(0.1, (0.0, 0.0, 0.0)) == world.clearance(0.1, (0.0, 0.0, 0.0))


@pytest.mark.parametrize("make_copy", COPIES[:2], ids=COPY_IDS[:2])
def test_a_subclass_with_slots_copies_them_and_worlds(make_copy: Callable[[Any], Any]) -> None:
    # Copying raised AttributeError: the state held only the subclass's own slots.
    world = _TaggedWorld([box(-1.0, 2.0, 1.0, 3.0)])
    world.tag = 7
    twin = make_copy(world)
    assert twin.tag == 7
    assert twin.clearance(0.1, (0.0, 0.0, 0.0)) == world.clearance(0.1, (0.0, 0.0, 0.0))
    assert twin._scanners == {}
