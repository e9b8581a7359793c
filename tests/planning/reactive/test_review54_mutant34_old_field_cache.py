"""Review 54 (MUTANT34): a repulsion pickled with its KD-tree cache, as 98fb796 made one.

Before 0123de4 the point repulsions were plain slotted classes whose
``_kdtree`` slot held the obstacles' KD-tree once a force had been asked for;
their pickles hold ``(None, {"_kdtree": tree, "obstacles": ..., ...})``.
Review 53 loads such a state under today's names and drops the caches (names
with a leading underscore); the tests' old pickles were made before any force
was asked for, so keeping the caches passed them: the tree then stayed in the
record's instance dict, and went into every pickle of it.
"""

from __future__ import annotations

import pickle
from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from navkit.planning import ConicAttraction, KhatibRepulsion

OBSTACLES = np.array([[0.0, 0.0], [1.0, 1.0], [-0.5, 2.0]])
POINTS = np.array([[0.3, 0.4], [1.2, -1.7], [-1.0, 1.5], [2.5, 0.5], [0.9, 1.1]])


def _blank(cls: type[KhatibRepulsion]) -> Any:
    """A record with no field set, as ``copyreg.__newobj__`` makes one."""
    return cls.__new__(cls)


class _SlottedThen:
    """Pickles as a KhatibRepulsion of 98fb796 did after a force was asked for."""

    def __reduce_ex__(self, protocol: Any) -> Any:
        state = {"_kdtree": cKDTree(OBSTACLES), "obstacles": OBSTACLES, "d0": 1.5, "k_rep": 2.0}
        return (_blank, (KhatibRepulsion,), (None, state))


def test_a_repulsion_pickled_with_its_kd_tree_loads_without_it() -> None:
    old = pickle.loads(pickle.dumps(_SlottedThen(), protocol=pickle.HIGHEST_PROTOCOL))
    today = KhatibRepulsion(OBSTACLES, k_rep=2.0, influence_radius=1.5)
    assert isinstance(old, KhatibRepulsion)
    assert old.influence_radius == 1.5 and old.k_rep == 2.0
    np.testing.assert_array_equal(old.obstacles_xy, OBSTACLES)
    np.testing.assert_array_equal(old.force(POINTS), today.force(POINTS))
    np.testing.assert_array_equal(old.potential(POINTS), today.potential(POINTS))
    # Nothing of the old cache is kept: pickled again, it is the field built today.
    assert pickle.dumps(old) == pickle.dumps(today)


class TaggedConic(ConicAttraction):
    """A user's subclass adding a slot: its pickle's state is ``(None, {"tag": ...})``."""

    __slots__ = ("tag",)
    tag: str


def test_a_subclass_adding_a_slot_keeps_its_fields_through_pickle() -> None:
    # Python's state of the added slot has the old slotted pickles' form; given to a
    # record already rebuilt with its fields, it is the subclass's, not an old field's.
    field = TaggedConic((1.0, -2.0), m=1.5, u_trans=0.8, threshold_radius=0.3)
    object.__setattr__(field, "tag", "left goal")
    again = pickle.loads(pickle.dumps(field))
    assert type(again) is TaggedConic and again.tag == "left goal"
    assert (again.m, again.u_trans, again.threshold_radius) == (1.5, 0.8, 0.3)
    assert tuple(again.goal_xy) == (1.0, -2.0)
    np.testing.assert_array_equal(again.force(POINTS), field.force(POINTS))
