"""OmniOdometry (compass heading) and DiffOdometry (encoder ticks) against exact motion."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry, OmniOdometry, compass_to_yaw
from navkit.geometry import Pose2D, Twist2D, angle_diff, integrate, rollout
from navkit.kinematics import DiffDrive, OmniDrive

OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


def omni_log(twist: Twist2D, dt: float, steps: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wheel increments, true yaws and the exact trajectory of a constant twist."""
    inc = np.tile(OMNI.inverse(twist) * dt, (steps, 1))
    truth = rollout(Pose2D(0.0, 0.0, 0.0), np.tile(twist.as_array(), (steps, 1)), dt)
    return inc, truth[1:, 2].copy(), truth


def test_omni_translation_is_exact_in_compass_frame() -> None:
    odo = OmniOdometry(OMNI, pose=Pose2D(1.0, 2.0, math.pi / 2))
    pose = odo.update(OMNI.inverse(Twist2D(0.3, -0.4, 0.0)) * 2.0, math.pi / 2)
    # 0.6 m forward (+y in the world) and 0.8 m to the right (+x in the world).
    assert pose.x == pytest.approx(1.8)
    assert pose.y == pytest.approx(2.6)
    assert pose.theta == pytest.approx(math.pi / 2)


def test_omni_circle_matches_exact_motion_with_mid_step_heading() -> None:
    twist = Twist2D(0.5, 0.2, 0.8)
    inc, yaws, truth = omni_log(twist, dt=0.02, steps=400)  # 6.4 s, almost a full turn
    traj = OmniOdometry(OMNI).update_batch(inc, yaws)
    err = np.hypot(*(traj[:, :2] - truth[:, :2]).T)
    # Mid-step heading: the per-step error is the sinc(ω dt / 2) factor, ~1e-5 m over 400 steps.
    assert err.max() < 2e-5
    # The end-of-step heading (first order) would be off by millimetres: the mid-step rule matters.
    c, s = np.cos(yaws), np.sin(yaws)
    body = OMNI.forward_batch(inc)
    first_order = np.cumsum(
        np.column_stack((c * body[:, 0] - s * body[:, 1], s * body[:, 0] + c * body[:, 1])), axis=0
    )
    first_err = np.hypot(*(first_order - truth[1:, :2]).T)
    assert first_err.max() > 100 * err.max()


def test_omni_heading_comes_from_compass_not_wheels() -> None:
    # The wheels report a spin (e.g. slipping), the compass says the robot did not turn.
    inc = OMNI.inverse(Twist2D(1.0, 0.0, 2.0)) * 0.1
    pose = OmniOdometry(OMNI).update(inc, yaw=compass_to_yaw(0.0))
    assert pose.theta == 0.0
    assert pose.x == pytest.approx(0.1)
    assert pose.y == pytest.approx(0.0, abs=1e-15)


def test_omni_update_equals_update_batch() -> None:
    inc, yaws, _ = omni_log(Twist2D(0.4, 0.1, -0.6), dt=0.05, steps=50)
    a = OmniOdometry(OMNI)
    stepwise = np.array([a.update(row, yaw).as_array() for row, yaw in zip(inc, yaws, strict=True)])
    b = OmniOdometry(OMNI)
    np.testing.assert_allclose(b.update_batch(inc, yaws)[1:], stepwise, atol=1e-12)
    assert b.pose.x == pytest.approx(a.pose.x)


def test_omni_pose_accepts_a_sequence_and_is_keyword_only() -> None:
    inc = OMNI.inverse(Twist2D(0.3, -0.4, 0.0)) * 2.0
    a = OmniOdometry(OMNI, pose=[1.0, 2.0, math.pi / 2]).update(inc, math.pi / 2)
    b = OmniOdometry(OMNI, pose=Pose2D(1.0, 2.0, math.pi / 2)).update(inc, math.pi / 2)
    assert a == b
    with pytest.raises(TypeError, match="positional"):
        OmniOdometry(OMNI, Pose2D(1.0, 2.0, 0.0))  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="pose must be a Pose2D"):
        OmniOdometry(OMNI, pose=3.0)


def test_omni_bad_input() -> None:
    odo = OmniOdometry(OMNI)
    with pytest.raises(ValueError, match="wheel_increments"):
        odo.update([0.1, 0.2], 0.0)
    with pytest.raises(ValueError, match="yaw"):
        odo.update([0.1, 0.2, 0.3], math.nan)
    with pytest.raises(ValueError, match="yaws"):
        odo.update_batch(np.zeros((3, 3)), np.zeros(2))
    with pytest.raises(TypeError, match="OmniDrive"):
        OmniOdometry(DiffDrive(track=0.3, wheel_radius=0.05))  # type: ignore[arg-type]
    assert odo.pose == Pose2D(0.0, 0.0, 0.0)


