"""A user's ``_potential``/``_force`` is checked however the class gets it (review 28, LAST2).

``PotentialField.__init_subclass__`` wrapped only a function in the class's own
body, and called it as ``method(self, pts)``: a ``staticmethod`` ``_force(pts)``
(which worked before the check) raised ``TypeError``, and one that came from a
mixin (``class Mine(Mixin, ConicAttraction)``) or was a ``classmethod`` went
unchecked, so a NaN force made ``PotentialFieldController`` stop without a word,
the silent stop the check was written against. The slow path's "caller's own
copy" also shared memory with an ndarray subclass the field kept. And a field
that is no dataclass (the docs ask only for a subclass) could not be copied or
pickled: ``reduce_record`` raised "must be called with a dataclass type or
instance", naming nothing.

The fix is proposed in LAST2's report (the source file is claimed by EXTEND):
until it lands these tests are strict xfails.
"""

from __future__ import annotations

import copy
import pickle
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.control import PotentialFieldController
from navkit.planning import ConicAttraction, PotentialField

F64 = NDArray[np.float64]

class Calm(PotentialField):
    """Zero everywhere, through staticmethods (no ``self``)."""

    __slots__ = ()

    @staticmethod
    def _potential(pts: F64) -> F64:
        return np.zeros(len(pts))

    @staticmethod
    def _force(pts: F64) -> F64:
        return np.zeros((len(pts), 2))


class NanForce:
    """A mixin whose force is NaN (a user's bug)."""

    def _force(self, pts: F64) -> F64:
        return np.full((len(pts), 2), np.nan)


@dataclass(frozen=True, slots=True, eq=False)
class MixedIn(NanForce, ConicAttraction):
    """ConicAttraction whose force comes from the mixin (first in the MRO)."""


class NanClassForce(PotentialField):
    """NaN through classmethods."""

    __slots__ = ()

    @classmethod
    def _potential(cls, pts: F64) -> F64:
        return np.full(len(pts), np.nan)

    @classmethod
    def _force(cls, pts: F64) -> F64:
        return np.full((len(pts), 2), np.nan)


class Kept(np.ndarray):  # type: ignore[type-arg]
    """An ndarray subclass: the slow path of the check."""


_KEPT = np.zeros((1, 2)).view(Kept)


class Keeper(PotentialField):
    """Returns the one (subclass) array it keeps."""

    __slots__ = ()

    def _potential(self, pts: F64) -> F64:
        return np.zeros(len(pts))

    def _force(self, pts: F64) -> Any:
        return _KEPT


def test_a_staticmethod_force_is_called_without_self() -> None:
    # Before the check this returned zeros; the wrapper passed self as the points.
    assert Calm().force([[1.0, 2.0], [3.0, 4.0]]).tolist() == [[0.0, 0.0], [0.0, 0.0]]
    assert Calm().potential([1.0, 2.0]).tolist() == [0.0]


def test_a_mixins_nan_force_is_refused_not_a_silent_stop() -> None:
    with pytest.raises(ValueError, match=r"MixedIn\._force\(points\)"):
        MixedIn((1.0, 0.0)).force([0.0, 0.0])
    controller = PotentialFieldController(attraction=MixedIn((1.0, 0.0)))
    # Unchecked, the NaN became a zero command: the robot stood still 1 m from its goal.
    with pytest.raises(ValueError, match=r"MixedIn\._force\(points\)"):
        controller.desired_velocity([0.0, 0.0, 0.0], (1.0, 0.0))


def test_a_classmethods_nan_output_is_refused() -> None:
    with pytest.raises(ValueError, match=r"NanClassForce\._force\(points\)"):
        NanClassForce().force([0.0, 0.0])
    with pytest.raises(ValueError, match=r"NanClassForce\._potential\(points\)"):
        NanClassForce().potential([0.0, 0.0])


def test_an_ndarray_subclass_output_is_copied() -> None:
    got = Keeper().force([0.0, 0.0])
    assert type(got) is np.ndarray
    assert not np.shares_memory(got, _KEPT)


def test_a_navkit_field_mixed_in_last_keeps_its_own_force() -> None:
    # ConicAttraction first in the MRO: its force wins, the mixin's is never called.
    @dataclass(frozen=True, slots=True, eq=False)
    class Last(ConicAttraction, NanForce):
        pass

    assert Last((1.0, 0.0)).force([0.0, 0.0]).tolist() == [[1.0, 0.0]]


class Slope(PotentialField):
    """A user's field that is no dataclass: a plain class with a slot."""

    __slots__ = ("k",)

    def __init__(self, k: float) -> None:
        self.k = k

    def _potential(self, pts: F64) -> F64:
        return self.k * pts[:, 0]

    def _force(self, pts: F64) -> F64:
        return np.tile([-self.k, 0.0], (len(pts), 1))


class SlopeWithDict(PotentialField):
    """The same with an instance ``__dict__``."""

    def __init__(self, k: float) -> None:
        self.k = k

    def _potential(self, pts: F64) -> F64:
        return self.k * pts[:, 0]

    def _force(self, pts: F64) -> F64:
        return np.tile([-self.k, 0.0], (len(pts), 1))


@pytest.mark.parametrize("kind", [Slope, SlopeWithDict])
@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_a_field_that_is_no_dataclass_pickles_and_copies(kind: type[Any], protocol: int) -> None:
    field = kind(2.5)
    for twin in (
        pickle.loads(pickle.dumps(field, protocol=protocol)),
        copy.copy(field),
        copy.deepcopy(field),
    ):
        assert type(twin) is kind
        assert twin.k == 2.5
        assert twin.force([1.0, 1.0]).tolist() == [[-2.5, 0.0]]
