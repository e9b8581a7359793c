"""Review 46: compass, IMU and wheel encoders against their stated reading equations.

The references are written from the docstrings' equations and from the drives'
kinematics as the papers state them (a differential drive's
``(v ∓ ω D / 2) / r_{l,r}``; an omnidirectional wheel at angle ``θi``:
``(-sin θi vx + cos θi vy + L ω) / r``), never from navkit's code: wheel
rotations are exact products in mpmath, tick counts their exact floors, and
noise is checked by its sample mean and spread over many readings with a fixed
seed, to five standard errors.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from constant_controller import Constant, run_constant
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import (
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Robot,
    Simulation,
    WheelEncoders,
    World,
)

mpmath.mp.dps = 40


def wheel_speeds(drive: DiffDrive | OmniDrive, vx: float, vy: float, omega: float) -> list:
    """Each wheel's angular speed (mpmath, exact to 40 digits) for a body twist."""
    v, w = mpmath.mpf(vx), mpmath.mpf(omega)
    if isinstance(drive, DiffDrive):
        half = w * mpmath.mpf(drive.track) / 2
        return [(v - half) / mpmath.mpf(drive.left_radius),
                (v + half) / mpmath.mpf(drive.right_radius)]  # fmt: skip
    r, base = mpmath.mpf(drive.wheel_radius), mpmath.mpf(drive.base_radius)
    # The layouts as stated (not read back from the drive): 30/150/270° for three wheels.
    degrees = WHEEL_DEGREES[drive.n_wheels]
    return [(-mpmath.sin(a) * v + mpmath.cos(a) * mpmath.mpf(vy) + base * w) / r
            for a in (mpmath.radians(d) for d in degrees)]  # fmt: skip


def exact_ticks(rate_rad: mpmath.mpf, t: float, tpr: float) -> int:
    return int(mpmath.floor(rate_rad * mpmath.mpf(t) / (2 * mpmath.pi) * mpmath.mpf(tpr)))


WHEEL_DEGREES = {3: (30, 150, 270), 5: (10, 80, 170, 200, 300)}
DRIVES = {
    "diff, unequal radii": (DiffDrive(track=0.3, left_radius=0.05, right_radius=0.062),
                            (0.4, 0.0, 0.7)),
    "omni 30/150/270": (OmniDrive.three_wheel(wheel_radius=0.04, base_radius=0.2),
                        (0.3, -0.2, 0.5)),
    "omni, 5 uneven wheels": (OmniDrive(np.radians(WHEEL_DEGREES[5]),
                                        wheel_radius=0.035, base_radius=0.25),
                              (0.25, 0.3, -0.9)),
}  # fmt: skip


# ------------------------------------------------------------------------ encoders
@settings(max_examples=200, deadline=None)
@given(
    angle=st.one_of(
        st.floats(-1e6, 1e6, allow_nan=False),
        st.integers(-(10**5), 10**5).map(lambda n: n * 2.0 * math.pi),
        st.integers(-(10**6), 10**6).map(lambda n: n / 1024.0 * 2.0 * math.pi),
    ),
    tpr=st.one_of(st.sampled_from([1.0, 360.0, 1024.0, 4096.0, 1e9]), st.floats(1.0, 1e6)),
)
@example(angle=-5e-324, tpr=1.0)  # just below 0: tick -1, though angle / 2π is -0.0
@example(angle=5e-324, tpr=1.0)
def test_ticks_are_the_floor_of_angle_over_tick_angle(angle: float, tpr: float) -> None:
    """The count is floor(angle / (2π / tpr)), by the documented float boundary rule.

    Exact rationals: the count is the largest k with ``(k / tpr) * (2 * math.pi)``
    (each operation rounded) at most the angle; it differs from the floor of the
    exact real quotient only where the angle is within a few roundings of a
    boundary; n whole turns read n * tpr.
    """
    k = int(WheelEncoders(ticks_per_rev=tpr, bits=None).ticks(np.array([angle]))[0])
    two_pi = 2.0 * math.pi
    assert (k / tpr) * two_pi <= angle < ((k + 1) / tpr) * two_pi
    # The real quotient (π to 40 digits): the same floor, but within a few roundings
    # of a boundary, where the float rule decides.
    quotient = mpmath.mpf(angle) * mpmath.mpf(tpr) / (2 * mpmath.pi)
    exact = int(mpmath.floor(quotient))
    if k != exact:
        assert abs(k - exact) == 1
        assert abs(quotient - max(k, exact)) <= 8 * abs(quotient) * mpmath.mpf(2) ** -52
    turns = angle / two_pi
    # A whole number of turns only if it gives the angle back: the quotient of a
    # negative angle within a few subnormals of 0 underflows to -0.0, but the angle
    # lies below 0 and reads -1 (a fresh seed drew -5e-324: the tick below 0).
    if tpr == int(tpr) and turns == int(turns) and int(turns) * two_pi == angle:
        assert k == int(turns) * int(tpr)


