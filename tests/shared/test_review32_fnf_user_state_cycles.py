"""A user's state of a record subclass copies as Python copies any object (review 32, FNF).

``reduce_record`` put a user's ``__getstate__`` state among the rebuild's
arguments, pickled before the new record existed: a state referring back to
the record (a parent link) recursed until ``RecursionError`` in ``deepcopy``
and ``pickle``. And a user's ``__setstate__`` without a ``__getstate__`` was
never called (the subclass's extras were set directly). Now the state is
pickled after the new record exists, so cycles are kept, and a user's
``__setstate__`` gets Python's default state ``(instance __dict__ or None,
{slot: value})``; the base's arrays stay read-only after it. Checked: against
``frozen.py`` of HEAD the cycle tests raise RecursionError and the
``__setstate__`` tests see no call.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from dataclasses import fields
from typing import Any

import numpy as np
import pytest

from navkit._shared import frozen
from navkit.geometry import Pose2D
from navkit.planning import ConicAttraction

DEEP: list[Callable[[Any], Any]] = [
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]
IDS = ["deepcopy", *(f"pickle{p}" for p in range(pickle.HIGHEST_PROTOCOL + 1))]


class Linked(ConicAttraction):
    """A state holding the record itself (a parent link) and a node pointing back."""

    def __getstate__(self) -> dict[str, Any]:
        state = {f.name: getattr(self, f.name) for f in fields(self)}
        state.update(self.__dict__)
        return state


class Node:
    def __init__(self, owner: Any) -> None:
        self.owner = owner


@pytest.mark.parametrize("duplicate", DEEP, ids=IDS)
def test_a_state_referring_back_keeps_the_cycle(duplicate: Callable[[Any], Any]) -> None:
    field = Linked((1.0, 2.0), m=2.0)
    field.me = field  # type: ignore[attr-defined]
    field.node = Node(field)  # type: ignore[attr-defined]
    twin = duplicate(field)
    assert type(twin) is Linked and twin is not field
    assert twin.me is twin and twin.node.owner is twin  # type: ignore[attr-defined]
    np.testing.assert_array_equal(twin.goal_xy, [1.0, 2.0])
    assert twin.m == 2.0 and not twin.goal_xy.flags.writeable
    np.testing.assert_array_equal(twin.force([3.0, 2.0]), field.force([3.0, 2.0]))
    assert not frozen._shells()  # nothing kept once the copy is made


@pytest.mark.parametrize("duplicate", DEEP, ids=IDS)
def test_two_records_referring_to_each_other(duplicate: Callable[[Any], Any]) -> None:
    a, b = Linked((1.0, 2.0)), Linked((3.0, 4.0))
    a.other, b.other = b, a  # type: ignore[attr-defined]
    a2, b2 = duplicate([a, b])
    assert a2.other is b2 and b2.other is a2
    np.testing.assert_array_equal(b2.goal_xy, [3.0, 4.0])


def test_a_shallow_copy_shares_the_state_as_for_any_object() -> None:
    field = Linked((1.0, 2.0))
    node = Node(field)
    field.node = node  # type: ignore[attr-defined]
    twin = copy.copy(field)
    assert twin is not field and twin.node is node  # type: ignore[attr-defined]
    assert not frozen._shells()


class Restored(ConicAttraction):
    """A ``__setstate__`` alone: it gets Python's default state and keeps count."""

    calls = 0

    def __setstate__(  # type: ignore[override]
        self, state: tuple[dict[str, Any] | None, dict[str, Any]]
    ) -> None:
        type(self).calls += 1
        instance, slots = state
        for name, value in slots.items():
            object.__setattr__(self, name, value)
        self.__dict__.update(instance or {}, restored=True)


@pytest.mark.parametrize("duplicate", [copy.copy, *DEEP], ids=["copy", *IDS])
def test_a_users_setstate_alone_is_called(duplicate: Callable[[Any], Any]) -> None:
    field = Restored((1.0, 2.0), m=2.0)
    field.tag = "goal"  # type: ignore[attr-defined]
    field.me = field  # type: ignore[attr-defined]
    before = Restored.calls
    twin = duplicate(field)
    assert Restored.calls == before + 1
    assert (twin.tag, twin.restored, twin.m) == ("goal", True, 2.0)
    assert twin.me is (field if duplicate is copy.copy else twin)
    assert not twin.goal_xy.flags.writeable


class Pose(Pose2D):
    """A ``__setstate__`` alone on a record of slots only (no ``__dict__`` in the state)."""

    __slots__ = ("seen",)

    def __setstate__(self, state: tuple[None, dict[str, Any]]) -> None:
        instance, slots = state
        assert instance is None
        for name, value in slots.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "seen", sorted(slots))


@pytest.mark.parametrize("duplicate", DEEP, ids=IDS)
def test_a_slotted_subclass_setstate_gets_every_slot(duplicate: Callable[[Any], Any]) -> None:
    pose = Pose(1.0, 2.0, 0.5)
    object.__setattr__(pose, "seen", [])
    twin = duplicate(pose)
    assert (twin.x, twin.y, twin.theta) == (1.0, 2.0, 0.5)
    assert twin.seen == sorted(["seen", "theta", "x", "y"])