DIFF = DiffDrive(track=0.4, wheel_radius=0.05)
TPR = 2048


def ticks_for(
    distance_left: float, distance_right: float, drive: DiffDrive = DIFF
) -> tuple[int, int]:
    return (
        round(distance_left / (2 * math.pi * drive.left_radius) * TPR),
        round(distance_right / (2 * math.pi * drive.right_radius) * TPR),
    )


def test_diff_wraparound_16_bit() -> None:
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    odo.update(65000, 64000)
    pose = odo.update(65000 + TPR - 65536, 64000 + TPR - 65536)  # both counters wrapped
    assert pose.x == pytest.approx(2 * math.pi * 0.05)
    assert pose.y == 0.0 and pose.theta == 0.0
    no_bits = DiffOdometry(DIFF, ticks_per_rev=TPR)
    no_bits.update(65000, 64000)
    assert no_bits.update(65000 + TPR - 65536, 64000 + TPR - 65536).x < -1.0


@pytest.mark.parametrize("method", ["arc", "midpoint", "first_order"])
def test_diff_circle(method: str) -> None:
    """Constant wheel speeds: the arc mode is exact, the others converge with the step."""
    steps = 200
    dl_step, dr_step = 0.004, 0.006  # per step; ω·D = dr - dl
    left = np.cumsum(np.full(steps, ticks_for(dl_step, dr_step)[0]))
    right = np.cumsum(np.full(steps, ticks_for(dl_step, dr_step)[1]))
    left = np.concatenate(([0], left))
    right = np.concatenate(([0], right))
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, method=method)  # type: ignore[arg-type]
    traj = odo.update_batch(left, right)
    # Ground truth: the same per-step wheel distances (after tick rounding) as an exact twist.
    d_l = left[1] * 2 * math.pi * 0.05 / TPR
    d_r = right[1] * 2 * math.pi * 0.05 / TPR
    twist = Twist2D(0.5 * (d_l + d_r), 0.0, (d_r - d_l) / DIFF.track)
    truth = rollout(Pose2D(0.0, 0.0, 0.0), np.tile(twist.as_array(), (steps, 1)), 1.0)
    err = np.hypot(*(traj[:, :2] - truth[:, :2]).T).max()
    limits = {"arc": 1e-12, "midpoint": 1e-6, "first_order": 5e-2}
    assert err < limits[method]
    if method == "first_order":
        assert err > 1e-3  # Euler really is worse
    np.testing.assert_allclose(angle_diff(traj[:, 2], truth[:, 2]), 0.0, atol=1e-12)


def test_diff_unequal_radii_go_straight() -> None:
    drive = DiffDrive(track=0.4, left_radius=0.05, right_radius=0.06)
    odo = DiffOdometry(drive, ticks_per_rev=TPR)
    odo.update(0, 0)
    # The smaller left wheel turns 6/5 as often for the same distance: straight line.
    pose = odo.update(1200 * 10, 1000 * 10)
    assert pose.theta == pytest.approx(0.0, abs=1e-12)
    assert pose.x == pytest.approx(10 * 2 * math.pi * 0.06 * 1000 / TPR)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(-300, 300), st.integers(-300, 300)), min_size=1, max_size=30))
def test_diff_update_equals_update_batch_and_matches_composition(
    steps: list[tuple[int, int]],
) -> None:
    counts = np.cumsum(np.array([(0, 0), *steps]), axis=0)
    counts = np.mod(counts + 40000, 65536)  # a 16-bit counter that starts near the middle
    a = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    stepwise = np.array([a.update(int(left), int(right)).as_array() for left, right in counts])
    b = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    traj = b.update_batch(counts[:, 0], counts[:, 1])
    np.testing.assert_allclose(traj[:, :2], stepwise[:, :2], atol=1e-9)
    np.testing.assert_allclose(angle_diff(traj[:, 2], stepwise[:, 2]), 0.0, atol=1e-9)
    # Reference: compose each step's exact-arc motion with Pose2D.
    pose = Pose2D(0.0, 0.0, 0.0)
    for dl_ticks, dr_ticks in steps:
        d_l = dl_ticks * 2 * math.pi * 0.05 / TPR
        d_r = dr_ticks * 2 * math.pi * 0.05 / TPR
        pose = integrate(pose, Twist2D(0.5 * (d_l + d_r), 0.0, (d_r - d_l) / DIFF.track), 1.0)
    assert traj[-1, 0] == pytest.approx(pose.x, abs=1e-9)
    assert traj[-1, 1] == pytest.approx(pose.y, abs=1e-9)
    # The same with DiffDrive.odometry_step: relative motions composed onto the pose.
    stepped = Pose2D(0.0, 0.0, 0.0)
    for dl_ticks, dr_ticks in steps:
        d_l = dl_ticks * 2 * math.pi * 0.05 / TPR
        d_r = dr_ticks * 2 * math.pi * 0.05 / TPR
        stepped = stepped.compose(DIFF.odometry_step(d_l, d_r))
    assert traj[-1, 0] == pytest.approx(stepped.x, abs=1e-9)
    assert traj[-1, 1] == pytest.approx(stepped.y, abs=1e-9)
    assert angle_diff(traj[-1, 2], stepped.theta) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("bits", [32, 64, None])
