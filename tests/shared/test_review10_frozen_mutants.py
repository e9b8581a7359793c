"""frozen_setattr's replacement methods, beyond what earlier tests pinned (mutation testing).

On a subclass, names that are not the record's fields are set and deleted "as for
frozen dataclasses without slots": the generated methods there hand them on with
``super(cls, self)``, so a class later in the subclass's MRO (a mixin with its own
``__setattr__``/``__delattr__``) sees them. The reference is the standard library's
own frozen dataclass without slots. The methods are also named after the class.
"""

from __future__ import annotations

from dataclasses import FrozenInstanceError, dataclass
from typing import Any

import pytest

from navkit._shared.frozen import frozen_setattr


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Slotted:
    x: float


@dataclass(frozen=True)
class Plain:  # the reference: no slots, the dataclass's own methods are right
    x: float


class Recording:
    """A mixin that records the names set and deleted through it."""

    def __setattr__(self, name: str, value: Any) -> None:
        object.__setattr__(self, "seen_" + name, value)
        object.__setattr__(self, name, value)

    def __delattr__(self, name: str) -> None:
        object.__setattr__(self, "gone_" + name, True)
        object.__delattr__(self, name)


class SlottedTagged(Slotted, Recording):
    pass


class PlainTagged(Plain, Recording):
    pass


@pytest.mark.parametrize("cls", [PlainTagged, SlottedTagged])
def test_a_subclass_hands_other_names_on_along_its_mro(cls: type[Any]) -> None:
    obj = cls(1.0)
    obj.note = "kept"
    assert obj.note == "kept"
    assert obj.seen_note == "kept"  # the mixin's __setattr__ ran
    del obj.note
    assert obj.gone_note is True  # the mixin's __delattr__ ran
    assert not hasattr(obj, "note")
    with pytest.raises(FrozenInstanceError):
        obj.x = 2.0


def test_the_methods_are_named_after_the_record() -> None:
    for name in ("__setattr__", "__delattr__"):
        method = getattr(Slotted, name)
        assert method.__qualname__ == f"{Slotted.__qualname__}.{name}"
        assert method.__module__ == Slotted.__module__
