"""A potential field a user writes, from the user's side (review 28, extension points).

``PotentialField`` documents subclassing (``_potential`` and ``_force``), and
:class:`~navkit.control.PotentialFieldController` takes a user's
``AttractiveField``. What a user's methods did was passed on unchecked: a field
that wrote to its points changed the caller's array (and what the next field of a
sum saw), a NaN force made the controller stop without a word (its "on an
obstacle" branch turned NaN into 0), and a wrong shape surfaced as a bare NumPy
broadcast or index error.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.control import PotentialFieldController
from navkit.planning import AttractiveField, ConicAttraction

F64 = NDArray[np.float64]


@dataclass(frozen=True, slots=True, eq=False)
class Scribbler(AttractiveField):
    """Writes over its points (a user's in-place shift, say)."""

    def _potential(self, pts: F64) -> F64:
        pts -= self.goal_xy
        return np.hypot(pts[:, 0], pts[:, 1])

    def _force(self, pts: F64) -> F64:
        pts -= self.goal_xy
        return -pts


@dataclass(frozen=True, slots=True, eq=False)
class Flat(AttractiveField):
    """Returns ``value`` everywhere, in the shape ``rows`` x 2 (N when None)."""

    value: float = float("nan")
    rows: int | None = None

    def _potential(self, pts: F64) -> F64:
        return np.full(len(pts) if self.rows is None else self.rows, self.value)

    def _force(self, pts: F64) -> F64:
        return np.full((len(pts) if self.rows is None else self.rows, 2), self.value)


@dataclass(frozen=True, slots=True, eq=False)
class Cached(AttractiveField):
    """Returns the one array it keeps (and may change later)."""

    kept: F64 = field(default_factory=lambda: np.zeros((1, 2)))

    def _potential(self, pts: F64) -> F64:
        return np.zeros(len(pts))

    def _force(self, pts: F64) -> F64:
        return self.kept


@dataclass(frozen=True, slots=True, eq=False)
class PublicForce(AttractiveField):
    """Overrides the public ``force`` itself (so the controller calls it)."""

    def _potential(self, pts: F64) -> F64:
        return np.zeros(len(pts))

    def _force(self, pts: F64) -> F64:
        return np.zeros((len(pts), 2))

    def force(self, points_xy: object) -> F64:
        return np.array([[np.nan, 0.0]])


def test_a_field_cannot_write_to_the_callers_points() -> None:
    pts = np.array([[0.0, 0.0], [1.0, 1.0]])
    before = pts.copy()
    for call in (Scribbler((1.0, 0.0)).force, Scribbler((1.0, 0.0)).potential):
        with pytest.raises(ValueError, match="read-only"):
            call(pts)
        np.testing.assert_array_equal(pts, before)
    # Nor change what a later field of the same sum is given.
    total = Scribbler((1.0, 0.0)) + ConicAttraction((3.0, 0.0))
    with pytest.raises(ValueError, match="read-only"):
        total.force(pts)
    np.testing.assert_array_equal(pts, before)


def test_a_nan_force_is_named_not_turned_into_a_stop() -> None:
    ctl = PotentialFieldController(attraction=Flat((1.0, 0.0)), max_speed=0.5)
    with pytest.raises(ValueError, match=r"Flat\._force\(points\) must contain only finite"):
        ctl.desired_velocity([0.0, 0.0, 0.0], (1.0, 0.0))
    public = PotentialFieldController(attraction=PublicForce((1.0, 0.0)), max_speed=0.5)
    with pytest.raises(ValueError, match=r"PublicForce\.force must contain only finite"):
        public.desired_velocity([0.0, 0.0, 0.0], (1.0, 0.0))


@pytest.mark.parametrize("rows", [0, 3])
def test_a_wrong_shape_is_named_wherever_the_field_is_used(rows: int) -> None:
    flat = Flat((1.0, 0.0), value=1.0, rows=rows)
    pts = np.zeros((2, 2))
    with pytest.raises(ValueError, match=r"Flat\._force\(points\) must have length 2"):
        flat.force(pts)
    with pytest.raises(ValueError, match=r"Flat\._potential\(points\) must have length 2"):
        flat.potential(pts)
    with pytest.raises(ValueError, match=r"Flat\._force\(points\)"):
        (flat + ConicAttraction((0.0, 0.0))).force(pts)
    ctl = PotentialFieldController(attraction=flat, max_speed=0.5)
    with pytest.raises(ValueError, match=r"Flat\._force\(points\) must have length 1"):
        ctl.desired_velocity([0.0, 0.0, 0.0], (1.0, 0.0))


@pytest.mark.parametrize("value", [np.nan, -np.inf])
def test_a_nan_or_minus_inf_potential_is_named(value: float) -> None:
    with pytest.raises(ValueError, match=r"Flat\._potential\(points\) must not return NaN"):
        Flat((1.0, 0.0), value=value).potential([[0.0, 0.0], [1.0, 0.0]])
    # +inf is a potential's obstacle value (KhatibRepulsion's): taken.
    assert Flat((1.0, 0.0), value=np.inf).potential([0.0, 0.0]).tolist() == [np.inf]


def test_the_result_is_the_callers_own_array() -> None:
    cached = Cached((1.0, 0.0))
    out = cached.force([0.0, 0.0])
    cached.kept[0, 0] = 5.0  # the field changes the array it keeps
    assert out.tolist() == [[0.0, 0.0]]


def test_navkits_own_fields_are_not_wrapped() -> None:
    # Their contract is documented and tested: the check costs them nothing.
    assert not hasattr(ConicAttraction._force, "_navkit_checked")
    assert getattr(Flat._force, "_navkit_checked", False)
