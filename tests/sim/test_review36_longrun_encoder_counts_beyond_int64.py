"""Simulated encoder counts past the int64 range wrap as a 64-bit counter (review 36, long runs).

The simulator counts each wheel's ticks in float64 and wrapped counters of up to 52
bits there; wider ones (53 to 64 bits) and counters that never wrap (``bits=None``)
were cast to int64 as they were. A long run of fast wheels on a fine encoder passes
2**63 ticks within the documented ranges (1e9 ticks a turn, ``max_wheel_speed`` up to
1e5 rad/s, ``duration * rate`` up to 1e7 steps: 5.8e10 rad of wheel rotation, 6.7
days at 1e5 rad/s), and from there NumPy's cast of the float count gave INT64_MIN (0
once masked to 53..63 bits) at every reading, with a RuntimeWarning "invalid value
encountered in cast" each time: the estimators read a wheel standing still. The
counts are now reduced modulo 2**64 first (exactly: ``fmod`` of a float is exact),
so every counter reads as a real 64-bit or narrower counter wraps, and
``tick_delta`` (or ``DiffOdometry``) decodes the steps across the boundary.

The oracle is exact arithmetic on the commanded motion: a wheel command held from
the start with unlimited acceleration turns the wheel by ``speed * t`` (the
simulator's float sum of it is within a few roundings), so the reading at ``t`` is
``floor(speed * t / 2π * ticks_per_rev)`` modulo ``2**bits``, to within the float
rounding of the angle's sum (a few thousand ticks of a 1e9-tick encoder at 1e11 rad,
against the 1e18 ticks the cast was off by).
"""

from __future__ import annotations

import functools
import math
import warnings
from fractions import Fraction

import numpy as np
import pytest
from shapely.geometry import box

from navkit.estimation import DiffOdometry, PlanarFusion
from navkit.kinematics import DiffDrive, tick_delta
from navkit.sim import EncoderReading, Reading, Robot, Simulation, WheelEncoders, World

TPR = 1e9  # the largest ticks_per_rev WheelEncoders takes
WHEEL_SPEED = 1e5  # rad/s, the largest finite max_wheel_speed a Robot takes
# Spinning on the spot: omega * (track / 2) / radius is the wheels' speed.
DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)
OMEGA = WHEEL_SPEED * 0.05 / 0.15
RATE = 0.002  # Hz: one physics step, control step and reading every 500 s
DURATION = 1.5e6  # s: 1.5e11 rad of wheel rotation, past 2**63 and 2**64 ticks
# Float rounding of the wheel angle's sum, in ticks: a few spacings of 1.5e11 rad
# (3e-5 rad each, 4800 ticks at 1e9 ticks a turn).
SLACK = 10**5


class _Readings:
    """An Estimator keeping every encoder reading."""

    pose = None

    def __init__(self) -> None:
        self.readings: list[EncoderReading] = []

    def observe(self, t: float, reading: Reading) -> None:
        if isinstance(reading, EncoderReading):
            self.readings.append(reading)


def _spin(obs: object) -> tuple[float, float, float]:
    return (0.0, 0.0, OMEGA)


@functools.cache  # one run per width, shared by the tests (they only read it)
def _run(bits: int | None) -> list[EncoderReading]:
    robot = Robot(
        drive=DRIVE,
        footprint=0.15,
        max_wheel_speed=WHEEL_SPEED,
        encoders=WheelEncoders(ticks_per_rev=TPR, bits=bits, rate=RATE),
    )
    keep = _Readings()
    sim = Simulation(World(box(-5.0, -5.0, 5.0, 5.0).exterior), robot, _spin,
                     start=(0.0, 0.0, 0.0), estimator=keep, rate=RATE, control_rate=RATE,
                     duration=DURATION)  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # NumPy's "invalid value encountered in cast"
        sim.run()
    return keep.readings


def _exact_count(t: float, sign: int) -> int:
    """The tick count of a wheel turning at ``sign * WHEEL_SPEED`` since 0 s, at ``t``."""
    turns = Fraction(sign) * Fraction(WHEEL_SPEED) * Fraction(t) / (2 * Fraction(math.pi))
    return math.floor(turns * Fraction(TPR))


