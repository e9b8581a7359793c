"""DiffDrive kinematics and odometry steps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.kinematics import DiffDrive

radii = st.floats(0.01, 0.5)
tracks = st.floats(0.05, 2.0)
speeds = st.floats(-20, 20, allow_nan=False)


@given(tracks, radii, radii, speeds, speeds)
def test_roundtrip_unequal_radii(d: float, rl: float, rr: float, wl: float, wr: float) -> None:
    drive = DiffDrive(d, left_radius=rl, right_radius=rr)
    back = drive.inverse(drive.forward(wl, wr))
    assert back[0] == pytest.approx(wl, abs=1e-9)
    assert back[1] == pytest.approx(wr, abs=1e-9)


@given(tracks, radii, radii, st.floats(-3, 3), st.floats(-3, 3))
def test_inverse_forward_roundtrip(d: float, rl: float, rr: float, v: float, w: float) -> None:
    drive = DiffDrive(d, left_radius=rl, right_radius=rr)
    t = drive.forward(*drive.inverse(Twist2D(v, 0.0, w)))
    assert t.vx == pytest.approx(v, abs=1e-9)
    assert t.omega == pytest.approx(w, abs=1e-9)
    assert t.vy == 0.0


def test_known_values() -> None:
    drive = DiffDrive(0.4, left_radius=0.1, right_radius=0.12)
    t = drive.forward(omega_left=10.0, omega_right=10.0)
    assert t.vx == pytest.approx((1.2 + 1.0) / 2)
    assert t.omega == pytest.approx((1.2 - 1.0) / 0.4)
    wl, wr = drive.inverse(Twist2D(0.0, 0.0, 1.0))
    assert wl == pytest.approx(-0.2 / 0.1)
    assert wr == pytest.approx(0.2 / 0.12)


def test_batch_matches_single() -> None:
    drive = DiffDrive(0.3, left_radius=0.05, right_radius=0.051)
    wl, wr = np.array([1.0, -2.0, 3.0]), np.array([2.0, 2.0, -1.0])
    tw = drive.forward_batch(wl, wr)
    for i in range(3):
        np.testing.assert_allclose(tw[i], drive.forward(wl[i], wr[i]).as_array())
    np.testing.assert_allclose(drive.inverse_batch(tw), np.column_stack((wl, wr)))


def test_lateral_velocity_rejected_unless_ignored() -> None:
    drive = DiffDrive(0.3, 0.05)
    with pytest.raises(ValueError, match="vy"):
        drive.inverse(Twist2D(1.0, 0.1, 0.0))
    assert drive.inverse(Twist2D(1.0, 0.1, 0.0), ignore_lateral=True) == drive.inverse(
        Twist2D(1.0, 0.0, 0.0)
    )
    with pytest.raises(ValueError, match="vy"):
        drive.inverse_batch([[1.0, 0.1, 0.0]])


@settings(deadline=None)
@given(tracks, st.floats(-1, 1), st.floats(-1, 1))
def test_arc_odometry_is_exact(d: float, dl: float, dr: float) -> None:
    """The arc step equals integrating the constant twist that rolls those distances."""
    drive = DiffDrive(d, 0.05)
    dx, dy, dth = drive.odometry_step(dl, dr)
    p = integrate(Pose2D(0, 0, 0), Twist2D((dl + dr) / 2, 0.0, (dr - dl) / d), 1.0)
    assert dx == pytest.approx(p.x, abs=1e-12)
    assert dy == pytest.approx(p.y, abs=1e-12)
    assert dth == pytest.approx((dr - dl) / d, abs=1e-12)


def test_methods_agree_to_their_order() -> None:
    drive = DiffDrive(0.5, 0.1)
    dl, dr = 0.10, 0.11
    arc = np.array(drive.odometry_step(dl, dr, "arc"))
    mid = np.array(drive.odometry_step(dl, dr, "midpoint"))
    first = np.array(drive.odometry_step(dl, dr, "first_order"))
    assert first[1] == 0.0
    assert first[0] == pytest.approx((dl + dr) / 2)
    # Mid-point errors are second order in dθ, first-order ones first order.
    assert np.abs(mid - arc).max() < 0.01 * np.abs(first - arc).max()


def test_odometry_arrays_and_errors() -> None:
    drive = DiffDrive(0.5, 0.1)
    dl, dr = np.array([0.1, 0.0, -0.2]), np.array([0.1, 0.1, 0.2])
    dx, dy, dth = drive.odometry_step(dl, dr)
    for i in range(3):
        np.testing.assert_allclose((dx[i], dy[i], dth[i]), drive.odometry_step(dl[i], dr[i]))
    with pytest.raises(ValueError, match="method"):
        drive.odometry_step(0.1, 0.1, method="euler")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="d_left"):
        drive.odometry_step([0.1, 0.2], [0.1])


def test_constructor_errors() -> None:
    with pytest.raises(ValueError, match="track"):
        DiffDrive(0.0, 0.05)
    with pytest.raises(ValueError, match="wheel_radius"):
        DiffDrive(0.3, -0.05)
    with pytest.raises(ValueError, match="left_radius"):
        DiffDrive(0.3, left_radius=math.nan, right_radius=0.05)
    with pytest.raises(ValueError, match="both"):
        DiffDrive(0.3, 0.05, left_radius=0.05, right_radius=0.05)
    with pytest.raises(ValueError, match="right_radius"):
        DiffDrive(0.3, left_radius=0.05)
    with pytest.raises(ValueError, match="omega_left"):
        DiffDrive(0.3, 0.05).forward(math.inf, 0.0)
