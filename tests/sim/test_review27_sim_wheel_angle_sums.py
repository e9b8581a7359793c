"""Wheel angles are summed with compensation: no drift over long runs (review 27).

The simulator added each step's wheel rotation to the wheel's angle plainly, so
the rounding of every sum accumulated: 10^7 steps drifted up to 0.4 tick of a
4096-tick encoder, 341 ticks of a 10^9-tick one after 2 * 10^6 steps (8 rad/s
at 100 Hz). The sums are now compensated (Kahan): the encoders read the exact
sum of the steps' rotations, to a tick, however long the run.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import EncoderReading, Reading, Robot, Simulation, WheelEncoders, World

TPR = 1e9  # ticks a turn: a tick is 6.3e-9 rad, so the drift of the plain sums shows
RATE = 100.0
# 0.5 m/s on wheels of 1/16 m: exactly 8 rad/s each (no ramp: unlimited acceleration).
DRIVE = DiffDrive(track=0.3, wheel_radius=0.0625)
CORRIDOR = World(box(-1.0, -1.0, 1e4, 1.0).exterior)


class _Last:
    """An Estimator keeping the last encoder reading."""

    pose = None

    def __init__(self) -> None:
        self.reading: EncoderReading | None = None

    def observe(self, t: float, reading: Reading) -> None:
        if isinstance(reading, EncoderReading):
            self.reading = reading


@pytest.mark.parametrize("duration", [100.0, 10_000.0])
def test_encoders_read_the_exact_sum_of_the_steps_rotations(duration: float) -> None:
    encoders = WheelEncoders(ticks_per_rev=TPR, bits=None, rate=1.0)
    robot = Robot(drive=DRIVE, footprint=0.1, encoders=encoders)
    last = _Last()
    Simulation(CORRIDOR, robot, lambda obs: Twist2D(0.5, 0.0, 0.0), start=(0.0, 0.0, 0.0),
               estimator=last, rate=RATE, control_rate=1.0, duration=duration).run()  # fmt: skip
    assert last.reading is not None
    steps = round(last.reading.stamp * RATE)
    assert steps == round(duration * RATE)
    # Each step turns each wheel by fl(8 * fl(1 / 100)) rad, exactly; their exact sum.
    exact = float(steps * Fraction(8.0 * (1.0 / RATE)))
    want = encoders.ticks(np.array([exact, exact]))
    # Compensated sums are within a few roundings of the exact one: 1e-3 tick here.
    assert np.abs(last.reading.ticks - want).max() <= 1
