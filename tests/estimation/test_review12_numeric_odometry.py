"""DiffOdometry.update_batch keeps its heading to rounding over long logs.

The batch heading used to be ``theta0 + np.cumsum(turns)``: every partial sum was
rounded at the size of the running total, so a robot that keeps turning (10^4 rad
after 10^6 readings) ended about 2e-7 rad off, while stepping reading by reading
(wrapped each time) is off by at most half an ulp of π per reading. The references
are exact: ``fractions.Fraction`` sums of the float heading changes the odometry
itself computes, reduced by the float ``2 * math.pi`` as :func:`wrap_angle` reduces.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive, ticks_to_distance

DRIVE = DiffDrive(track=0.5, wheel_radius=0.1)
TICKS_PER_REV = 1000
TWO_PI = Fraction(2 * math.pi)  # the float 2π wrap_angle reduces by


def turns(left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """Heading change of each reading after the first, as the odometry computes it."""
    d_left, d_right = (
        ticks_to_distance(np.diff(ticks), ticks_per_rev=TICKS_PER_REV, wheel_radius=0.1)
        for ticks in (left, right)
    )
    return DRIVE.odometry_step_batch(d_left, d_right)[:, 2]


def heading_error(theta: float, theta0: float, total: Fraction) -> float:
    """|theta - (theta0 + total)| in rad, up to a multiple of the float 2π."""
    err = Fraction(theta) - Fraction(theta0) - total
    err -= round(err / TWO_PI) * TWO_PI
    return float(abs(err))


def test_spinning_in_place_for_200000_readings_keeps_the_heading() -> None:
    n = 200_000
    left = -7 * np.arange(n + 1, dtype=np.int64)
    right = 7 * np.arange(n + 1, dtype=np.int64)
    theta0 = 0.3
    out = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV, pose=(0.0, 0.0, theta0)).update_batch(
        left, right
    )
    turn = turns(left, right)
    assert np.all(turn == turn[0])  # about 0.0176 rad a reading: 3,500 rad in all
    # Stepping reading by reading rounds at most half an ulp of π a reading (4.4e-11
    # rad in all); the running sum of NumPy's cumsum was 1.2e-8 rad off here.
    bound = n * math.ulp(math.pi) / 2
    assert heading_error(float(out[-1, 2]), theta0, n * Fraction(float(turn[0]))) <= bound
    assert heading_error(float(out[n // 2, 2]), theta0, n // 2 * Fraction(float(turn[0]))) <= bound
    assert np.all((-math.pi < out[:, 2]) & (out[:, 2] <= math.pi))


def test_a_long_circle_in_batch_equals_reading_by_reading() -> None:
    # 60,000 readings on a circle of 0.3 m radius: 2,900 laps.
    n = 60_000
    left = 3 * np.arange(n + 1, dtype=np.int64)
    right = 10 * np.arange(n + 1, dtype=np.int64)
    batch = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV).update_batch(left, right)
    online = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV)
    for a, b in zip(left.tolist(), right.tolist(), strict=True):
        pose = online.update(a, b)
    # Both within n half-ulps of π of the exact heading. The positions (|x|, |y| below
    # 0.6 m) take one rounding of at most half an ulp of 1 m a reading each way.
    turn = turns(left, right)
    exact = n * Fraction(float(turn[0]))
    assert heading_error(pose.theta, 0.0, exact) <= n * math.ulp(math.pi) / 2
    assert heading_error(float(batch[-1, 2]), 0.0, exact) <= n * math.ulp(math.pi) / 2
    bound = n * math.ulp(1.0)
    assert abs(batch[-1, 0] - pose.x) <= bound and abs(batch[-1, 1] - pose.y) <= bound


@settings(max_examples=15, deadline=None)
@given(
    spin=st.integers(-300, 300),
    jitter=st.integers(0, 150),
    seed=st.integers(0, 2**32 - 1),
    theta0=st.floats(-math.pi, math.pi, exclude_min=True),
)
def test_batch_heading_is_the_exact_sum_to_rounding(
    spin: int, jitter: int, seed: int, theta0: float
) -> None:
    # 3,000 readings of a robot that turns steadily (up to 0.75 rad a reading) with
    # jitter in the tick counts.
    noise = np.random.default_rng(seed).integers(-jitter, jitter + 1, size=3000)
    step = noise.astype(np.int64)
    left = np.concatenate(([0], np.cumsum(step - spin)))
    right = np.concatenate(([0], np.cumsum(step + spin)))
    out = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV, pose=(0.0, 0.0, theta0)).update_batch(
        left, right
    )
    total = sum((Fraction(float(t)) for t in turns(left, right)), Fraction(0))
    # One rounding of at most half an ulp of π a reading: as stepping reading by reading.
    assert heading_error(float(out[-1, 2]), theta0, total) <= len(noise) * math.ulp(math.pi) / 2
