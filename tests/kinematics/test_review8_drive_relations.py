"""Metamorphic relations of the drive kinematics: mirrors, wheel permutations, scaling.

Tolerances: lengths in [0.01, 5] m and speeds O(20) rad/s give results of a few
float64 operations (rounding ~1e-15 relative); 1e-9 is a wide margin that any
wrong sign or factor would exceed by far. The omni-drive forward map is a
pseudo-inverse (rounding grows with the layout's condition number, kept below 1e4
here), hence 1e-7 there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, angle_diff, integrate
from navkit.kinematics import DiffDrive, OmniDrive

lengths = st.floats(0.01, 5.0)
speeds = st.floats(-20.0, 20.0)
scales = st.floats(0.1, 10.0)
METHODS = ("arc", "midpoint", "first_order")
FAST = settings(max_examples=60, deadline=None)


def assert_same_pose(a: Pose2D, b: Pose2D, tol: float = 1e-9) -> None:
    scale = 1.0 + max(abs(a.x), abs(a.y))
    assert abs(a.x - b.x) <= tol * scale and abs(a.y - b.y) <= tol * scale, (a, b)
    assert abs(angle_diff(a.theta, b.theta)) <= tol, (a, b)


@FAST
@given(lengths, lengths, lengths, speeds, speeds, scales)
def test_diff_drive_mirror_and_scale(
    track: float, left: float, right: float, wl: float, wr: float, k: float
) -> None:
    drive = DiffDrive(track=track, left_radius=left, right_radius=right)
    # The mirror image of the robot has its wheels (and their radii) swapped sides.
    mirror = DiffDrive(track=track, left_radius=right, right_radius=left)
    twist = drive.forward([wl, wr])
    flipped = mirror.forward([wr, wl])
    assert math.isclose(flipped.vx, twist.vx, rel_tol=1e-12, abs_tol=1e-12)
    assert math.isclose(flipped.omega, -twist.omega, rel_tol=1e-12, abs_tol=1e-12)
    np.testing.assert_allclose(
        mirror.inverse([twist.vx, 0.0, -twist.omega]), [wr, wl], rtol=1e-9, atol=1e-9
    )
    # Every length times k: speeds times k, turn rates unchanged.
    big = DiffDrive(track=k * track, left_radius=k * left, right_radius=k * right)
    scaled = big.forward([wl, wr])
    assert math.isclose(scaled.vx, k * twist.vx, rel_tol=1e-9, abs_tol=1e-9)
    assert math.isclose(scaled.omega, twist.omega, rel_tol=1e-9, abs_tol=1e-9)


@FAST
@given(lengths, lengths, lengths, speeds, speeds, scales, st.sampled_from(METHODS))
def test_odometry_step_mirror_and_scale(
    track: float, left: float, right: float, wl: float, wr: float, k: float, method: str
) -> None:
    drive = DiffDrive(track=track, left_radius=left, right_radius=right)
    dl, dr = 0.1 * wl * left, 0.1 * wr * right
    step = drive.odometry_step(dl, dr, method=method)  # type: ignore[arg-type]
    swapped = drive.odometry_step(dr, dl, method=method)  # type: ignore[arg-type]
    assert_same_pose(Pose2D(swapped.x, -swapped.y, -swapped.theta), step)
    big = DiffDrive(track=k * track, left_radius=left, right_radius=right)
    scaled = big.odometry_step(k * dl, k * dr, method=method)  # type: ignore[arg-type]
    assert_same_pose(Pose2D(scaled.x / k, scaled.y / k, scaled.theta), step)


@FAST
@given(lengths, lengths, lengths, speeds, speeds, st.floats(0.0, 2.0))
def test_arc_odometry_is_the_exact_motion_of_the_forward_twist(
    track: float, left: float, right: float, wl: float, wr: float, dt: float
) -> None:
    # Constant wheel speeds for dt: the "arc" step is the SE(2) exponential of the twist.
    drive = DiffDrive(track=track, left_radius=left, right_radius=right)
    step = drive.odometry_step(wl * left * dt, wr * right * dt)
    assert_same_pose(step, integrate(Pose2D(0.0, 0.0, 0.0), drive.forward([wl, wr]), dt))


def _layout_ok(angles: list[float]) -> bool:
    layout = np.column_stack((-np.sin(angles), np.cos(angles), np.ones(len(angles))))
    return bool(np.linalg.cond(layout) < 1e4)


layouts = st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=6, unique=True)
twist_values = st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5))


@settings(FAST, max_examples=25)
@given(
    layouts, lengths, lengths, twist_values, st.floats(-3.0, 3.0), st.randoms(use_true_random=False)
)
def test_omni_drive_relations(
    angles: list[float],
    r: float,
    base: float,
    twist: tuple[float, float, float],
    rot: float,
    rnd: object,
) -> None:
    assume(_layout_ok(angles))
    vx, vy, w = twist
    drive = OmniDrive(angles, wheel_radius=r, base_radius=base)
    wheels = drive.inverse(twist)
    # Mirror: wheel angles negated; the mirrored twist turns every wheel backwards.
    mirror = OmniDrive([-a for a in angles], wheel_radius=r, base_radius=base)
    np.testing.assert_allclose(mirror.inverse([vx, -vy, -w]), -wheels, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(
        mirror.forward(-wheels).as_array(), [vx, -vy, -w], rtol=1e-7, atol=1e-7
    )
    # Wheel order is a labelling: permuting the wheels permutes the speeds.
    perm = np.array(rnd.sample(range(len(angles)), len(angles)))  # type: ignore[attr-defined]
    shuffled = OmniDrive(np.array(angles)[perm], wheel_radius=r, base_radius=base)
    np.testing.assert_allclose(shuffled.inverse(twist), wheels[perm], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(
        shuffled.forward(wheels[perm]).as_array(),
        drive.forward(wheels).as_array(),
        rtol=1e-7,
        atol=1e-7,
    )
    # Turning the whole layout by rot is expressing the twist in a frame turned by rot.
    turned = OmniDrive(np.array(angles) + rot, wheel_radius=r, base_radius=base)
    c, s = math.cos(rot), math.sin(rot)
    turned_twist = [c * vx - s * vy, s * vx + c * vy, w]
    np.testing.assert_allclose(turned.inverse(turned_twist), wheels, rtol=1e-7, atol=1e-7)


test_omni_drive_relations_thoroughly = slow_twin(test_omni_drive_relations, max_examples=60)


@settings(FAST, max_examples=25)
@given(layouts, lengths, lengths, twist_values, scales)
def test_omni_drive_is_scale_free(
    angles: list[float], r: float, base: float, twist: tuple[float, float, float], k: float
) -> None:
    assume(_layout_ok(angles))
    vx, vy, w = twist
    drive = OmniDrive(angles, wheel_radius=r, base_radius=base)
    big = OmniDrive(angles, wheel_radius=k * r, base_radius=k * base)
    wheels = drive.inverse(twist)
    np.testing.assert_allclose(big.inverse([k * vx, k * vy, w]), wheels, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(
        big.forward(wheels).as_array(), [k * vx, k * vy, w], rtol=1e-7, atol=1e-7
    )


test_omni_drive_is_scale_free_thoroughly = slow_twin(test_omni_drive_is_scale_free, max_examples=60)


@pytest.mark.parametrize("method", METHODS)
def test_odometry_step_batch_rows_are_the_single_steps(method: str) -> None:
    drive = DiffDrive(track=0.4, left_radius=0.05, right_radius=0.06)
    rng = np.random.default_rng(3)
    dl, dr = rng.normal(size=(2, 20))
    rows = drive.odometry_step_batch(dl, dr, method=method)  # type: ignore[arg-type]
    singles = [
        drive.odometry_step(a, b, method=method).as_array()  # type: ignore[arg-type]
        for a, b in zip(dl, dr, strict=True)
    ]
    np.testing.assert_array_equal(rows, np.array(singles))
