"""Pose2D and Twist2D."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, Twist2D

coords = st.floats(-100, 100, allow_nan=False)
angles = st.floats(-10, 10, allow_nan=False)
poses = st.builds(Pose2D, coords, coords, angles)


def close(a: Pose2D, b: Pose2D, tol: float = 1e-9) -> bool:
    return (
        math.isclose(a.x, b.x, abs_tol=tol)
        and math.isclose(a.y, b.y, abs_tol=tol)
        and math.isclose(math.cos(a.theta - b.theta), 1.0, abs_tol=tol)
    )


@settings(deadline=None)  # the first example loads the compiled SE(2) kernels
@given(poses)
def test_inverse_is_identity(p: Pose2D) -> None:
    identity = Pose2D(0.0, 0.0, 0.0)
    assert close(p.compose(p.inverse()), identity)
    assert close(p.inverse().compose(p), identity)


@settings(max_examples=40)
@given(poses, poses, poses)
def test_compose_associative(a: Pose2D, b: Pose2D, c: Pose2D) -> None:
    assert close((a @ b) @ c, a @ (b @ c), tol=1e-7)


test_compose_associative_thoroughly = slow_twin(test_compose_associative, max_examples=100)


@given(poses, poses)
def test_relative_to_roundtrip(a: Pose2D, frame: Pose2D) -> None:
    assert close(frame.compose(a.relative_to(frame)), a, tol=1e-7)


@settings(max_examples=40)
@given(poses, st.lists(st.tuples(coords, coords), min_size=1, max_size=5))
def test_transform_points_matches_compose(p: Pose2D, pts: list[tuple[float, float]]) -> None:
    arr = np.array(pts)
    out = p.transform_points(arr)
    for (x, y), (wx, wy) in zip(pts, out, strict=True):
        q = p.compose(Pose2D(x, y, 0.0))
        assert math.isclose(q.x, wx, abs_tol=1e-9)
        assert math.isclose(q.y, wy, abs_tol=1e-9)


test_transform_points_matches_compose_thoroughly = slow_twin(
    test_transform_points_matches_compose, max_examples=100
)


def test_known_values() -> None:
    p = Pose2D(1.0, 2.0, math.pi / 2)
    np.testing.assert_allclose(p.transform_points([[1.0, 0.0], [0.0, 1.0]]), [[1, 3], [0, 2]])
    assert Pose2D(0, 0, 3 * math.pi).theta == pytest.approx(math.pi)
    assert Pose2D.from_array(p.as_array()) == p
    assert Twist2D.from_array([1.0, 2.0, 3.0]) == Twist2D(1.0, 2.0, 3.0)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="theta"):
        Pose2D(0.0, 0.0, math.nan)
    with pytest.raises(ValueError, match="x"):
        Pose2D(math.inf, 0.0)
    with pytest.raises(TypeError, match="y"):
        Pose2D(0.0, "a")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="omega"):
        Twist2D(0.0, 0.0, math.nan)
    with pytest.raises(ValueError, match="values"):
        Pose2D.from_array([1.0, 2.0])
    with pytest.raises(ValueError, match="points"):
        Pose2D(0, 0).transform_points(np.zeros((3, 3)))


@settings(max_examples=40)
@given(poses, poses)
def test_compose_accepts_a_three_sequence(a: Pose2D, b: Pose2D) -> None:
    as_list = [b.x, b.y, b.theta]
    assert a.compose(as_list) == a.compose(b)
    assert a.compose(tuple(as_list)) == a.compose(b)
    assert a.compose(np.array(as_list)) == a.compose(b)
    assert a @ as_list == a @ b
    assert b.relative_to(as_list) == b.relative_to(b)
    assert a.relative_to([b.x, b.y, b.theta]) == a.relative_to(b)


test_compose_accepts_a_three_sequence_thoroughly = slow_twin(
    test_compose_accepts_a_three_sequence, max_examples=100
)


@pytest.mark.parametrize("bad", [3, 3.0, None, "1 2 3", {"x": 1.0}])
def test_compose_rejects_non_poses_naming_the_argument(bad: object) -> None:
    p = Pose2D(1.0, 2.0, 0.5)
    with pytest.raises(TypeError, match="other must be a Pose2D"):
        p.compose(bad)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="other must be a Pose2D"):
        p @ bad  # type: ignore[operator]
    with pytest.raises(TypeError, match="frame must be a Pose2D"):
        p.relative_to(bad)  # type: ignore[arg-type]


def test_compose_rejects_wrong_length_naming_the_argument() -> None:
    with pytest.raises(ValueError, match="other"):
        Pose2D(0.0, 0.0).compose([1.0, 2.0])
    with pytest.raises(ValueError, match="frame"):
        Pose2D(0.0, 0.0).relative_to([1.0, 2.0, 3.0, 4.0])
    with pytest.raises(ValueError, match="other"):
        Pose2D(0.0, 0.0) @ [1.0, math.nan, 0.0]


def test_equality_is_by_value() -> None:
    assert Pose2D(1.0, 2.0, 0.5) == Pose2D(1.0, 2.0, 0.5)
    assert Pose2D(1.0, 2.0, 0.5) != Pose2D(1.0, 2.0, 0.6)
    assert Pose2D(0.0, 0.0, 3 * math.pi) == Pose2D(0.0, 0.0, math.pi)
    assert Twist2D(1.0, 0.0, 0.5) == Twist2D(1.0, 0.0, 0.5)
    assert Twist2D(1.0) != Twist2D(1.0, 0.1)
    assert hash(Pose2D(1.0, 2.0)) == hash(Pose2D(1.0, 2.0))


def test_frozen() -> None:
    p = Pose2D(0.0, 0.0)
    with pytest.raises(AttributeError):
        p.x = 1.0  # type: ignore[misc]
