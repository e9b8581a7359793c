"""DiffDrive kinematics and odometry steps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, Twist2D, angle_diff, integrate
from navkit.kinematics import DiffDrive

radii = st.floats(0.01, 0.5)
tracks = st.floats(0.05, 2.0)
speeds = st.floats(-20, 20, allow_nan=False)


@settings(max_examples=40)
@given(tracks, radii, radii, speeds, speeds)
def test_roundtrip_unequal_radii(d: float, rl: float, rr: float, wl: float, wr: float) -> None:
    drive = DiffDrive(track=d, left_radius=rl, right_radius=rr)
    back = drive.inverse(drive.forward([wl, wr]))
    assert isinstance(back, np.ndarray) and back.shape == (2,)
    assert back[0] == pytest.approx(wl, abs=1e-9)
    assert back[1] == pytest.approx(wr, abs=1e-9)


test_roundtrip_unequal_radii_thoroughly = slow_twin(test_roundtrip_unequal_radii, max_examples=100)


@settings(max_examples=40)
@given(tracks, radii, radii, st.floats(-3, 3), st.floats(-3, 3))
def test_inverse_forward_roundtrip(d: float, rl: float, rr: float, v: float, w: float) -> None:
    drive = DiffDrive(track=d, left_radius=rl, right_radius=rr)
    t = drive.forward(drive.inverse(Twist2D(v, 0.0, w)))
    assert t.vx == pytest.approx(v, abs=1e-9)
    assert t.omega == pytest.approx(w, abs=1e-9)
    assert t.vy == 0.0


test_inverse_forward_roundtrip_thoroughly = slow_twin(
    test_inverse_forward_roundtrip, max_examples=100
)


def test_known_values() -> None:
    drive = DiffDrive(track=0.4, left_radius=0.1, right_radius=0.12)
    t = drive.forward([10.0, 10.0])
    assert t.vx == pytest.approx((1.2 + 1.0) / 2)
    assert t.omega == pytest.approx((1.2 - 1.0) / 0.4)
    wl, wr = drive.inverse(Twist2D(0.0, 0.0, 1.0))
    assert wl == pytest.approx(-0.2 / 0.1)
    assert wr == pytest.approx(0.2 / 0.12)
    # Wheel speeds are [left, right]: the right wheel is faster when turning left.
    t = drive.forward(np.array([0.0, 10.0]))
    assert t.omega == pytest.approx(1.2 / 0.4)
    assert drive.n_wheels == 2


def test_inverse_returns_array_and_accepts_sequences() -> None:
    drive = DiffDrive(track=0.4, left_radius=0.1, right_radius=0.12)
    speeds = drive.inverse(Twist2D(0.5, 0.0, 1.0))
    assert isinstance(speeds, np.ndarray)
    assert speeds.shape == (2,) and speeds.dtype == np.float64
    np.testing.assert_array_equal(drive.inverse([0.5, 0.0, 1.0]), speeds)
    np.testing.assert_array_equal(drive.inverse((0.5, 0.0, 1.0)), speeds)
    np.testing.assert_array_equal(drive.inverse_batch([[0.5, 0.0, 1.0]])[0], speeds)
    with pytest.raises(TypeError, match="twist must be a Twist2D"):
        drive.inverse(0.5)
    with pytest.raises(ValueError, match="twist"):
        drive.inverse([0.5, 1.0])


def test_batch_matches_single() -> None:
    drive = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.051)
    wheels = np.column_stack(([1.0, -2.0, 3.0], [2.0, 2.0, -1.0]))
    tw = drive.forward_batch(wheels)
    assert tw.shape == (3, 3)
    for i in range(3):
        np.testing.assert_allclose(tw[i], drive.forward(wheels[i]).as_array())
        np.testing.assert_allclose(drive.inverse(tw[i]), wheels[i])
    np.testing.assert_allclose(drive.inverse_batch(tw), wheels)
    with pytest.raises(ValueError, match="wheel_speeds"):
        drive.forward_batch(np.zeros((3, 3)))


def test_lateral_velocity_rejected_unless_ignored() -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    with pytest.raises(ValueError, match="vy"):
        drive.inverse(Twist2D(1.0, 0.1, 0.0))
    np.testing.assert_array_equal(
        drive.inverse(Twist2D(1.0, 0.1, 0.0), ignore_lateral=True),
        drive.inverse(Twist2D(1.0, 0.0, 0.0)),
    )
    with pytest.raises(ValueError, match="vy"):
        drive.inverse_batch([[1.0, 0.1, 0.0]])


@settings(max_examples=40, deadline=None)
@given(tracks, st.floats(-1, 1), st.floats(-1, 1))
def test_arc_odometry_is_exact(d: float, dl: float, dr: float) -> None:
    """The arc step equals integrating the constant twist that rolls those distances."""
    drive = DiffDrive(track=d, wheel_radius=0.05)
    step = drive.odometry_step(dl, dr)
    assert isinstance(step, Pose2D)
    p = integrate(Pose2D(0, 0, 0), Twist2D((dl + dr) / 2, 0.0, (dr - dl) / d), 1.0)
    assert step.x == pytest.approx(p.x, abs=1e-12)
    assert step.y == pytest.approx(p.y, abs=1e-12)
    # The Pose2D wraps the rotation; it is (dr - dl) / d modulo 2π.
    assert angle_diff(step.theta, (dr - dl) / d) == pytest.approx(0.0, abs=1e-12)
    batch = drive.odometry_step_batch([dl], [dr])
    np.testing.assert_array_equal(batch[0], step.as_array())


test_arc_odometry_is_exact_thoroughly = slow_twin(test_arc_odometry_is_exact, max_examples=100)


def test_methods_agree_to_their_order() -> None:
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    dl, dr = 0.10, 0.11
    arc = drive.odometry_step(dl, dr, method="arc").as_array()
    mid = drive.odometry_step(dl, dr, method="midpoint").as_array()
    first = drive.odometry_step(dl, dr, method="first_order").as_array()
    np.testing.assert_array_equal(arc, drive.odometry_step(dl, dr).as_array())
    assert first[1] == 0.0
    assert first[0] == pytest.approx((dl + dr) / 2)
    # Mid-point errors are second order in dθ, first-order ones first order.
    assert np.abs(mid - arc).max() < 0.01 * np.abs(first - arc).max()


def test_odometry_arrays_and_errors() -> None:
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    dl, dr = np.array([0.1, 0.0, -0.2]), np.array([0.1, 0.1, 0.2])
    for method in ("arc", "midpoint", "first_order"):
        steps = drive.odometry_step_batch(dl, dr, method=method)
        assert steps.shape == (3, 3)
        for i in range(3):
            one = drive.odometry_step(dl[i], dr[i], method=method)
            np.testing.assert_allclose(steps[i], one.as_array())
    assert drive.odometry_step_batch([], []).shape == (0, 3)
    with pytest.raises(ValueError, match="method"):
        drive.odometry_step(0.1, 0.1, method="euler")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="method"):
        drive.odometry_step_batch([0.1], [0.1], method="euler")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="d_left"):
        drive.odometry_step_batch([0.1, 0.2], [0.1])
    with pytest.raises(ValueError, match="d_left"):
        drive.odometry_step_batch(0.1, 0.1)
    with pytest.raises(TypeError, match="d_left"):
        drive.odometry_step([0.1], 0.1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="d_right"):
        drive.odometry_step(0.1, math.inf)
    with pytest.raises(TypeError):
        drive.odometry_step(0.1, 0.1, "arc")  # type: ignore[call-arg]


def test_constructor_errors() -> None:
    with pytest.raises(ValueError, match="track"):
        DiffDrive(track=0.0, wheel_radius=0.05)
    with pytest.raises(ValueError, match="wheel_radius"):
        DiffDrive(track=0.3, wheel_radius=-0.05)
    with pytest.raises(ValueError, match="left_radius"):
        DiffDrive(track=0.3, left_radius=math.nan, right_radius=0.05)
    with pytest.raises(ValueError, match="both"):
        DiffDrive(track=0.3, wheel_radius=0.05, left_radius=0.05, right_radius=0.05)
    with pytest.raises(ValueError, match="right_radius"):
        DiffDrive(track=0.3, left_radius=0.05)
    with pytest.raises(ValueError, match="wheel_speeds"):
        DiffDrive(track=0.3, wheel_radius=0.05).forward([math.inf, 0.0])
    with pytest.raises(ValueError, match="wheel_speeds"):
        DiffDrive(track=0.3, wheel_radius=0.05).forward([1.0, 2.0, 3.0])


def test_constructor_is_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        DiffDrive(0.3, 0.05)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="positional"):
        DiffDrive(0.3, wheel_radius=0.05)  # type: ignore[call-arg]
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    assert drive.track == 0.3
    assert drive.left_radius == drive.right_radius == 0.05