def _off_by(reading: int, exact: int, bits: int) -> int:
    """The signed difference of two counts modulo ``2**bits``."""
    period = 1 << bits
    diff = (reading - exact) % period
    return diff - period if diff >= period // 2 else diff


@pytest.mark.parametrize("bits", [None, 64, 63, 60, 53, 52])
def test_counts_past_the_int64_range_read_as_the_counter_wraps(bits: int | None) -> None:
    readings = _run(bits)
    assert len(readings) == 3001  # one every 500 s from 0 s to 1.5e6 s
    # The right wheel's count passes 2**63 at about 5.8e5 s and 2**64 at 1.16e6 s.
    assert _exact_count(readings[-1].stamp, 1) > 2**64
    width = 64 if bits is None else bits
    for r in readings:
        left, right = (int(v) for v in r.ticks)
        if bits is not None and bits < 64:
            assert 0 <= left < 2**bits and 0 <= right < 2**bits  # unsigned readings
        else:
            assert -(2**63) <= left < 2**63 and -(2**63) <= right < 2**63
        assert abs(_off_by(right, _exact_count(r.stamp, 1), width)) < SLACK
        assert abs(_off_by(left, _exact_count(r.stamp, -1), width)) < SLACK


@pytest.mark.parametrize("bits", [None, 64, 60])
def test_tick_delta_decodes_the_steps_across_the_int64_range(bits: int | None) -> None:
    # 500 s at 1e5 rad/s is 8e15 ticks a reading: within half of a 55-bit or wider
    # counter's range, so every step decodes whatever the count.
    readings = _run(bits)
    ticks = np.array([r.ticks for r in readings])
    steps = tick_delta(ticks[:-1], ticks[1:], bits=64 if bits is None else bits)
    per_reading = WHEEL_SPEED * 500.0 / (2 * math.pi) * TPR
    assert np.abs(steps[:, 1] - per_reading).max() < SLACK
    assert np.abs(steps[:, 0] + per_reading).max() < SLACK


# The simulator's own estimators decode the readings across the int64 range too: the
# wrapped step of a 64-bit counter was taken as a plain difference, a jump of -2**64
# ticks (5.8e9 m on these wheels) at the reading that crossed it; and a DiffOdometry of
# 64 bits fed a narrower counter's readings, unwrapped, was given sums past the int64
# range, which it refuses (ValueError mid-run). Readings every 500 s of a straight drive
# at 5000 m/s (both wheels at 1e5 rad/s) decode to the same steps whatever the width
# (8e15 ticks a step, within half of a 60-bit range), so the estimates are the same.


def _straight(bits: int | None, estimator: object) -> np.ndarray:
    robot = Robot(
        drive=DRIVE,
        footprint=0.15,
        max_wheel_speed=WHEEL_SPEED,
        encoders=WheelEncoders(ticks_per_rev=TPR, bits=bits, rate=RATE),
    )
    twist = DRIVE.forward(np.array([WHEEL_SPEED, WHEEL_SPEED]))
    sim = Simulation(World(), robot, lambda obs: twist, start=(0.0, 0.0, 0.0),
                     estimator=estimator, rate=RATE, control_rate=RATE,
                     duration=DURATION)  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        trace = sim.run()
    assert trace.poses[-1, 0] == pytest.approx(5000.0 * DURATION)  # 7.5e9 m, past 2**64 ticks
    return trace.estimates


@pytest.mark.parametrize("bits", [None, 64])
def test_a_fusion_estimator_reads_64_bit_counters_across_the_int64_range(
    bits: int | None,
) -> None:
    wide = _straight(bits, PlanarFusion(t0=0.0))
    narrow = _straight(60, PlanarFusion(t0=0.0))
    np.testing.assert_array_equal(wide, narrow)


@pytest.mark.parametrize("own", [None, 64])
def test_a_64_bit_diff_odometry_reads_a_narrower_counter_past_the_int64_range(
    own: int | None,
) -> None:
    wide = _straight(60, DiffOdometry(DRIVE, ticks_per_rev=TPR, bits=own))
    narrow = _straight(60, DiffOdometry(DRIVE, ticks_per_rev=TPR, bits=60))
    np.testing.assert_array_equal(wide, narrow)
    assert wide[-1, 0] == pytest.approx(5000.0 * DURATION)
