"""Copies and pickles of subclasses of the reactive records keep what the subclass adds.

The frozen slotted dataclasses (the fields, :class:`SampledField`,
:class:`GreedyStep`) pickled their fields alone (the dataclass decorator's
``__getstate__``), so a subclass came back from ``copy.copy``,
``copy.deepcopy`` and pickle without its own attributes (its ``__dict__``
and slots), and a subclass that is itself a slotted frozen dataclass (to add
a field) came back with writable arrays. Pickles of the old form (a list of
field values) still load.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    GreedyStep,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
    SampledField,
)


# Subclasses at module level so that pickle finds them.
class MyParaboloid(ParaboloidAttraction):
    pass


class MyConic(ConicAttraction):
    pass


class MyBlended(BlendedAttraction):
    pass


class MyPiecewise(PiecewiseAttraction):
    pass


class MyKhatib(KhatibRepulsion):
    pass


class MyPiecewiseRepulsion(PiecewiseRepulsion):
    pass


class MyComposite(CompositeField):
    pass


class MySampled(SampledField):
    pass


class MyStep(GreedyStep):
    pass


class SlottedKhatib(KhatibRepulsion):
    __slots__ = ("__hidden", "tag")


@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class LabelledKhatib(KhatibRepulsion):
    label: str = ""


@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class LabelledConic(ConicAttraction):
    label: str = ""


@dataclass(frozen=True, slots=True, eq=False)
class LabelledSampled(SampledField):
    label: str = ""


BUILDERS: list[tuple[type[Any], Callable[[type[Any]], Any]]] = [
    (MyParaboloid, lambda cls: cls((1.0, 2.0), k_att=2.0, a=0.5)),
    (MyConic, lambda cls: cls((1.0, 2.0), m=0.5, threshold_radius=0.2)),
    (MyBlended, lambda cls: cls((1.0, 2.0), width=0.3)),
    (MyPiecewise, lambda cls: cls((1.0, 2.0), goal_radius=0.1)),
    (MyKhatib, lambda cls: cls([[0.0, 0.0], [1.0, 1.0]], influence_radius=2.0)),
    (MyPiecewiseRepulsion, lambda cls: cls([[0.0, 0.0]], obstacle_radius=0.2)),
    (MyComposite, lambda cls: cls((ConicAttraction((1.0, 0.0)), KhatibRepulsion([[0.5, 0.5]])))),
    (
        MySampled,
        lambda cls: cls([0.5, 1.5], [0.5], [[1.0, 2.0]], np.ones((1, 2, 2)), resolution=1.0),
    ),
    (MyStep, lambda cls: cls((10, 12), (0.2, 0.0), g=0.2, h=1.8, candidates=440)),
]

COPIES: list[tuple[str, Callable[[Any], Any]]] = [
    ("copy", copy.copy),
    ("deepcopy", copy.deepcopy),
    ("pickle", lambda obj: pickle.loads(pickle.dumps(obj))),
]

POINTS = [[0.3, 0.4], [2.0, 2.0], [1.0, 2.0]]


def _arrays(obj: Any) -> dict[str, np.ndarray]:
    names = [n for n in dir(obj) if not n.startswith("__")]
    found = {}
    for name in names:
        value = getattr(obj, name, None)
        if isinstance(value, np.ndarray):
            found[name] = value
    return found


@pytest.mark.parametrize(("cls", "build"), BUILDERS, ids=lambda v: getattr(v, "__name__", ""))
@pytest.mark.parametrize(("how", "clone"), COPIES, ids=[c[0] for c in COPIES])
def test_a_subclass_copies_whole(
    cls: type[Any], build: Callable[[type[Any]], Any], how: str, clone: Callable[[Any], Any]
) -> None:
    original = build(cls)
    object.__setattr__(original, "note", ["kept"])
    out = clone(original)
    assert type(out) is cls
    assert out.note == ["kept"]
    if how != "copy":
        assert out.note is not original.note
    for name, array in _arrays(original).items():
        copied = getattr(out, name)
        assert np.array_equal(copied, array)
        assert copied.flags.writeable == array.flags.writeable
    if isinstance(original, PotentialField):
        assert np.array_equal(out.force(POINTS), original.force(POINTS))
        assert np.array_equal(out.potential(POINTS), original.potential(POINTS))


@pytest.mark.parametrize(("how", "clone"), COPIES, ids=[c[0] for c in COPIES])
def test_a_subclass_keeps_its_own_slots(how: str, clone: Callable[[Any], Any]) -> None:
    original = SlottedKhatib([[0.0, 0.0]], k_rep=2.0)
    object.__setattr__(original, "tag", "left wall")
    object.__setattr__(original, "_SlottedKhatib__hidden", 7)
    out = clone(original)
    assert type(out) is SlottedKhatib
    assert out.tag == "left wall"
    assert out._SlottedKhatib__hidden == 7
    assert not out.obstacles_xy.flags.writeable
    assert np.array_equal(out.force(POINTS), original.force(POINTS))


@pytest.mark.parametrize(("how", "clone"), COPIES, ids=[c[0] for c in COPIES])
@pytest.mark.parametrize(
    "build",
    [
        lambda: LabelledKhatib([[0.0, 0.0], [1.0, 0.5]], k_rep=2.0, label="walls"),
        lambda: LabelledConic((1.0, 2.0), m=0.5, label="walls"),
        lambda: LabelledSampled(
            [0.5, 1.5], [0.5], [[1.0, 2.0]], np.ones((1, 2, 2)), resolution=1.0, label="walls"
        ),
    ],
    ids=["KhatibRepulsion", "ConicAttraction", "SampledField"],
)
def test_a_dataclass_subclass_keeps_its_field_and_read_only_arrays(
    build: Callable[[], Any], how: str, clone: Callable[[Any], Any]
) -> None:
    original = build()
    out = clone(original)
    assert type(out) is type(original)
    assert out.label == "walls"
    arrays = _arrays(original)
    assert arrays
    for name, array in arrays.items():
        assert not array.flags.writeable
        assert not getattr(out, name).flags.writeable
        assert np.array_equal(getattr(out, name), array)


def test_old_pickles_load_with_read_only_arrays() -> None:
    field = KhatibRepulsion([[0.0, 0.0], [1.0, 0.0]], k_rep=3.0)
    # The former pickle state: the field values as a list, arrays writable copies.
    old = [
        np.array(getattr(field, name)) if name == "obstacles_xy" else getattr(field, name)
        for name in ("obstacles_xy", "_kdtree", "k_rep", "influence_radius")
    ]
    restored = KhatibRepulsion.__new__(KhatibRepulsion)
    restored.__setstate__(old)
    assert not restored.obstacles_xy.flags.writeable
    assert np.array_equal(restored.force(POINTS), field.force(POINTS))


def test_a_copied_subclass_is_independent_of_the_original() -> None:
    original = MyKhatib([[0.0, 0.0]])
    object.__setattr__(original, "note", ["kept"])
    out = copy.deepcopy(original)
    out.note.append("changed")
    assert original.note == ["kept"]
