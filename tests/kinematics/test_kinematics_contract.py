"""Issue 12 in navkit.kinematics: documented ranges, flags, overflow as ValueError, never NaN."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.kinematics import DiffDrive, OmniDrive, tick_delta, ticks_to_distance

LENGTHS = st.floats(1e-6, 1e6)


def test_odometry_step_of_opposite_huge_distances_is_a_value_error_not_nan() -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    # Before issue 12: ValueError "x must be finite, got nan" from a NaN pose.
    with pytest.raises(ValueError, match="d_left, d_right: the heading change"):
        drive.odometry_step(1e308, -1e308)
    with pytest.raises(ValueError, match="d_left, d_right"):
        drive.odometry_step_batch([0.1, 1e308], [0.1, -1e308])
    # Equal huge distances: a straight line, no overflow in the mean distance.
    step = drive.odometry_step(1e308, 1e308).as_array()
    np.testing.assert_array_equal(step, drive.odometry_step_batch([1e308], [1e308])[0])
    assert drive.odometry_step(1.7e308, 1.7e308).x == 1.7e308


@pytest.mark.parametrize(
    ("make", "name"),
    [
        (lambda: OmniDrive.three_wheel(wheel_radius=1e308, base_radius=0.2), "wheel_radius"),
        (lambda: OmniDrive.three_wheel(wheel_radius=0.05, base_radius=5e-324), "base_radius"),
        (lambda: OmniDrive([0.0, 2.0, 4.0], wheel_radius=1e-7, base_radius=0.2), "wheel_radius"),
        (lambda: DiffDrive(track=1e7, wheel_radius=0.05), "track"),
        (lambda: DiffDrive(track=0.3, wheel_radius=5e-324), "wheel_radius"),
        (lambda: DiffDrive(track=0.3, left_radius=0.05, right_radius=2e6), "right_radius"),
        (lambda: ticks_to_distance(1, ticks_per_rev=0.5, wheel_radius=0.1), "ticks_per_rev"),
        (lambda: ticks_to_distance(1, ticks_per_rev=1e13, wheel_radius=0.1), "ticks_per_rev"),
        (lambda: ticks_to_distance(1, ticks_per_rev=100, wheel_radius=1e308), "wheel_radius"),
    ],
)
def test_parameters_outside_their_documented_range_are_refused(make, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=f"{name} must be in"):
        make()


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda d, o: d.forward([1e308, -1e308]), "wheel_speeds"),
        (lambda d, o: d.forward_batch([[1e308, -1e308]]), "wheel_speeds"),
        (lambda d, o: d.inverse([1e308, 0.0, 1e308]), "twist"),
        (lambda d, o: d.inverse_batch([[1e308, 0.0, 1e308]]), "twists"),
        (lambda d, o: o.inverse([1e308, 1e308, 1e308]), "twist"),
        (lambda d, o: o.inverse_batch([[1e308, 1e308, 1e308]]), "twists"),
        (lambda d, o: o.big.forward([1e308, -1e308, 1e308]), "wheel_speeds"),
        (lambda d, o: o.big.forward_batch([[1e308, -1e308, 1e308]]), "wheel_speeds"),
        (lambda d, o: ticks_to_distance(1e308, ticks_per_rev=1, wheel_radius=1e6), "delta_ticks"),
    ],
)
def test_results_that_would_overflow_are_value_errors(call, name) -> None:  # type: ignore[no-untyped-def]
    diff = DiffDrive(track=1e-6, wheel_radius=1e-6)
    omni = SimpleNamespace(
        inverse=OmniDrive.three_wheel(wheel_radius=1e-6, base_radius=1e6).inverse,
        inverse_batch=OmniDrive.three_wheel(wheel_radius=1e-6, base_radius=1e6).inverse_batch,
        big=OmniDrive.three_wheel(wheel_radius=1e6, base_radius=1e-6),
    )
    with pytest.raises(ValueError, match=f"{name}: .* would overflow"):
        call(diff, omni)


@pytest.mark.parametrize("flag", ["no", 0, 1, None, np.float64(1.0)])
def test_ignore_lateral_must_be_a_bool(flag: object) -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    with pytest.raises(TypeError, match="ignore_lateral must be a bool"):
        drive.inverse([1.0, 1.0, 0.0], ignore_lateral=flag)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="ignore_lateral must be a bool"):
        drive.inverse_batch([[1.0, 1.0, 0.0]], ignore_lateral=flag)  # type: ignore[arg-type]
    assert drive.inverse([1.0, 1.0, 0.0], ignore_lateral=np.bool_(True)).tolist() == [20.0, 20.0]


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda d: d.forward(np.array([1 + 1j, 2.0])), "wheel_speeds"),
        (lambda d: d.odometry_step("0.1", 0.1), "d_left"),
        (lambda d: d.odometry_step(0.1, 0.1, method=3), "method"),
        (lambda d: d.odometry_step_batch(np.array([0.1 + 0j]), [0.1]), "d_left"),
        (lambda d: ticks_to_distance(np.array([1 + 1j]), ticks_per_rev=100, wheel_radius=0.1),
         "delta_ticks"),
        (lambda d: ticks_to_distance(1, ticks_per_rev="100", wheel_radius=0.1), "ticks_per_rev"),
        (lambda d: DiffDrive(track=True, wheel_radius=0.05), "track"),
        (lambda d: OmniDrive.three_wheel(wheel_radius=0.05 + 0j, base_radius=0.2), "wheel_radius"),
    ],
)
def test_complex_strings_and_bools_are_type_errors(call, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TypeError, match=name):
        call(DiffDrive(track=0.3, wheel_radius=0.05))


def test_tick_delta_shapes_that_do_not_broadcast_name_the_arguments() -> None:
    with pytest.raises(ValueError, match="previous and current must broadcast"):
        tick_delta(np.array([1, 2]), np.array([1, 2, 3]), bits=16)


@settings(max_examples=40, deadline=None)  # the first example may load compiled kernels
@given(LENGTHS, LENGTHS, st.floats(1e-6, 1e6), st.floats(-1e6, 1e6), st.floats(-1e6, 1e6))
def test_in_range_drives_never_produce_nan(
    track: float, radius: float, base: float, w0: float, w1: float
) -> None:
    diff = DiffDrive(track=track, wheel_radius=radius)
    twist = diff.forward([w0, w1])
    assert math.isfinite(twist.vx) and math.isfinite(twist.omega)
    assert np.isfinite(diff.inverse(twist)).all()
    step = diff.odometry_step(w0, w1)
    assert all(math.isfinite(v) for v in (step.x, step.y, step.theta))
    omni = OmniDrive.three_wheel(wheel_radius=radius, base_radius=base)
    assert np.isfinite(omni.jacobian).all() and np.isfinite(omni.forward_matrix).all()
    speeds = omni.inverse([w0, w1, w0])
    assert np.isfinite(speeds).all()
    back = omni.forward(speeds)
    assert all(math.isfinite(v) for v in (back.vx, back.vy, back.omega))


test_in_range_drives_never_produce_nan_thoroughly = slow_twin(
    test_in_range_drives_never_produce_nan, max_examples=100
)
