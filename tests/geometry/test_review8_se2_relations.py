"""Metamorphic relations of SE(2) poses, exact twist integration and quaternions.

Each test checks a relation the mathematics guarantees between two runs (one step
vs two half steps, a world moved by a common transform, a mirrored world), over
random inputs. Tolerances: the inputs are O(100) m and O(10) rad, every result is a
handful of float64 operations on them, so rounding is about 1e-13 relative; 1e-9
(relative to the coordinates' size) leaves a wide margin while any modelling error
(a wrong sign, a first-order formula) would be orders of magnitude larger.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from navkit.geometry import (
    Pose2D,
    Twist2D,
    angle_diff,
    imu_to_base,
    integrate,
    quaternion_to_matrix,
    quaternion_to_yaw,
    rollout,
    yaw_to_quaternion,
)

coords = st.floats(-100.0, 100.0)
angles = st.floats(-10.0, 10.0)
rates = st.floats(-5.0, 5.0)
steps = st.floats(0.0, 3.0)
poses = st.builds(Pose2D, coords, coords, angles)
twists = st.builds(Twist2D, rates, rates, rates)
FAST = settings(max_examples=60, deadline=None)

TOL = 1e-9


def assert_same_pose(a: Pose2D, b: Pose2D) -> None:
    scale = 1.0 + max(abs(a.x), abs(a.y))
    assert abs(a.x - b.x) <= TOL * scale, (a, b)
    assert abs(a.y - b.y) <= TOL * scale, (a, b)
    # Headings compared on the circle: ±π are the same heading.
    assert abs(angle_diff(a.theta, b.theta)) <= TOL, (a, b)


def mirrored(p: Pose2D) -> Pose2D:
    return Pose2D(p.x, -p.y, -p.theta)


@FAST
@given(poses, twists, steps, st.floats(0.0, 1.0))
def test_one_step_equals_two_steps_of_a_constant_twist(
    pose: Pose2D, twist: Twist2D, dt: float, frac: float
) -> None:
    # The SE(2) exponential is exact: exp(t1 ξ) exp(t2 ξ) = exp((t1 + t2) ξ).
    first = dt * frac
    one = integrate(pose, twist, dt)
    two = integrate(integrate(pose, twist, first), twist, dt - first)
    assert_same_pose(one, two)
    rows = rollout(pose, [twist, twist], [first, dt - first])
    assert_same_pose(Pose2D.from_array(rows[-1]), one)


@FAST
@given(poses, poses, twists, steps)
def test_integration_is_left_equivariant(
    g: Pose2D, pose: Pose2D, twist: Twist2D, dt: float
) -> None:
    # Body twists do not see the world frame: moving the start by g moves the end by g.
    assert_same_pose(g.compose(integrate(pose, twist, dt)), integrate(g.compose(pose), twist, dt))
    # and the motion is the start composed with the motion from the identity.
    assert_same_pose(integrate(pose, twist, dt), pose.compose(integrate([0, 0, 0], twist, dt)))


@FAST
@given(poses, twists, steps)
def test_integration_mirrors_and_reverses(pose: Pose2D, twist: Twist2D, dt: float) -> None:
    end = integrate(pose, twist, dt)
    # Reflect the world (y -> -y): lateral speed and yaw rate change sign.
    flipped = integrate(mirrored(pose), Twist2D(twist.vx, -twist.vy, -twist.omega), dt)
    assert_same_pose(mirrored(flipped), end)
    # Driving the negated twist for the same time comes back to the start.
    back = integrate(end, Twist2D(-twist.vx, -twist.vy, -twist.omega), dt)
    assert_same_pose(back, pose)


@FAST
@given(poses, poses, poses)
def test_compose_inverse_and_relative_to_relations(a: Pose2D, b: Pose2D, c: Pose2D) -> None:
    assert_same_pose(a.compose(b).compose(c), a.compose(b.compose(c)))
    assert_same_pose(a.compose(a.inverse()), Pose2D(0.0, 0.0, 0.0))
    assert_same_pose(a.inverse().compose(a), Pose2D(0.0, 0.0, 0.0))
    assert_same_pose(b.relative_to(a), a.inverse().compose(b))
    # A relative pose does not change when both poses move by the same transform.
    assert_same_pose(c.compose(b).relative_to(c.compose(a)), b.relative_to(a))
    pts = np.array([[b.x, b.y], [c.x, c.y]])
    np.testing.assert_allclose(
        a.compose(b).transform_points(pts),
        a.transform_points(b.transform_points(pts)),
        rtol=TOL,
        atol=TOL * 1e3,  # points up to ~300 m from the origin after two transforms
    )


quaternions = st.tuples(*[st.floats(-1.0, 1.0)] * 4).filter(lambda q: np.linalg.norm(q) > 1e-3)


@FAST
# 1.3e-6 horizontal: k q's yaw 3.7e-10 off q's (2 ε / horizontal).
@example(
    (0.012813733287061093, 0.22524009049164814, -0.012814000572710964, 0.22524023064893917),
    0.0,
    1.9263642344301037e-92,
)
@given(quaternions, angles, st.floats(1e-200, 1e200))
def test_quaternion_yaw_relations(q: tuple[float, ...], psi: float, k: float) -> None:
    quat = np.array(q)
    rot = quaternion_to_matrix(quat)
    horizontal = math.hypot(float(rot[0, 0]), float(rot[1, 0]))
    assume(horizontal > 1e-6)  # the yaw is undefined at pitch ±90°
    yaw = float(quaternion_to_yaw(quat))
    # q, -q and k q are the same rotation. k q normalises to q but for rounding, which
    # moves the heading of a nearly vertical x axis by rounding / its horizontal length.
    assert abs(float(angle_diff(quaternion_to_yaw(-quat), yaw))) <= 1e-12
    assert abs(float(angle_diff(quaternion_to_yaw(k * quat), yaw))) <= 1e-12 / horizontal
    # A yaw about the world z axis adds to the yaw of any orientation; the heading of the
    # projected x axis has an error of rounding / its horizontal length.
    turned = yaw_to_quaternion(psi)
    x1, y1, z1, w1 = turned
    x2, y2, z2, w2 = quat / np.linalg.norm(quat)
    product = np.array(
        [
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        ]
    )
    assert abs(float(angle_diff(quaternion_to_yaw(product), yaw + psi))) <= 1e-9 / horizontal
    np.testing.assert_allclose(
        quaternion_to_matrix(product), quaternion_to_matrix(turned) @ rot, atol=1e-12
    )


@FAST
@given(quaternions, quaternions, st.tuples(*[rates] * 3), st.tuples(*[rates] * 3))
def test_imu_mounting_and_its_inverse_cancel(
    q: tuple[float, ...], m: tuple[float, ...], w: tuple[float, ...], a: tuple[float, ...]
) -> None:
    mounted = imu_to_base(q, w, a, mount=m)
    inverse = np.array(m) * np.array([-1.0, -1.0, -1.0, 1.0])  # conjugate: m⁻¹ up to scale
    back = imu_to_base(
        mounted.orientations, mounted.angular_velocities, mounted.linear_accelerations,
        mount=inverse,
    )
    np.testing.assert_allclose(back.angular_velocities, w, atol=1e-12)
    np.testing.assert_allclose(back.linear_accelerations, a, atol=1e-12)
    np.testing.assert_allclose(
        quaternion_to_matrix(back.orientations), quaternion_to_matrix(q), atol=1e-12
    )