@pytest.mark.parametrize("bits", [2, 8, 16, 52, 63])
def test_ticks_wrap_modulo_two_to_the_bits(bits: int) -> None:
    angles = np.array([-3.0, -0.001, 0.0, 1.0, 1e5, -1e5])
    plain = WheelEncoders(ticks_per_rev=4096, bits=None).ticks(angles)
    wrapped = WheelEncoders(ticks_per_rev=4096, bits=bits).ticks(angles)
    assert wrapped.tolist() == [int(p) % (1 << bits) for p in plain.tolist()]


@pytest.mark.parametrize("name", sorted(DRIVES))
def test_encoders_count_the_inverse_kinematics_wheel_rotation(name: str) -> None:
    """A constant twist: each counter reads floor(w_i t / 2π * tpr), w_i from the equations."""
    drive, twist = DRIVES[name]
    tpr = 4096.0
    robot = Robot(drive=drive, footprint=0.1, wheel_radius_error=0.03, wheel_slip=0.0,
                  encoders=WheelEncoders(ticks_per_rev=tpr, bits=None, rate=50.0))  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(*twist), 10.0, rate=100.0, control_rate=20.0)
    speeds = wheel_speeds(drive, *twist)
    readings = ctrl.readings(EncoderReading)
    assert len(readings) == 501  # 50 Hz from 0 s to 10 s
    for r in readings:
        assert r.ticks.tolist() == [exact_ticks(w, r.stamp, tpr) for w in speeds], r.stamp


@pytest.mark.parametrize("bits", [8, 16, 53, 63, 64])
def test_encoder_counters_in_the_loop_wrap_as_the_encoders_ticks(bits: int) -> None:
    """Wheels turning backwards too (omni): each reading is ``ticks`` of the wheel's rotation."""
    drive, twist = DRIVES["omni 30/150/270"]
    encoders = WheelEncoders(ticks_per_rev=4096, bits=bits, rate=50.0)
    robot = Robot(drive=drive, footprint=0.1, encoders=encoders)
    _, ctrl = run_constant(robot, Twist2D(*twist), 3.0, rate=100.0, control_rate=20.0)
    speeds = wheel_speeds(drive, *twist)
    assert any(w < 0 for w in speeds)
    for r in ctrl.readings(EncoderReading):
        counts = [exact_ticks(w, r.stamp, 4096.0) for w in speeds]
        want = [c % (1 << bits) if bits < 64 else c for c in counts]
        assert r.ticks.tolist() == want, r.stamp


def _long_run(duration: float) -> None:
    """Fast wheels on a fine encoder for ``duration`` s at 1 kHz: exact counts at every reading.

    Summed plainly, the wheel angles drifted by hundreds of ticks of a 10^9-tick
    encoder over 10^6 steps (issue of review 27); the count must stay the exact
    floor of the speed times the time.
    """
    drive = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.07)
    tpr = 1e9
    robot = Robot(drive=drive, footprint=0.1,
                  encoders=WheelEncoders(ticks_per_rev=tpr, bits=None, rate=1.0))  # fmt: skip
    twist = (1.3, 0.0, 0.9)
    _, ctrl = run_constant(robot, Twist2D(*twist), duration, rate=1000.0, control_rate=1.0)
    speeds = wheel_speeds(drive, *twist)
    readings = ctrl.readings(EncoderReading)
    assert len(readings) >= duration - 1
    for r in readings:
        got = r.ticks.tolist()
        want = [exact_ticks(w, r.stamp, tpr) for w in speeds]
        # The physics step is the float 1 / 1000 and a wheel speed a rounded float:
        # the exact rotation of those floats is within 1e-15 relative of the real one.
        slack = [int(abs(w * mpmath.mpf(r.stamp)) / (2 * mpmath.pi) * tpr * 1e-14) + 1
                 for w in speeds]  # fmt: skip
        assert all(abs(g - e) <= s for g, e, s in zip(got, want, slack, strict=True)), r.stamp


def test_long_run_encoder_counts_do_not_drift() -> None:
    _long_run(200.0)


@pytest.mark.slow
def test_very_long_run_encoder_counts_do_not_drift() -> None:
    _long_run(3000.0)


