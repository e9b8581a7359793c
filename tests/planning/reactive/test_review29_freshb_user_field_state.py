"""A user's field keeps what its class adds, through with_goal and pickling (review 29, FRESHB).

``AttractiveField.with_goal`` (which :class:`~navkit.control.PotentialFieldController`
calls every step) rebuilt the field from its dataclass fields alone: a subclass
that is no dataclass, holding a parameter of its own (``self.gain`` set in its
``__init__``, or a slot), came back without it, and its ``_force`` raised
``AttributeError`` at the controller's first step. ``copy`` and ``pickle`` kept it
(``reduce_record`` copies a subclass's ``__dict__`` and slots); ``with_goal`` now
does too. And a field that is no dataclass pickled its ``__dict__`` through
``object.__getstate__``, skipping a ``__getstate__`` of its own (one dropping a
lock, say), so its ``__setstate__`` got a state it never wrote; Python pickles
any object through its ``__getstate__``, and so does the field now.
"""

from __future__ import annotations

import copy
import pickle
import threading
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.control import PotentialFieldController
from navkit.planning import ConicAttraction, PotentialField

F64 = NDArray[np.float64]


class Boost(ConicAttraction):
    """A cone scaled by a gain of its own, set in ``__init__`` (no dataclass field)."""

    def __init__(self, goal_xy: Any, gain: float) -> None:
        super().__init__(goal_xy)
        self.gain = gain

    def _force(self, pts: F64) -> F64:
        return ConicAttraction._force(self, pts) * self.gain


class SlotBoost(ConicAttraction):
    """The same with the gain in a slot."""

    __slots__ = ("gain",)

    def __init__(self, goal_xy: Any, gain: float) -> None:
        super().__init__(goal_xy)
        object.__setattr__(self, "gain", gain)

    def _force(self, pts: F64) -> F64:
        return ConicAttraction._force(self, pts) * self.gain


@pytest.mark.parametrize("kind", [Boost, SlotBoost])
def test_with_goal_keeps_a_subclass_parameter(kind: type[Any]) -> None:
    # Before: AttributeError: 'Boost' object has no attribute 'gain'.
    moved = kind((0.0, 0.0), 0.5).with_goal((3.0, 4.0))
    assert type(moved) is kind and moved.gain == 0.5
    np.testing.assert_array_equal(moved.goal_xy, [3.0, 4.0])
    np.testing.assert_allclose(moved.force([0.0, 0.0]), [[0.3, 0.4]], rtol=0, atol=1e-15)


@pytest.mark.parametrize("kind", [Boost, SlotBoost])
def test_the_controller_drives_a_subclass_with_a_parameter(kind: type[Any]) -> None:
    ctl = PotentialFieldController(max_speed=1.0, attraction=kind((0.0, 0.0), 0.5))
    # The unit cone's pull scaled by 0.5 (below max_speed: not clipped).
    np.testing.assert_allclose(
        ctl.desired_velocity([0.0, 0.0, 0.0], (2.0, 0.0)), [0.5, 0.0], rtol=0, atol=1e-15
    )


def test_with_goal_leaves_the_original_alone() -> None:
    field = Boost((1.0, 1.0), 2.0)
    moved = field.with_goal((5.0, 5.0))
    moved.gain = 3.0  # the copy's own __dict__, not the original's
    assert field.gain == 2.0
    np.testing.assert_array_equal(field.goal_xy, [1.0, 1.0])


class Locked(PotentialField):
    """A field holding a lock, dropped from its pickled state by its own __getstate__."""

    def __init__(self, k: float) -> None:
        self.k = k
        self.lock = threading.Lock()

    def __getstate__(self) -> dict[str, Any]:
        return {"k": self.k}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.k = state["k"]
        self.lock = threading.Lock()

    def _potential(self, pts: F64) -> F64:
        return self.k * pts[:, 0]

    def _force(self, pts: F64) -> F64:
        return np.tile([-self.k, 0.0], (len(pts), 1))


@pytest.mark.parametrize("protocol", [2, pickle.HIGHEST_PROTOCOL])
def test_a_field_that_is_no_dataclass_pickles_through_its_getstate(protocol: int) -> None:
    # Before: TypeError: cannot pickle '_thread.lock' object (its __getstate__ skipped).
    field = Locked(2.0)
    for twin in (pickle.loads(pickle.dumps(field, protocol)), copy.deepcopy(field)):
        assert type(twin) is Locked and twin.k == 2.0 and twin.lock is not field.lock
        np.testing.assert_array_equal(twin.force([1.0, 0.0]), [[-2.0, 0.0]])
