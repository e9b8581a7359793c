"""A record subclass whose attributes refer back to it copies and pickles whole (review 31).

``reduce_record`` (the ``__reduce__`` of navkit's frozen records) put what a
subclass adds, its ``__dict__`` and slots, among the arguments of the
rebuild. Arguments are pickled (and deep-copied) before the object exists,
so an attribute that leads back to the record (a parent link, a graph edge,
a bound method of the record kept as a callback) reached the record again
while its state was still being read:

- ``pickle.loads(pickle.dumps(sub))`` (every protocol) gave a record whose
  ``__dict__`` was empty: every attribute of the subclass lost, silently;
- ``copy.deepcopy(sub)`` gave two records, the copy's ``me`` another record
  without any attributes;
- a subclass's slot referring back (``__slots__``) recursed without end
  (``RecursionError``) in both.

What a subclass adds now comes after the rebuild, as Python restores any
object's state: the attribute finds the new record. Navkit's records whose own
``__setstate__`` reads a list of field values (older pickles) read this state
too; a class whose ``__setstate__`` is the one a slotted dataclass generates
(a user's slotted dataclass subclass) keeps the old layout.

Checked: against ``frozen.py`` before the change every pickle and deepcopy
case fails (``AttributeError: ... has no attribute 'me'``, or ``is`` false);
the shallow-copy and older-pickle cases pass before and after.
"""

from __future__ import annotations

import copy
import importlib
import inspect
import pickle
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

import navkit
from navkit._shared.frozen import _restores_extra, rebuild_record
from navkit.estimation import UpdateResult
from navkit.geometry import Pose2D, Twist2D
from navkit.mapping import LaserScan
from navkit.planning import Path2D
from navkit.sim import Circle, MovingObstacle


class CyclicPose(Pose2D):
    def on_event(self) -> float:
        return self.x


class CyclicTwist(Twist2D):
    pass


class CyclicScan(LaserScan):
    pass


class CyclicResult(UpdateResult):
    pass


class CyclicPath(Path2D):
    pass


class CyclicCircle(Circle):
    pass


class CyclicObstacle(MovingObstacle):
    pass


class SlottedPose(Pose2D):
    __slots__ = ("note", "peer")


