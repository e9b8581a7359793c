"""A user's ``__getstate__`` without a ``__setstate__`` of its own restores (review 30, FRESH).

Review 29 sent a user subclass's ``__getstate__`` state to "the class's
``__setstate__``": for navkit's records that is navkit's own (the loader of
older pickles, a list of field values, or the one a slotted frozen dataclass
generates), which no user state fits. A subclass that only drops a cache from
Python's default ``(__dict__, {slot: value})`` state failed to copy ("zip()
argument 2 is shorter than argument 1", naming nothing); one returning a dict
of its fields copied *silently wrong*, every field holding its own name
(``goal_xy='goal_xy'``). The state now goes to a ``__setstate__`` of the
user's classes, or, without one, is restored as Python restores a state
without one (slots set past the frozen guard); a state that is no dict then
is refused naming the class (a list of the fields went to navkit's loader of
older pickles, which happens to read that very list). Checked: against
``frozen.py`` before the change every test here but the last fails.
"""

from __future__ import annotations

import copy
import pickle
import threading
from collections.abc import Callable
from dataclasses import fields
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.planning import ConicAttraction

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]


class Cached(ConicAttraction):
    """Python's default state, less a lock: no ``__setstate__`` of its own."""

    def __getstate__(self) -> tuple[dict[str, Any], dict[str, Any]]:
        kept = {k: v for k, v in self.__dict__.items() if k != "lock"}
        return kept, {f.name: getattr(self, f.name) for f in fields(self)}


class Fields(ConicAttraction):
    """A plain dict of the fields (slots): the extra attribute is left out."""

    def __getstate__(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in fields(self)}


class Pose(Pose2D):
    """On a record whose only ``__setstate__`` is the dataclass-generated one."""

    def __getstate__(self) -> tuple[dict[str, Any], dict[str, Any]]:
        kept = {k: v for k, v in self.__dict__.items() if k != "lock"}
        return kept, {f.name: getattr(self, f.name) for f in fields(self)}


@pytest.mark.parametrize("make_copy", COPIES)
def test_default_layout_state_without_setstate(make_copy: Callable[[Any], Any]) -> None:
    field = Cached((1.0, 2.0), m=2.0)
    field.note = "kept"
    field.lock = threading.Lock()
    out = make_copy(field)
    assert type(out) is Cached
    assert out.note == "kept"
    assert not hasattr(out, "lock")
    np.testing.assert_array_equal(out.goal_xy, [1.0, 2.0])
    assert out.m == 2.0
    assert not out.goal_xy.flags.writeable
    np.testing.assert_array_equal(out.force(np.array([3.0, 2.0])), field.force([3.0, 2.0]))


@pytest.mark.parametrize("make_copy", COPIES)
def test_dict_of_fields_state_is_not_read_as_a_list(make_copy: Callable[[Any], Any]) -> None:
    field = Fields((1.0, 2.0), m=2.0)
    field.cache = object()
    out = make_copy(field)
    assert isinstance(out.goal_xy, np.ndarray)
    np.testing.assert_array_equal(out.goal_xy, [1.0, 2.0])
    assert (out.m, out.u_trans, out.threshold_radius) == (
        field.m,
        field.u_trans,
        field.threshold_radius,
    )
    assert not hasattr(out, "cache")


@pytest.mark.parametrize("make_copy", COPIES)
def test_a_pose_subclass_with_getstate_alone(make_copy: Callable[[Any], Any]) -> None:
    pose = Pose(1.0, 2.0, 0.5)
    pose.note = 3
    pose.lock = threading.Lock()
    out = make_copy(pose)
    assert (type(out), out.x, out.y, out.theta, out.note) == (Pose, 1.0, 2.0, 0.5, 3)
    assert not hasattr(out, "lock")


def test_a_state_that_fits_no_restore_is_refused_naming_the_class() -> None:
    class Listed(ConicAttraction):
        def __getstate__(self) -> list[Any]:
            return [getattr(self, f.name) for f in fields(self)]

    with pytest.raises(TypeError, match=r"Listed\.__getstate__.*__setstate__"):
        copy.copy(Listed((1.0, 2.0), m=2.0))


def test_a_users_own_setstate_still_gets_the_state() -> None:
    seen: list[Any] = []

    class Own(ConicAttraction):
        def __getstate__(self) -> str:
            return "token"

        def __setstate__(self, state: Any) -> None:
            seen.append(state)

    copy.copy(Own((1.0, 2.0), m=2.0))
    assert seen == ["token"]