# --------------------------------------------------------------------------- compass
@settings(max_examples=200, deadline=None)
@given(
    yaw=st.floats(-1e3, 1e3),
    north=st.floats(-2.0 * math.pi, 2.0 * math.pi),
    bias=st.floats(-math.pi, math.pi),
    z=st.floats(-5.0, 5.0),
)
def test_compass_reading_equation(yaw: float, north: float, bias: float, z: float) -> None:
    """degrees(north - yaw + bias + noise z) mod 360, clockwise from north, in [0, 360)."""
    compass = Compass(noise=0.1, bias=bias, north=north)
    got = compass.heading_deg(yaw, z)
    assert 0.0 <= got < 360.0
    exact = mpmath.degrees(mpmath.mpf(north) - mpmath.mpf(yaw) + mpmath.mpf(bias)
                           + mpmath.mpf(0.1) * mpmath.mpf(z))  # fmt: skip
    diff = float((mpmath.mpf(got) - exact + 180) % 360 - 180)
    assert abs(diff) < 1e-9


def test_compass_in_the_loop_turns_clockwise_with_noise_about_the_truth() -> None:
    """Spinning counter-clockwise, the reading falls; noise statistics across the 0/360 seam.

    A robot facing north (the reading about 0°, where half the noisy readings
    wrap to 359°): the wrapped error's mean is within 5 standard errors of the
    bias, its standard deviation within 5 standard errors of the noise.
    """
    noise, bias = 0.05, 0.01
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1, encoders=None,
                  compass=Compass(noise=noise, bias=bias, rate=100.0))  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(0.0, 0.0, 0.0), 100.0, rate=100.0, control_rate=10.0)
    readings = np.array([r.heading_deg for r in ctrl.readings(CompassReading)])
    truth = 90.0  # facing +x, east, from (0, 0, 0)
    err = np.radians((readings - truth + 180.0) % 360.0 - 180.0)
    n = err.size
    assert n == 10_001
    assert abs(err.mean() - bias) < 5.0 * noise / math.sqrt(n)
    assert abs(err.std(ddof=1) - noise) < 5.0 * noise / math.sqrt(2.0 * n)
    # Facing north: readings on both sides of the seam, all in [0, 360).
    north = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1, encoders=None,
                  compass=Compass(noise=noise, rate=100.0))  # fmt: skip
    ctrl = Constant(Twist2D(0.0, 0.0, 0.0))
    Simulation(World(), north, ctrl, start=(0.0, 0.0, math.pi / 2), duration=10.0, rate=100.0,
               control_rate=10.0).run()  # fmt: skip
    seam = np.array([r.heading_deg for r in ctrl.readings(CompassReading)])
    assert np.all((seam >= 0.0) & (seam < 360.0))
    assert 0.3 < float(np.mean(seam > 180.0)) < 0.7
    # Spinning at +0.5 rad/s (counter-clockwise): the noise-free reading is 90° - 0.5 t.
    spin = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1, encoders=None,
                 compass=Compass(rate=20.0))  # fmt: skip
    _, ctrl = run_constant(spin, Twist2D(0.0, 0.0, 0.5), 20.0, rate=100.0, control_rate=20.0)
    for r in ctrl.readings(CompassReading):
        want = math.degrees(math.pi / 2 - 0.5 * r.stamp) % 360.0
        assert abs((r.heading_deg - want + 180.0) % 360.0 - 180.0) < 1e-9


# ------------------------------------------------------------------------------- IMU
@pytest.mark.parametrize("name", sorted(DRIVES))
def test_imu_reads_yaw_rate_and_the_centripetal_acceleration(name: str) -> None:
    """Holding a twist: gyro ω, accelerometer (v̇x - ω vy, v̇y + ω vx) = (-ω vy, ω vx)."""
    drive, (vx, vy, w) = DRIVES[name]
    robot = Robot(drive=drive, footprint=0.1, imu=Imu(rate=100.0))
    _, ctrl = run_constant(robot, Twist2D(vx, vy, w), 5.0, rate=100.0, control_rate=20.0)
    readings = ctrl.readings(ImuReading)
    assert len(readings) == 501
    for r in readings[2:]:  # after the first step's jump to speed
        assert r.yaw_rate == pytest.approx(w, abs=1e-12)
        assert r.acceleration_x == pytest.approx(-w * vy, abs=1e-12)
        assert r.acceleration_y == pytest.approx(w * vx, abs=1e-12)