MAKERS: dict[str, Callable[[], Any]] = {
    "Pose2D": lambda: CyclicPose(1.0, 2.0, 0.5),
    "Twist2D": lambda: CyclicTwist(0.1, 0.0, 0.2),
    "LaserScan": lambda: CyclicScan(
        np.array([1.0, 2.0]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
    ),
    "UpdateResult": lambda: CyclicResult(True, 0.5, np.array([0.1, -0.2])),
    "Path2D": lambda: CyclicPath(np.zeros((2, 2)), "world", 1.0, 1.0, 3),
    "Circle": lambda: CyclicCircle(np.array([1.0, 2.0]), 0.5),
    "MovingObstacle": lambda: CyclicObstacle(
        0.2, np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([0.0, 1.0])
    ),
}

ROUND_TRIPS: dict[str, Callable[[Any], Any]] = {
    **{
        f"pickle{protocol}": (lambda obj, p=protocol: pickle.loads(pickle.dumps(obj, p)))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    },
    "deepcopy": copy.deepcopy,
}


def _read_only_arrays(obj: Any) -> list[str]:
    return [
        name
        for name in getattr(type(obj), "__dataclass_fields__", {})
        if isinstance(getattr(obj, name), np.ndarray) and not getattr(obj, name).flags.writeable
    ]


@pytest.mark.parametrize("how", sorted(ROUND_TRIPS))
@pytest.mark.parametrize("kind", sorted(MAKERS))
def test_attributes_that_refer_back_survive(kind: str, how: str) -> None:
    original = MAKERS[kind]()
    original.me = original
    original.family = [original, {"note": 5}]
    frozen = _read_only_arrays(original)
    got = ROUND_TRIPS[how](original)
    assert type(got) is type(original)
    assert got.me is got
    assert got.family[0] is got and got.family[1] == {"note": 5}
    assert got is not original and got.family is not original.family
    assert repr(got) == repr(original)
    assert _read_only_arrays(got) == frozen


@pytest.mark.parametrize("how", sorted(ROUND_TRIPS))
def test_a_bound_method_of_the_record_kept_as_a_callback(how: str) -> None:
    original = CyclicPose(3.0, 0.0)
    original.callback = original.on_event
    got = ROUND_TRIPS[how](original)
    assert got.callback.__self__ is got and got.callback() == 3.0


@pytest.mark.parametrize("how", sorted(ROUND_TRIPS))
def test_slots_that_refer_back_survive(how: str) -> None:
    original = SlottedPose(1.0, 2.0)
    object.__setattr__(original, "peer", original)
    object.__setattr__(original, "note", "kept")
    got = ROUND_TRIPS[how](original)
    assert type(got) is SlottedPose and got.peer is got and got.note == "kept"


def test_a_shallow_copy_shares_the_attributes_not_the_dict() -> None:
    original = CyclicPose(1.0, 2.0)
    original.me = original
    original.items = [1]
    got = copy.copy(original)
    assert got.me is original and got.items is original.items
    got.extra = 1
    assert not hasattr(original, "extra")


def test_an_older_pickle_layout_still_loads() -> None:
    # What reduce_record wrote before: the subclass's __dict__ among the arguments.
    values = {
        "ranges": np.array([1.0]), "angle_min": 0.0, "angle_increment": 0.1,
        "range_min": 0.1, "range_max": 5.0, "intensities": None,
    }  # fmt: skip
    got = rebuild_record(CyclicScan, values, ("ranges",), {"tag": "old"}, {})
    assert type(got) is CyclicScan and got.tag == "old"
    assert not got.ranges.flags.writeable


def _records_reduced_by_reduce_record() -> list[type]:
    found: dict[str, type] = {}
    for info in pkgutil.walk_packages(navkit.__path__, "navkit."):
        module = importlib.import_module(info.name)
        for obj in vars(module).values():
            if not inspect.isclass(obj) or not obj.__module__.startswith("navkit."):
                continue
            if inspect.isabstract(obj):  # no instances, only subclasses (listed)
                continue
            # Its own __reduce__ or the one it inherits (the potential fields').
            owner = next(k for k in obj.__mro__ if "__reduce__" in k.__dict__)
            reduce = owner.__dict__["__reduce__"]
            if inspect.isfunction(reduce) and "reduce_record(" in inspect.getsource(reduce):
                found[f"{obj.__module__}.{obj.__qualname__}"] = obj
    return [found[name] for name in sorted(found)]


RECORDS = _records_reduced_by_reduce_record()


def test_the_records_are_found() -> None:
    names = {cls.__name__ for cls in RECORDS}
    assert {"Pose2D", "Twist2D", "LaserScan", "UpdateResult", "Trace", "BagScans"} <= names
    assert len(RECORDS) >= 30


@pytest.mark.parametrize("record", RECORDS, ids=lambda cls: cls.__qualname__)
def test_every_navkit_setstate_reads_what_a_subclass_adds(record: type) -> None:
    # Each record class (and every subclass of one) whose __setstate__ is navkit's
    # gets (instance __dict__, {slot: value}) after the rebuild: it must set those
    # and touch no field (the rebuild set them).
    # Otherwise the rebuild takes what a subclass adds, and loses what refers back.
    assert _restores_extra(record), f"{record.__qualname__} needs a __setstate__ of navkit's"
    sub = type(f"Sub{record.__name__}", (record,), {})
    obj = object.__new__(sub)
    obj.__setstate__(({"tag": "kept"}, {}))
    assert obj.__dict__ == {"tag": "kept"}
    assert not any(hasattr(obj, field) for field in record.__dataclass_fields__)


@dataclass(frozen=True, slots=True)
class TaggedPose(Pose2D):
    """A user's slotted dataclass subclass: its generated __setstate__ reads fields."""

    tag: str = ""


class OpenTaggedPose(TaggedPose):
    pass


@pytest.mark.parametrize("how", [*sorted(ROUND_TRIPS), "copy"])
def test_a_subclass_whose_setstate_is_the_dataclass_s_keeps_the_old_layout(how: str) -> None:
    original = OpenTaggedPose(1.0, 2.0, 0.5, tag="t")
    object.__setattr__(original, "note", [5])  # its generated __setattr__ fails (3.11)
    got = (copy.copy if how == "copy" else ROUND_TRIPS[how])(original)
    assert type(got) is OpenTaggedPose
    assert (got.x, got.y, got.theta, got.tag) == (1.0, 2.0, 0.5, "t")
    assert got.note == [5]