def test_diff_update_batch_takes_uint64_readings_after_earlier_ones(bits: int | None) -> None:
    """Later batches continue from the last reading whatever the readings' dtype.

    Joining the last reading (a Python int) to uint64 readings used to promote
    them to float64, which the second batch then refused.
    """
    readings = np.array([[10, 10], [20, 30], [30, 40], [45, 41]], dtype=np.uint64)
    whole = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=bits)
    want = whole.update_batch(readings[:, 0].astype(np.int64), readings[:, 1].astype(np.int64))
    split = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=bits)
    split.update_batch(readings[:2, 0], readings[:2, 1])
    got = split.update_batch(readings[2:, 0], readings[2:, 1])
    np.testing.assert_allclose(got, want[2:], rtol=1e-12, atol=1e-15)  # sums split in two


def test_diff_update_batch_wraps_from_the_top_of_a_64_bit_counter() -> None:
    stepwise = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=64)
    batch = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=64)
    for odo in (stepwise, batch):
        odo.update(2**64 - 1, 0)
    poses = [stepwise.update(5, 5).as_array(), stepwise.update(6, 6).as_array()]
    np.testing.assert_allclose(batch.update_batch([5, 6], [5, 6]), poses, atol=1e-15)
    # 7 left ticks (2**64 - 1 -> 5 -> 6) against 6 right ones: one tick of turn.
    assert poses[-1][2] == pytest.approx(-2 * math.pi * 0.05 / TPR / DIFF.track)


def test_diff_bad_input() -> None:
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    with pytest.raises(TypeError, match="left_ticks"):
        odo.update_batch([0.5], [1])
    with pytest.raises(ValueError, match="equal length"):
        odo.update_batch([1, 2], [1])
    with pytest.raises(ValueError, match=r"left_ticks holds readings outside .* 16-bit"):
        odo.update_batch([70000], [1])
    with pytest.raises(ValueError, match=r"right_ticks holds readings outside .* 16-bit"):
        odo.update(1, -40000)
    with pytest.raises(ValueError, match="bits must"):
        DiffOdometry(DIFF, ticks_per_rev=TPR, bits=1)
    with pytest.raises(ValueError, match="ticks_per_rev"):
        DiffOdometry(DIFF, ticks_per_rev=0)
    with pytest.raises(ValueError, match="method"):
        DiffOdometry(DIFF, ticks_per_rev=TPR, method="euler")  # type: ignore[arg-type]
    for bad in (["arc"], np.array(["arc"]), None):
        with pytest.raises(TypeError, match="method must be one of"):
            DiffOdometry(DIFF, ticks_per_rev=TPR, method=bad)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="positional"):
        DiffOdometry(DIFF, TPR)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="pose must be a Pose2D"):
        DiffOdometry(DIFF, ticks_per_rev=TPR, pose="origin")
    assert odo.pose == Pose2D(0.0, 0.0, 0.0)
    odo.update(5, 5)
    odo.reset(Pose2D(1.0, 1.0, 1.0))
    assert odo.update(100, 100) == Pose2D(1.0, 1.0, 1.0)
    odo.reset([2.0, 3.0, 0.5])
    assert odo.pose == Pose2D(2.0, 3.0, 0.5)
    assert odo.update(7, 9) == Pose2D(2.0, 3.0, 0.5)  # the first reading after reset latches
    with pytest.raises(TypeError, match="pose must be a Pose2D"):
        odo.reset(1.0)
    with pytest.raises(ValueError, match="pose"):
        odo.reset([1.0, 2.0])
    assert odo.pose == Pose2D(2.0, 3.0, 0.5)  # a bad reset changes nothing


