"""``row + pose`` and friends: a TypeError that says what to write (review 36).

``Pose2D`` and ``Twist2D`` set ``__array_ufunc__ = None`` (review 34), so NumPy
leaves ``row + pose`` to the pose; with no ``__radd__`` Python fell back to the
array's sequence concatenation and raised NumPy's "Concatenation operation is
not implemented for NumPy arrays, use np.concatenate() instead", and
``pose + row`` raised "operand 'Pose2D' does not support ufuncs". An array, a
list, a tuple or a record added to a pose or a twist (an offset, meant as
one) now gets Python's "unsupported operand type(s) for +" with a hint; other
operands are left to Python (and to their own ``__radd__``) as before.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D

POSE = Pose2D(1.0, 2.0, 0.5)
TWIST = Twist2D(0.4, 0.1, 0.3)
ROW = np.array([0.5, -1.0, 1.0])

POSE_HINT = "a Pose2D is a transform, not a vector: pose @ Pose2D(dx, dy, dtheta)"
TWIST_HINT = "a Twist2D has no arithmetic: Twist2D.from_array(twist.as_array()"


def _add(left: Any, right: Any) -> Any:
    return left + right


@pytest.mark.parametrize(
    ("left", "right", "names", "hint"),
    [
        (ROW, POSE, ("numpy.ndarray", "Pose2D"), POSE_HINT),
        (POSE, ROW, ("Pose2D", "numpy.ndarray"), POSE_HINT),
        ([0.5, -1.0, 1.0], POSE, ("list", "Pose2D"), POSE_HINT),
        (POSE, (0.5, -1.0, 1.0), ("Pose2D", "tuple"), POSE_HINT),
        (POSE, POSE, ("Pose2D", "Pose2D"), POSE_HINT),
        (ROW, TWIST, ("numpy.ndarray", "Twist2D"), TWIST_HINT),
        (TWIST, ROW, ("Twist2D", "numpy.ndarray"), TWIST_HINT),
        (TWIST, TWIST, ("Twist2D", "Twist2D"), TWIST_HINT),
        (np.array([POSE, POSE], dtype=object), POSE, ("numpy.ndarray", "Pose2D"), POSE_HINT),
    ],
    ids=[
        "row+pose",
        "pose+row",
        "list+pose",
        "pose+tuple",
        "pose+pose",
        "row+twist",
        "twist+row",
        "twist+twist",
        "poses+pose",
    ],
)
def test_adding_an_offset_says_what_to_write(
    left: Any, right: Any, names: tuple[str, str], hint: str
) -> None:
    expected = f"unsupported operand type(s) for +: '{names[0]}' and '{names[1]}' ({hint}"
    with pytest.raises(TypeError, match=re.escape(expected)) as info:
        _add(left, right)
    assert "Concatenation" not in str(info.value)
    assert "ufunc" not in str(info.value)


def test_the_hints_do_what_they_say() -> None:
    dx, dy, dtheta = 0.5, -1.0, 1.0
    moved = POSE @ Pose2D(dx, dy, dtheta)  # by (dx, dy) in the pose's own frame
    c, s = math.cos(POSE.theta), math.sin(POSE.theta)
    assert moved.x == pytest.approx(POSE.x + c * dx - s * dy, abs=1e-15)
    assert moved.y == pytest.approx(POSE.y + s * dx + c * dy, abs=1e-15)
    assert moved.theta == pytest.approx(POSE.theta + dtheta, abs=1e-15)
    shifted = Pose2D.from_array(POSE.as_array() + np.array([dx, dy, dtheta]))  # in the world frame
    assert shifted == Pose2D(POSE.x + dx, POSE.y + dy, POSE.theta + dtheta)
    faster = Twist2D.from_array(TWIST.as_array() + np.array([0.1, 0.0, 0.0]))
    assert faster == Twist2D(TWIST.vx + 0.1, TWIST.vy, TWIST.omega)


@pytest.mark.parametrize("record", [POSE, TWIST], ids=["pose", "twist"])
def test_other_operands_get_pythons_own_message(record: Any) -> None:
    name = type(record).__name__
    plain = r"^unsupported operand type\(s\) for \+: '\w+' and '\w+'$"
    for left, right in ((1.0, record), (record, 1.0), (None, record)):
        with pytest.raises(TypeError, match=plain):
            _add(left, right)
    with pytest.raises(TypeError, match=plain.replace(r"'\w+' and '\w+'", f"'int' and '{name}'")):
        sum([record])


def test_an_operand_that_knows_the_sum_still_gets_it() -> None:
    class Offset:
        def __radd__(self, other: Any) -> str:
            return f"moved {type(other).__name__}"

        def __add__(self, other: Any) -> str:
            return f"{type(other).__name__} moved"

    assert POSE + Offset() == "moved Pose2D"
    assert Offset() + POSE == "Pose2D moved"
    assert TWIST + Offset() == "moved Twist2D"


def test_a_subclass_is_named_and_hinted_as_its_base() -> None:
    class Waypoint(Pose2D):
        pass

    with pytest.raises(TypeError, match=re.escape("'numpy.ndarray' and 'Waypoint' (" + POSE_HINT)):
        _add(ROW, Waypoint(0.0, 0.0))
