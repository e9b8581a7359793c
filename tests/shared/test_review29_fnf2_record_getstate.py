"""A user's ``__getstate__`` on a subclass of a navkit record is honoured (review 29, FNF2).

The records (frozen slotted dataclasses: the potential fields, poses, ...)
copy and pickle through ``reduce_record``, which took their fields, instance
``__dict__`` and slots itself: a ``__getstate__`` that a user's subclass
defines (to drop a lock or a cache) was bypassed, so the subclass failed to
pickle ("cannot pickle '_thread.lock' object") and its ``__setstate__`` was
never called. It is now called, as Python calls it, and its state goes to the
class's ``__setstate__``; read-only arrays of the base's fields stay read-only.
The ``__getstate__`` a slotted frozen dataclass generates is no user's: navkit's
own records reduce exactly as before (so their pickles are byte-identical).
Checked: against ``frozen.py`` before the change the user-state tests fail.
"""

from __future__ import annotations

import copy
import pickle
import threading
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
import pytest

from navkit._shared.frozen import rebuild_record
from navkit.kinematics import DiffDrive
from navkit.planning import (
    CompositeField,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PotentialField,
)
from navkit.sim import Robot

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]


@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class Locked(KhatibRepulsion):
    """A slotted dataclass subclass with a lock, dropped from its state and made anew."""

    lock: Any = field(default_factory=threading.Lock)

    def __getstate__(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "lock"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "lock", threading.Lock())


class Cached(ConicAttraction):
    """No dataclass: an instance ``__dict__`` with a cache that the state leaves out."""

    def __getstate__(self) -> tuple[dict[str, Any], dict[str, Any]]:
        kept = {k: v for k, v in self.__dict__.items() if k != "cache"}
        return kept, {f.name: getattr(self, f.name) for f in fields(self)}

    def __setstate__(self, state: tuple[dict[str, Any], dict[str, Any]]) -> None:
        instance, slots = state
        self.__dict__.update(instance, cache="rebuilt")
        for name, value in slots.items():
            object.__setattr__(self, name, value)


@pytest.mark.parametrize("make_copy", COPIES)
def test_a_slotted_dataclass_subclass_pickles_through_its_own_getstate(
    make_copy: Callable[[Any], Any],
) -> None:
    field_ = Locked([[0.5, 0.5], [1.0, 2.0]], influence_radius=0.5)
    twin = make_copy(field_)
    assert type(twin) is Locked
    assert twin.lock is not field_.lock and not twin.lock.locked()
    np.testing.assert_array_equal(twin.obstacles_xy, field_.obstacles_xy)
    assert not twin.obstacles_xy.flags.writeable  # the base's array stays read-only
    pts = [[0.2, 0.1], [0.9, 1.7]]
    np.testing.assert_array_equal(twin.force(pts), field_.force(pts))


@pytest.mark.parametrize("make_copy", COPIES)
def test_a_subclass_with_a_dict_pickles_through_its_own_getstate(
    make_copy: Callable[[Any], Any],
) -> None:
    field_ = Cached((1.0, 2.0))
    field_.tag = "goal"  # type: ignore[attr-defined]
    field_.cache = threading.Lock()  # type: ignore[attr-defined]
    twin = make_copy(field_)
    assert type(twin) is Cached
    assert (twin.tag, twin.cache) == ("goal", "rebuilt")  # type: ignore[attr-defined]
    np.testing.assert_array_equal(twin.force([0.0, 0.0]), field_.force([0.0, 0.0]))


def test_the_getstate_of_a_subclass_is_called_once_and_the_original_unchanged() -> None:
    calls: list[int] = []

    @dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
    class Counted(ConicAttraction):
        def __getstate__(self) -> dict[str, Any]:
            calls.append(1)
            return {f.name: getattr(self, f.name) for f in fields(self)}

        def __setstate__(self, state: dict[str, Any]) -> None:
            for name, value in state.items():
                object.__setattr__(self, name, value)

    field_ = Counted(goal_xy=(1.0, 2.0))
    goal = field_.goal_xy
    twin = copy.deepcopy(field_)
    assert calls == [1] and field_.goal_xy is goal and not goal.flags.writeable
    assert twin.goal_xy is not goal and not twin.goal_xy.flags.writeable


NAVKIT_RECORDS: list[Any] = [
    Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15),
    ConicAttraction((1.0, 2.0)),
    ParaboloidAttraction((0.5, 0.5)),
    KhatibRepulsion([[0.5, 0.5], [1.0, 2.0]], influence_radius=0.5),
    CompositeField([ConicAttraction((1.0, 0.0))]),
]


@pytest.mark.parametrize("record", NAVKIT_RECORDS, ids=lambda r: type(r).__name__)
def test_navkit_records_reduce_as_before(record: Any) -> None:
    # Their __getstate__ is the one the dataclass decorator generates: not a user's.
    # The reduce value is the one of before the review, so pickles are byte-identical.
    values = {f.name: getattr(record, f.name) for f in fields(record)}
    func, args = record.__reduce__()
    assert func is rebuild_record
    assert args[0] is type(record) and args[3:] == (None, {})
    assert args[1].keys() == values.keys()
    assert all(args[1][k] is v for k, v in values.items())


def test_a_plain_dataclass_subclass_without_getstate_reduces_as_before() -> None:
    @dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
    class Tagged(ConicAttraction):
        tag: str = ""

    func, args = Tagged(goal_xy=(1.0, 2.0), tag="a").__reduce__()
    assert func is rebuild_record and args[1]["tag"] == "a"
    assert isinstance(Tagged(goal_xy=(0.0, 0.0)), PotentialField)