def test_diff_pose_accepts_a_sequence() -> None:
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, pose=[1.0, -1.0, math.pi / 2])
    odo.update(0, 0)
    pose = odo.update(TPR, TPR)  # one wheel turn forward, facing +y
    assert pose.x == pytest.approx(1.0, abs=1e-12)
    assert pose.y == pytest.approx(-1.0 + 2 * math.pi * 0.05)


def test_diff_readings_beyond_64_bits_are_out_of_range_and_change_nothing() -> None:
    # They used to be refused as a TypeError ("got object"), not as out of range.
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    odo.update(0, 0)
    for huge in (2**64, 2**70, -(2**70)):
        with pytest.raises(ValueError, match=r"right_ticks holds readings outside .* 16-bit"):
            odo.update(0, huge)
        with pytest.raises(ValueError, match=r"left_ticks holds readings outside .* 16-bit"):
            odo.update_batch([1, huge], [1, 2])
    unbounded = DiffOdometry(DIFF, ticks_per_rev=TPR)
    with pytest.raises(ValueError, match=r"left_ticks holds readings outside .* 64-bit"):
        unbounded.update_batch([2**64], [0])
    assert odo.pose == unbounded.pose == Pose2D(0.0, 0.0, 0.0)
    assert odo.update(TPR, TPR).x == pytest.approx(2 * math.pi * 0.05)  # still from (0, 0)


def test_diff_update_batch_takes_empty_lists_and_mixed_signed_unsigned_readings() -> None:
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=64)
    empty = odo.update_batch([], [])  # float64 to NumPy
    assert empty.shape == (0, 3)
    # 2**64 - 1 and -1 are the same 64-bit reading; NumPy has no integer dtype for both.
    traj = odo.update_batch([2**64 - 1, -1, TPR - 1], [-1, 2**64 - 1, TPR - 1])
    want = np.zeros((3, 3))
    want[2, 0] = 2 * math.pi * 0.05
    np.testing.assert_allclose(traj, want)
    assert odo.update(2 * TPR - 1, 2 * TPR - 1).x == pytest.approx(4 * math.pi * 0.05)


@pytest.mark.parametrize("readings", [[False, TPR], (0, True), [np.True_, 5]])
def test_diff_refuses_booleans_mixed_into_lists(readings: object) -> None:
    # NumPy converts [False, 2048] to int64 [0, 2048]: a flag read as a counter value.
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=16)
    with pytest.raises(TypeError, match=r"left_ticks .* bool"):
        odo.update_batch(readings, [0, TPR])  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"right_ticks .* bool"):
        odo.update_batch([0, TPR], readings)  # type: ignore[arg-type]
    assert odo.pose == Pose2D(0.0, 0.0, 0.0)
    assert odo.update(0, 0) == Pose2D(0.0, 0.0, 0.0)  # nothing was latched


@pytest.mark.parametrize(
    ("bits", "error"),
    [(True, TypeError), (np.True_, TypeError), (16.0, TypeError), ("16", TypeError),
     (1, ValueError), (65, ValueError)],
)  # fmt: skip
def test_diff_bits_errors(bits: object, error: type[Exception]) -> None:
    with pytest.raises(error, match="bits must"):
        DiffOdometry(DIFF, ticks_per_rev=TPR, bits=bits)  # type: ignore[arg-type]
    # A NumPy integer is a width like any other: 65535 -> 1 is two ticks forward.
    odo = DiffOdometry(DIFF, ticks_per_rev=TPR, bits=np.int8(16))  # type: ignore[arg-type]
    odo.update(65535, 65535)
    assert odo.update(1, 1).x == pytest.approx(2 / TPR * 2 * math.pi * DIFF.left_radius)


@pytest.mark.parametrize(
    ("left", "right", "name"),
    [
        ([5], 0, "left_ticks"),
        ((5,), 0, "left_ticks"),
        (0, np.array([5]), "right_ticks"),
        (np.array([5, 6]), 0, "left_ticks"),
    ],
)
def test_diff_odometry_update_refuses_sequences_as_not_integers(
    left: object, right: object, name: str
) -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=16)
    odo.update(10, 10)
    with pytest.raises(TypeError, match=f"{name} must be one integer counter reading"):
        odo.update(left, right)  # type: ignore[arg-type]
    assert odo.update(1010, 1010).x == pytest.approx(2 * np.pi * 0.1)  # unchanged, still latched


def test_diff_odometry_update_takes_zero_dimensional_readings() -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=16)
    odo.update(np.array(65000), np.uint16(65000))  # type: ignore[arg-type]
    assert odo.update(np.array(464), 464).x == pytest.approx(2 * np.pi * 0.1)  # type: ignore[arg-type]
