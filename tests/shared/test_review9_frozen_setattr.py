"""Frozen slotted records refuse assignment with FrozenInstanceError, never a confusing TypeError.

Python 3.11's ``dataclass(frozen=True, slots=True)`` generates a
``__setattr__``/``__delattr__`` bound to the class it replaced, so any name that
is not a field (on the record or on a user's subclass) raised ``TypeError:
super(type, obj): obj must be an instance or subtype of type``.
``navkit._shared.frozen.frozen_setattr`` restores the frozen-dataclass rules.
"""

from __future__ import annotations

import copy
import importlib
import importlib.util
import pickle
import pkgutil
from dataclasses import FrozenInstanceError, dataclass, fields, is_dataclass
from typing import Any

import pytest

from navkit._shared.frozen import frozen_setattr
from navkit.geometry import Pose2D


def _frozen_records() -> list[type]:
    """Every frozen dataclass navkit defines (plotting included when matplotlib is there)."""
    import navkit

    found: dict[str, type] = {}
    for info in pkgutil.walk_packages(navkit.__path__, "navkit."):
        if info.name.startswith("navkit.plot") and importlib.util.find_spec("matplotlib") is None:
            continue
        module = importlib.import_module(info.name)
        for value in vars(module).values():
            if (
                isinstance(value, type)
                and value.__module__.startswith("navkit.")
                and is_dataclass(value)
                and value.__dataclass_params__.frozen  # type: ignore[attr-defined]
            ):
                found[f"{value.__module__}.{value.__qualname__}"] = value
    return [found[name] for name in sorted(found)]


RECORDS = _frozen_records()


def test_the_records_are_found() -> None:
    # A discovery that found nothing would let every test below pass vacuously.
    names = {cls.__name__ for cls in RECORDS}
    assert {"Pose2D", "Path2D", "LaserScan", "ScanMatchResult", "UpdateResult"} <= names
    assert len(RECORDS) >= 50


def _blank(cls: type) -> Any:
    # The rules under test do not depend on the field values: no constructor arguments
    # needed. An abstract record (a user's extension point) gets its methods stubbed.
    abstract = getattr(cls, "__abstractmethods__", frozenset())
    if abstract:
        stubs: dict[str, Any] = {name: lambda *args: None for name in abstract}
        cls = type(cls.__name__, (cls,), {"__slots__": (), **stubs})
    return object.__new__(cls)


@pytest.mark.parametrize(
    "record",
    [cls for cls in RECORDS if not getattr(cls, "__abstractmethods__", None)],
    ids=lambda c: c.__name__,
)
def test_record_refuses_every_name(record: type) -> None:
    obj = _blank(record)
    field = fields(record)[0].name
    for name in (field, "not_a_field"):
        with pytest.raises(FrozenInstanceError, match=rf"'{name}'.*{record.__name__} is frozen"):
            setattr(obj, name, 1.0)
        with pytest.raises(FrozenInstanceError, match=rf"'{name}'.*{record.__name__} is frozen"):
            delattr(obj, name)


@pytest.mark.parametrize("record", RECORDS, ids=lambda c: c.__name__)
def test_plain_subclass_refuses_fields_and_keeps_its_own_attributes(record: type) -> None:
    sub = type("Sub", (record,), {})
    obj = _blank(sub)
    for field in fields(record):
        with pytest.raises(FrozenInstanceError, match=rf"field '{field.name}'"):
            setattr(obj, field.name, 1.0)
        with pytest.raises(FrozenInstanceError, match=rf"field '{field.name}'"):
            delattr(obj, field.name)
    # Not a field: the subclass's own __dict__, as for frozen dataclasses without slots.
    obj.note = "kept"
    assert obj.note == "kept"
    del obj.note
    assert not hasattr(obj, "note")


@pytest.mark.parametrize("record", RECORDS, ids=lambda c: c.__name__)
def test_slotted_subclass_gives_attribute_error_for_unknown_names(record: type) -> None:
    sub = type("Slotted", (record,), {"__slots__": ("user_tag",)})
    obj = _blank(sub)
    obj.user_tag = "laser"
    assert obj.user_tag == "laser"
    with pytest.raises(AttributeError) as info:
        obj.other = 1
    assert not isinstance(info.value, TypeError)


class TaggedPose(Pose2D):
    __slots__ = ("frame",)
    frame: str


def test_subclass_of_pose_refuses_fields_and_copies() -> None:
    pose = TaggedPose(1.0, 2.0, 0.5)
    with pytest.raises(FrozenInstanceError, match=r"field 'x'.*Pose2D is frozen"):
        pose.x = 3.0  # type: ignore[misc]
    pose.frame = "base"
    assert pose.frame == "base" and (pose.x, pose.y, pose.theta) == (1.0, 2.0, 0.5)
    for out in (copy.copy(pose), copy.deepcopy(pose), pickle.loads(pickle.dumps(pose))):
        assert type(out) is TaggedPose and out == pose


def test_frozen_dataclass_subclass_keeps_its_own_rules() -> None:
    @frozen_setattr
    @dataclass(frozen=True, slots=True)
    class Base:
        a: float

    @dataclass(frozen=True, slots=True)
    class Child(Base):
        b: float = 0.0

    child = Child(1.0, 2.0)
    for name in ("a", "b"):
        with pytest.raises(FrozenInstanceError):
            setattr(child, name, 3.0)
    assert (child.a, child.b) == (1.0, 2.0)
    with pytest.raises(FrozenInstanceError, match="'z': Base is frozen"):
        Base(1.0).z = 2.0  # type: ignore[attr-defined]