def test_imu_reads_the_physics_steps_own_acceleration_and_yaw_rate() -> None:
    """Wheels ramping at α: the documented step values (the Imu docstring's second paragraph).

    A straight ramp from rest reads r α / 2 at its first step and at the step
    after it ends, r α between, 0 after; while the robot also turns, every
    sample's yaw rate is the trace's heading change over the step, and the
    forward ``v̇`` samples times ``dt`` sum to the final speed (the trace's
    displacement over the last step over ``dt``).
    """
    alpha, r_wheel, dt = 4.0, 0.05, 0.01
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=r_wheel), footprint=0.1,
                  max_wheel_acceleration=alpha, imu=Imu(rate=100.0))  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(0.5, 0.0, 0.0), 4.0, rate=100.0, control_rate=20.0)
    # 0.5 m/s is 10 rad/s of wheel: 2.5 s of ramp, steps 1 to 250.
    ax = {round(r.stamp / dt): r.acceleration_x for r in ctrl.readings(ImuReading)}
    assert ax[0] == 0.0
    assert ax[1] == pytest.approx(r_wheel * alpha / 2.0, rel=1e-9)
    for i in range(2, 251):
        assert ax[i] == pytest.approx(r_wheel * alpha, rel=1e-9), i
    assert ax[251] == pytest.approx(r_wheel * alpha / 2.0, rel=1e-9)
    assert all(abs(ax[i]) < 1e-9 for i in range(252, 400))
    # Turning while ramping (the right wheel only): yaw rate = Δθ / dt of each step.
    turn = Robot(drive=DiffDrive(track=0.3, wheel_radius=r_wheel), footprint=0.1,
                 max_wheel_acceleration=alpha, imu=Imu(rate=100.0))  # fmt: skip
    trace, ctrl = run_constant(turn, Twist2D(0.25, 0.0, 0.25 / 0.15), 3.0, rate=100.0,
                               control_rate=20.0)  # fmt: skip
    readings = ctrl.readings(ImuReading)
    heading = np.unwrap(trace.poses[:, 2])
    for r in readings[1:]:
        i = round(r.stamp / dt)
        assert r.yaw_rate == pytest.approx((heading[i] - heading[i - 1]) / dt, abs=1e-9)
    i_last = round(readings[-1].stamp / dt)
    # The last step's arc: its chord over sin(h) / h of the half turn h, over dt.
    half = 0.5 * (heading[i_last] - heading[i_last - 1])
    chord = math.hypot(*(trace.poses[i_last, :2] - trace.poses[i_last - 1, :2]))
    speed = chord * half / math.sin(half) / dt
    # No sideways speed: ax is v̇x alone.
    assert sum(r.acceleration_x for r in readings) * dt == pytest.approx(speed, rel=1e-12)


def test_imu_noise_and_bias_statistics() -> None:
    """Bias plus white Gaussian noise per sample and axis (10^4 samples, 5 standard errors)."""
    g_noise, g_bias, a_noise, a_bias = 0.01, 0.003, 0.2, -0.1
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1, encoders=None,
                  imu=Imu(gyro_noise=g_noise, gyro_bias=g_bias, accel_noise=a_noise,
                          accel_bias=a_bias, rate=100.0))  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(0.0, 0.0, 0.0), 100.0, rate=100.0, control_rate=10.0)
    values = np.array([(r.yaw_rate, r.acceleration_x, r.acceleration_y)
                       for r in ctrl.readings(ImuReading)])  # fmt: skip
    n = values.shape[0]
    assert n == 10_001
    for col, mean, sd in ((0, g_bias, g_noise), (1, a_bias, a_noise), (2, a_bias, a_noise)):
        assert abs(values[:, col].mean() - mean) < 5.0 * sd / math.sqrt(n)
        assert abs(values[:, col].std(ddof=1) - sd) < 5.0 * sd / math.sqrt(2.0 * n)
    # Independent axes (white, per axis): correlations within 5 / sqrt(n).
    corr = np.corrcoef(values.T)
    assert np.all(np.abs(corr[np.triu_indices(3, 1)]) < 5.0 / math.sqrt(n))


# ------------------------------------------------------------------ sample schedules
@pytest.mark.parametrize(("physics", "sensor"), [(100.0, 30.0), (100.0, 7.0), (30.0, 30.0),
                                                 (250.0, 100.0 / 3.0)])  # fmt: skip
def test_each_sensor_samples_at_the_first_step_at_or_after_its_times(
    physics: float, sensor: float
) -> None:
    """Sample k is taken at the first step i with i / rate >= k / sensor_rate (exact rationals)."""
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1,
                  encoders=WheelEncoders(rate=sensor), compass=Compass(rate=sensor),
                  imu=Imu(rate=sensor))  # fmt: skip
    _, ctrl = run_constant(robot, Twist2D(0.1, 0.0, 0.1), 3.0, rate=physics,
                           control_rate=physics)  # fmt: skip
    rate, f = Fraction(physics), Fraction(sensor)
    for kind in (EncoderReading, CompassReading, ImuReading):
        stamps = [r.stamp for r in ctrl.readings(kind)]
        want = []
        for k in range(len(stamps)):
            i = math.ceil((Fraction(k) / f - Fraction(1, 10**9)) * rate)
            want.append(float(Fraction(max(i, 0)) / rate))
        assert stamps == want, kind.__name__
        assert len(stamps) >= math.floor(3.0 * sensor)
