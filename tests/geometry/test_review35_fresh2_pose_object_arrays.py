"""An object array of poses (or twists) compared with a pose, element by element.

Review 34 set ``__array_ufunc__ = None`` on ``Pose2D`` and ``Twist2D`` so that
``row == pose`` is False for a numeric row. It also made NumPy defer the
comparison of an *object* array of poses (``np.array([p, q])``, NumPy's array
of two poses) to the pose, whose dataclass ``__eq__`` answered a plain False:
``p in np.array([p, q])`` was False, ``np.array([p, q]) == p`` was False (not
``[True, False]``), ``np.where(poses == p)`` raised NumPy's "Calling nonzero on
0d arrays", and ``!=`` was True for an array holding the pose. Such an array is
compared element by element again, as before review 34.
"""

from __future__ import annotations

import copy
import operator
import pickle

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D

P = Pose2D(1.0, 2.0, 0.5)
Q = Pose2D(0.0, 0.0, 0.0)
T = Twist2D(1.0, 0.0, 0.25)
U = Twist2D(0.0)


@pytest.mark.parametrize(("a", "b"), [(P, Q), (T, U)])
def test_an_object_array_is_compared_element_by_element(a: object, b: object) -> None:
    held = np.array([a, b, a])
    assert held.dtype == object
    for result in (held == a, a == held):
        assert isinstance(result, np.ndarray) and result.dtype == bool
        np.testing.assert_array_equal(result, [True, False, True])
    for result in (held != a, a != held):
        assert isinstance(result, np.ndarray) and result.dtype == bool
        np.testing.assert_array_equal(result, [False, True, False])
    assert a in held and b in held
    np.testing.assert_array_equal(np.flatnonzero(held == b), [1])
    assert np.count_nonzero(held == a) == 2


def test_an_array_without_the_pose_holds_no_equal_element() -> None:
    held = np.array([Q, Pose2D(1.0, 2.0, 0.25), T, None, 1.0], dtype=object)
    np.testing.assert_array_equal(held == P, [False] * 5)
    assert P not in held
    # A pose equal by value (another instance, or a copy) is found.
    assert Pose2D(1.0, 2.0, 0.5) in np.array([Q, copy.copy(P)])
    assert pickle.loads(pickle.dumps(P)) in np.array([Q, P])


def test_a_zero_d_object_array_and_a_two_d_one() -> None:
    assert bool(np.asarray(P) == P) is True
    assert bool(np.asarray(Q) != P) is True
    grid = np.empty((2, 2), dtype=object)
    grid[0, 0], grid[0, 1], grid[1, 0], grid[1, 1] = P, Q, Q, P
    np.testing.assert_array_equal(grid == P, [[True, False], [False, True]])


def test_numeric_rows_and_other_values_are_still_unequal_scalars() -> None:
    # Review 34's decision stands: a numeric row (or list, scalar) is no pose.
    eq, ne = operator.eq, operator.ne
    for other in (np.array([1.0, 2.0, 0.5]), [1.0, 2.0, 0.5], (1.0, 2.0, 0.5), 1.0, None,
                  np.float64(1.0), np.array([1, 2, 0]), np.array(1.0)):  # fmt: skip
        assert eq(P, other) is False
        assert eq(other, P) is False
        assert ne(P, other) is True
        assert ne(other, P) is True


def test_poses_still_compare_and_hash_by_value() -> None:
    eq, ne = operator.eq, operator.ne
    same = Pose2D(1.0, 2.0, 0.5)
    assert eq(P, same) is True and ne(P, same) is False
    assert eq(P, Q) is False and ne(P, Q) is True
    assert hash(P) == hash(same)
    assert len({P, same, Q}) == 2
    assert eq(T, Twist2D(1.0, 0.0, 0.25)) is True and ne(T, U) is True
    assert hash(T) == hash(Twist2D(1.0, 0.0, 0.25))
    assert eq(Pose2D(0.0, -0.0, 0.0), Q) is True  # -0.0 == 0.0, as the fields compare
    assert eq(P, T) is False and ne(P, T) is True  # a pose is no twist

    class Sub(Pose2D):
        pass

    # As the dataclass's own __eq__: another class is not equal, even a subclass.
    assert eq(Sub(1.0, 2.0, 0.5), P) is False
    assert ne(P, Sub(1.0, 2.0, 0.5)) is True
