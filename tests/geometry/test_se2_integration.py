"""Exact SE(2) integration: integrate and rollout."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, Twist2D, integrate, rollout

speeds = st.floats(-5, 5, allow_nan=False)
rates = st.floats(-5, 5, allow_nan=False)
twists = st.builds(Twist2D, speeds, speeds, rates)
poses = st.builds(Pose2D, st.floats(-50, 50), st.floats(-50, 50), st.floats(-math.pi, math.pi))
dts = st.floats(0.0, 2.0, allow_nan=False)


def assert_pose_close(a: Pose2D, b: Pose2D, tol: float = 1e-9) -> None:
    assert a.x == pytest.approx(b.x, abs=tol)
    assert a.y == pytest.approx(b.y, abs=tol)
    assert math.cos(a.theta - b.theta) == pytest.approx(1.0, abs=tol)


@settings(max_examples=40, deadline=None)
@given(poses, twists, dts)
def test_two_half_steps_equal_one_step(p: Pose2D, t: Twist2D, dt: float) -> None:
    once = integrate(p, t, 2 * dt)
    twice = integrate(integrate(p, t, dt), t, dt)
    assert_pose_close(once, twice, tol=1e-8)


test_two_half_steps_equal_one_step_thoroughly = slow_twin(
    test_two_half_steps_equal_one_step, max_examples=100
)


@settings(max_examples=40, deadline=None)
@given(poses, twists, dts)
def test_matches_fine_euler_integration(p: Pose2D, t: Twist2D, dt: float) -> None:
    n = 20000
    x, y, th = p.x, p.y, p.theta
    h = dt / n
    # Midpoint rule on a fine grid, vectorised over the headings.
    ths = th + t.omega * h * (np.arange(n) + 0.5)
    c, s = np.cos(ths), np.sin(ths)
    x += h * np.sum(c * t.vx - s * t.vy)
    y += h * np.sum(s * t.vx + c * t.vy)
    assert_pose_close(integrate(p, t, dt), Pose2D(x, y, th + t.omega * dt), tol=1e-6)


test_matches_fine_euler_integration_thoroughly = slow_twin(
    test_matches_fine_euler_integration, max_examples=100
)


def test_known_arc_and_straight_line() -> None:
    half_circle = integrate(Pose2D(0, 0, 0), Twist2D(1.0, 0.0, math.pi), 1.0)
    assert_pose_close(half_circle, Pose2D(0.0, 2.0 / math.pi, math.pi))
    line = integrate(Pose2D(1, 1, math.pi / 2), Twist2D(2.0, 0.0, 0.0), 0.5)
    assert_pose_close(line, Pose2D(1.0, 2.0, math.pi / 2))
    strafe = integrate(Pose2D(0, 0, 0), Twist2D(0.0, 1.0, 0.0), 1.0)
    assert_pose_close(strafe, Pose2D(0.0, 1.0, 0.0))


def test_accurate_across_small_rates() -> None:
    # Series of sin(e)/e and (1 - cos e)/e, exact to double precision for e <= 1e-3,
    # checked on both sides of the kernel's switch to its own series at 1e-4.
    for e in (0.0, 1e-12, 1e-8, 1e-5, 1e-4 * (1 - 1e-9), 1e-4 * (1 + 1e-9), 1e-3):
        a = 1 - e**2 / 6 + e**4 / 120
        b = e / 2 - e**3 / 24 + e**5 / 720
        te = integrate(Pose2D(0, 0, 0), Twist2D(1.0, 0.5, e), 1.0)
        assert te.x == pytest.approx(a - 0.5 * b, abs=1e-15)
        assert te.y == pytest.approx(b + 0.5 * a, abs=1e-15)


@settings(deadline=None, max_examples=50)
@given(poses, st.lists(st.tuples(speeds, speeds, rates, dts), min_size=0, max_size=20))
def test_rollout_matches_repeated_integrate(
    p: Pose2D, steps: list[tuple[float, float, float, float]]
) -> None:
    tw = np.array([s[:3] for s in steps]).reshape(-1, 3)
    dt = np.array([s[3] for s in steps])
    traj = rollout(p, tw, dt)
    assert traj.shape == (len(steps) + 1, 3)
    q = p
    np.testing.assert_allclose(traj[0], p.as_array())
    for i, (vx, vy, om, h) in enumerate(steps):
        q = integrate(q, Twist2D(vx, vy, om), h)
        np.testing.assert_allclose(traj[i + 1], q.as_array(), atol=1e-12)


def test_rollout_scalar_dt_and_errors() -> None:
    traj = rollout(Pose2D(0, 0, 0), [[1.0, 0.0, 0.0]] * 4, 0.25)
    np.testing.assert_allclose(traj[:, 0], [0, 0.25, 0.5, 0.75, 1.0])
    with pytest.raises(ValueError, match="twists"):
        rollout(Pose2D(0, 0), np.zeros((3, 2)), 0.1)
    with pytest.raises(ValueError, match="dt"):
        rollout(Pose2D(0, 0), np.zeros((3, 3)), [0.1, 0.2])
    with pytest.raises(ValueError, match="dt"):
        rollout(Pose2D(0, 0), np.zeros((1, 3)), -0.1)
    with pytest.raises(ValueError, match="twists"):
        rollout(Pose2D(0, 0), [[0.0, math.nan, 0.0]], 0.1)
    with pytest.raises(ValueError, match="dt"):
        integrate(Pose2D(0, 0), Twist2D(1.0), -1.0)
    with pytest.raises(TypeError, match="twist must be a Twist2D"):
        integrate(Pose2D(0, 0), 1.0, 1.0)
    with pytest.raises(TypeError, match="pose must be a Pose2D"):
        integrate(3, Twist2D(1.0), 1.0)
    with pytest.raises(ValueError, match="twist"):
        integrate(Pose2D(0, 0), (1.0, 0.0), 1.0)
    with pytest.raises(TypeError, match="pose must be a Pose2D"):
        rollout("0 0 0", np.zeros((1, 3)), 0.1)


def test_integrate_accepts_sequences() -> None:
    ref = integrate(Pose2D(1.0, 2.0, 0.3), Twist2D(0.5, 0.1, 0.7), 0.4)
    assert integrate([1.0, 2.0, 0.3], (0.5, 0.1, 0.7), 0.4) == ref
    assert integrate(np.array([1.0, 2.0, 0.3]), np.array([0.5, 0.1, 0.7]), 0.4) == ref


def test_rollout_accepts_twist_objects_and_a_pose_sequence() -> None:
    twists = [Twist2D(1.0, 0.0, 0.5), Twist2D(0.5, 0.2, -0.3), Twist2D(0.0, 0.0, 1.0)]
    ref = rollout(Pose2D(1.0, -1.0, 0.2), np.array([t.as_array() for t in twists]), 0.3)
    np.testing.assert_array_equal(rollout(Pose2D(1.0, -1.0, 0.2), twists, 0.3), ref)
    np.testing.assert_array_equal(rollout([1.0, -1.0, 0.2], tuple(twists), 0.3), ref)
    # Twist2D items and [vx, vy, omega] rows may be mixed.
    mixed = [twists[0], [0.5, 0.2, -0.3], twists[2]]
    np.testing.assert_array_equal(rollout(Pose2D(1.0, -1.0, 0.2), mixed, 0.3), ref)
    empty = rollout(Pose2D(1.0, -1.0, 0.2), [], 0.3)
    np.testing.assert_array_equal(empty, [[1.0, -1.0, 0.2]])
    with pytest.raises(TypeError, match=r"twists\[1\]"):
        rollout(Pose2D(0, 0), [Twist2D(1.0), "fast"], 0.1)
    with pytest.raises(ValueError, match=r"twists\[1\]"):
        rollout(Pose2D(0, 0), [Twist2D(1.0), [1.0, 0.0]], 0.1)
    with pytest.raises(ValueError, match="dt"):
        rollout(Pose2D(0, 0), twists, [0.1, 0.2])


def test_an_overflowing_turn_is_named_as_such() -> None:
    # A 0.5 m circle: the pose stays bounded, but omega * dt = 2e308 rad is not a float.
    with pytest.raises(ValueError, match=r"twist, dt: the heading change omega \* dt overflows"):
        integrate(Pose2D(0, 0, 0), Twist2D(1.0, 0.0, 2.0), 1e308)
    with pytest.raises(ValueError, match=r"twists, dt: the heading change omega \* dt overflows"):
        rollout(Pose2D(0, 0, 0), [[1.0, 0.0, 0.0], [1.0, 0.0, 2.0]], 1e308)
    # A position that overflows is still reported as one.
    with pytest.raises(ValueError, match="twist, dt: the motion overflows float64"):
        integrate(Pose2D(0, 0, 0), Twist2D(1e308, 0.0, 0.0), 10.0)
