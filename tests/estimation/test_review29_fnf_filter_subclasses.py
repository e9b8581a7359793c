"""User subclasses of the filters: what the EKF's docstring promises them (review 29, FNF).

``ExtendedKalmanFilter.__repr__`` and ``PlanarFusion.__repr__`` spelled their own
class name, so a subclass printed as its base: ``ExtendedKalmanFilter(dim=2, ...)``.
They now name ``type(self)``, as the potential fields' repr does (and dataclass
reprs). Checked: against the two reprs before the change (a scratch copy of src)
the repr tests fail. The other tests pin the Notes of ``ExtendedKalmanFilter``:
a subclass with slots and an instance dict copies and pickles (every protocol)
as itself, with what it adds, steps as the base does, bit for bit, and an
override of a public method changes only its own callers.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion

F = np.array([[1.0, 0.1], [0.0, 1.0]])
Q = 0.01 * np.eye(2)
H = np.array([[1.0, 0.0]])
R = np.array([[0.04]])


class Slotted(ExtendedKalmanFilter):
    """A constant-velocity model of its own: a slot, a method, a counted override."""

    __slots__ = ("predictions", "tag")

    def __init__(self, x0: Any, P0: Any, tag: str) -> None:
        super().__init__(x0, P0, angle_states=(0,))
        self.tag = tag
        self.predictions = 0

    def step(self, dt: float) -> None:
        jac = np.array([[1.0, dt], [0.0, 1.0]])
        self.predict(lambda x: jac @ x, jac, Q)

    def predict(self, f: Any, F: Any, Q: Any) -> None:
        self.predictions += 1
        super().predict(f, F, Q)


class WithDict(Slotted):
    """No slots of its own: an instance ``__dict__``."""


class Fusion(PlanarFusion):
    __slots__ = ("label",)

    def __init__(self) -> None:
        super().__init__(t0=0.0)
        self.label = "f"


COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]


def test_a_subclass_is_named_by_its_repr() -> None:
    ekf = Slotted([0.0, 1.0], np.eye(2), "a")
    assert repr(ekf) == "Slotted(<2 states>, angle_states=(0,))"
    assert (
        repr(ExtendedKalmanFilter([0.0], [[1.0]]))
        == "ExtendedKalmanFilter(<1 state>, angle_states=())"
    )
    assert repr(Fusion()).startswith("Fusion(t=0.0, x=[")
    assert repr(PlanarFusion(t0=0.0)).startswith("PlanarFusion(t=0.0, x=[")


def _run(ekf: ExtendedKalmanFilter, steps: int) -> None:
    for k in range(steps):
        ekf.predict(lambda x: F @ x, F, Q)
        ekf.update([0.1 * k], lambda x: x[:1], H, R)


@pytest.mark.parametrize("make_copy", COPIES)
@pytest.mark.parametrize("cls", [Slotted, WithDict])
def test_a_subclass_copies_as_itself_and_steps_as_the_base(
    cls: type[Slotted], make_copy: Callable[[Any], Any]
) -> None:
    ekf = cls([0.0, 1.0], np.eye(2), "a")
    if cls is WithDict:
        ekf.note = [1]  # type: ignore[attr-defined]
    base = ExtendedKalmanFilter([0.0, 1.0], np.eye(2), angle_states=(0,))
    _run(ekf, 3)
    _run(base, 3)
    twin = make_copy(ekf)
    assert type(twin) is cls
    assert (twin.tag, twin.predictions) == ("a", 3)
    assert repr(twin) == f"{cls.__name__}(<2 states>, angle_states=(0,))"
    if cls is WithDict:
        assert twin.note == [1]  # type: ignore[attr-defined]
    # The same estimate, and each goes on as the base filter does, bit for bit.
    for other in (ekf, twin):
        np.testing.assert_array_equal(other.x, base.x)
        np.testing.assert_array_equal(other.P, base.P)
    _run(twin, 2)
    _run(base, 2)
    np.testing.assert_array_equal(twin.x, base.x)
    np.testing.assert_array_equal(twin.P, base.P)
    assert ekf.predictions == 3 and twin.predictions == 5  # independent


def test_an_override_changes_only_its_own_callers() -> None:
    # update and the subclass's own step: update calls no public method; step calls
    # the overridden predict, as it should.
    ekf = Slotted([0.0, 1.0], np.eye(2), "a")
    assert ekf.update([0.5], lambda x: x[:1], H, R).accepted
    assert ekf.predictions == 0
    ekf.step(0.1)
    assert ekf.predictions == 1


@pytest.mark.parametrize("make_copy", COPIES)
def test_a_fusion_subclass_copies_as_itself(make_copy: Callable[[Any], Any]) -> None:
    fusion = Fusion()
    fusion.predict(0.5)
    assert fusion.update_speed(0.5, 0.3, variance=0.01).accepted
    twin = make_copy(fusion)
    assert type(twin) is Fusion and twin.label == "f"
    assert repr(twin) == repr(fusion) and repr(twin).startswith("Fusion(t=0.5,")
    np.testing.assert_array_equal(twin.P, fusion.P)
