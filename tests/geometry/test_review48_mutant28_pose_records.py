"""``==`` and ``!=`` of poses and twists look at every field, each alone.

Review 48 (mutation testing, MUTANT28). ``Pose2D.__ne__`` (written out beside
``__eq__`` for object arrays, review 35) read without its ``y`` comparison
passed every test: ``Pose2D(0, 0) != Pose2D(0, 1)`` was False. Each field is
changed alone here, and ``!=`` must be ``not ==``. ``Twist2D`` checking ``vy``
under the name ``vx`` passed too: each field's error is checked to name it;
so did ``f"{record}"`` ignoring a subclass's ``__str__``, and ``as_pose``
refusing a foreign array (an object with ``__array__`` only).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D, as_pose, as_twist, integrate

RECORDS = [Pose2D(1.0, -2.0, 0.5), Twist2D(0.25, -0.5, 0.125)]


@pytest.mark.parametrize("record", RECORDS, ids=lambda r: type(r).__name__)
@pytest.mark.parametrize("index", [0, 1, 2])
def test_each_field_alone_makes_records_unequal(record: Pose2D | Twist2D, index: int) -> None:
    name = dataclasses.fields(record)[index].name
    other = dataclasses.replace(record, **{name: getattr(record, name) + 0.25})
    assert (record == other) is False and (other == record) is False
    assert (record != other) is True and (other != record) is True


@pytest.mark.parametrize("record", RECORDS, ids=lambda r: type(r).__name__)
def test_equal_records_are_not_unequal(record: Pose2D | Twist2D) -> None:
    same = dataclasses.replace(record)
    assert same is not record
    assert (record == same) is True and (record != same) is False


@pytest.mark.parametrize("kind", [Pose2D, Twist2D], ids=lambda k: k.__name__)
@pytest.mark.parametrize("index", [0, 1, 2])
@pytest.mark.parametrize(("bad", "error"), [(float("nan"), ValueError), ("1.0", TypeError)])
def test_a_bad_field_is_named_first_in_the_error(
    kind: type[Pose2D] | type[Twist2D], index: int, bad: object, error: type[Exception]
) -> None:
    # Twist2D's vy checked under the name "vx" passed every test: only the
    # first and last fields of each record were named by one.
    name = dataclasses.fields(kind)[index].name
    values: list[object] = [0.5, 0.25, 0.125]
    values[index] = bad
    with pytest.raises(error, match=rf"^{name} "):
        kind(*values)  # type: ignore[arg-type]


class _Named(Pose2D):
    """A subclass with its own ``__str__``, as an application may write."""

    def __str__(self) -> str:
        return f"pose at ({self.x}, {self.y})"


class _NamedTwist(Twist2D):
    def __str__(self) -> str:
        return f"moving at {self.vx}"


@pytest.mark.parametrize(
    "record", [_Named(1.0, 2.0, 0.5), _NamedTwist(0.5, 0.0, 0.1)], ids=lambda r: type(r).__name__
)
def test_an_empty_format_spec_gives_str_also_of_a_subclass(record: Pose2D | Twist2D) -> None:
    # As object.__format__: f"{record}" is str(record). The fields formatted one
    # by one with the empty spec spell the dataclass repr, not a subclass's own
    # __str__ (that branch dropped passed every test).
    assert f"{record}" == format(record, "") == str(record)
    assert f"{record:.1f}".startswith(type(record).__qualname__ + "(")


class _Foreign:
    """A foreign array (a tensor, a message buffer): no sequence, only ``__array__``."""

    def __init__(self, *values: float) -> None:
        self._values = values

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        return np.array(self._values, dtype=np.float64)


def test_a_foreign_array_is_a_pose_and_a_twist() -> None:
    # as_pose's type check let these through by has_array_protocol alone (not
    # sequences, not ndarrays); without it they were refused, passing every test.
    pose = Pose2D(1.0, 2.0, 0.5)
    assert as_pose(_Foreign(1.0, 2.0, 0.5)) == pose
    assert as_twist(_Foreign(0.5, 0.0, 0.1)) == Twist2D(0.5, 0.0, 0.1)
    assert pose.compose(_Foreign(1.0, 0.0, 0.0)) == pose.compose([1.0, 0.0, 0.0])
    assert pose.relative_to(_Foreign(0.0, 0.0, 0.0)) == pose
    assert integrate(_Foreign(0.0, 0.0, 0.0), _Foreign(1.0, 0.0, 0.0), 2.0) == Pose2D(2.0, 0.0)
    with pytest.raises(ValueError, match="pose"):
        as_pose(_Foreign(1.0, 2.0))
