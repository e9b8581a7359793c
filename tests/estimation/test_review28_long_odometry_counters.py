"""DiffOdometry over counters that wrap many times (review 28, the long-run lens).

A robot that runs for days wraps a 16-bit encoder counter every 64 wheel turns
(1024 ticks a turn) and even a 32-bit one, read signed or unsigned. Long runs
are simulated by starting just below the wrap: the wrapped readings, decoded
with the counter's width, give the same tick changes as the unwrapped count,
so the poses are those of the run read with ``bits=None`` from the unwrapped
count, bit for bit, online and in a batch. And the ``bits`` notes: the width
must be the counter's, a wrap read with a wider one is a silent jump backwards.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive

DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)


def _readings(bits: int, signed: bool, start: int, steps: np.ndarray) -> np.ndarray:
    """The counter readings of the unwrapped counts ``start + cumsum(steps)``."""
    counts = start + np.cumsum(steps, axis=0)
    wrapped = counts % (1 << bits)
    if signed:
        wrapped = np.where(wrapped >= 1 << (bits - 1), wrapped - (1 << bits), wrapped)
    return wrapped


@pytest.mark.parametrize("bits", [16, 32])
@pytest.mark.parametrize("signed", [False, True])
def test_many_wraps_read_as_the_unwrapped_count(bits: int, signed: bool) -> None:
    rng = np.random.default_rng(bits + signed)
    # 20,000 readings of up to 3000 ticks forward (and some back) per wheel: a
    # 16-bit counter wraps hundreds of times, a 32-bit one starts 5000 ticks
    # below its wrap (the count of a robot that has run for days).
    steps = rng.integers(-200, 3000, size=(20_000, 2))
    start = (1 << (bits - 1 if signed else bits)) - 5000
    raw = _readings(bits, signed, start, steps)
    unwrapped = start + np.cumsum(steps, axis=0)
    wraps = int((np.abs(np.diff(raw[:, 0])) > 1 << (bits - 1)).sum())
    assert wraps > (300 if bits == 16 else 0)

    reference = DiffOdometry(DRIVE, ticks_per_rev=1024)  # bits=None: never wraps
    expected = reference.update_batch(unwrapped[:, 0], unwrapped[:, 1])
    batch = DiffOdometry(DRIVE, ticks_per_rev=1024, bits=bits)
    assert np.array_equal(batch.update_batch(raw[:, 0], raw[:, 1]), expected)

    online = DiffOdometry(DRIVE, ticks_per_rev=1024, bits=bits)
    twin = DiffOdometry(DRIVE, ticks_per_rev=1024)
    for (left, right), (ul, ur) in zip(raw.tolist(), unwrapped.tolist(), strict=True):
        assert online.update(left, right) == twin.update(ul, ur)
    # One reading at a time and one batch agree to rounding (the class notes).
    assert abs(math.remainder(online.pose.theta - batch.pose.theta, 2 * math.pi)) < 1e-9
    assert math.hypot(online.pose.x - batch.pose.x, online.pose.y - batch.pose.y) < 1e-6


@pytest.mark.parametrize("bits", [None, 32])
def test_a_16_bit_wrap_read_with_a_wider_width_is_a_jump_backwards(bits: int | None) -> None:
    # The `bits` notes: 65535 -> 4 is +5 ticks, read as 65,531 ticks back (20 m).
    wide = DiffOdometry(DRIVE, ticks_per_rev=1024, bits=bits)
    wide.update(65535, 65535)
    jumped = wide.update(4, 4)
    assert jumped.x == pytest.approx(-65531 / 1024 * 2 * math.pi * 0.05)
    assert -20.2 < jumped.x < -20.0
    right = DiffOdometry(DRIVE, ticks_per_rev=1024, bits=16)
    right.update(65535, 65535)
    assert right.update(4, 4).x == pytest.approx(5 / 1024 * 2 * math.pi * 0.05)


def test_half_the_range_or_more_between_readings_aliases() -> None:
    # The `bits` notes: a wheel must turn less than 2**(bits - 1) ticks a reading.
    odo = DiffOdometry(DRIVE, ticks_per_rev=1024, bits=16)
    odo.update(0, 0)
    assert odo.update(32767, 32767).x > 0.0  # just under half: forward
    odo.reset()
    odo.update(0, 0)
    assert odo.update(32768, 32768).x < 0.0  # half: read as backwards
