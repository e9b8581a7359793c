"""A sensor's latency is the same whole number of physics steps for all its readings (review 27).

The simulator chose a delayed reading's delivery step by comparing
``step * dt + 1e-9`` with ``stamp + latency`` in floats. A latency 1e-9 s over
a whole number of steps sits on that tolerance, so the rounding of each sum
decided: at 100 Hz an IMU with a 0.03 s + 1e-9 s latency had 144 of its 1998
readings delivered a step later than the others (4 steps, not 3), 260 of 1996
for 0.05 s + 1e-9 s. The number of steps is now counted once per sensor, in
exact rational arithmetic on the floats given: the fewest ``m`` with
``m / rate >= latency - 1e-9``.
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box
from test_review26_simtime_step_times import _Log

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Imu, Lidar, Robot, Simulation, WheelEncoders, World

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
ROOM = World(box(-1.0, -1.0, 1.0, 1.0).exterior)


def _lags(rate: float, duration: float, **sensors: object) -> dict[str, Counter[int]]:
    """Steps from each reading's step to its delivery's, counted per sensor kind."""
    robot = Robot(drive=DIFF, footprint=0.2, **{"encoders": None, **sensors})  # type: ignore[arg-type]
    log = _Log()
    Simulation(ROOM, robot, lambda obs: Twist2D(0.0, 0.0, 0.2), start=(0.0, 0.0, 0.0),
               estimator=log, rate=rate, control_rate=rate / 5,
               duration=duration).run()  # fmt: skip
    out: dict[str, Counter[int]] = {}
    for kind, stamp, t in log.seen:
        out.setdefault(kind, Counter())[round(t * rate) - round(stamp * rate)] += 1
    return out


def _exact_lag(latency: float, rate: float) -> int:
    """The documented rule, in rationals: fewest m with m / rate >= latency - 1e-9 s."""
    return max(math.ceil((Fraction(latency) - Fraction(1, 10**9)) * Fraction(rate)), 0)


@pytest.mark.parametrize(
    ("rate", "latency", "steps"),
    [
        (100.0, 0.03 + 1e-9, 3),  # 144 of 1998 readings were 4 steps late
        (100.0, 0.05 + 1e-9, 6),  # fl(0.05) > 1/20: over by more than 1e-9 s
        (30.0, 2.0 / 30.0 + 1e-9, 2),
        (100.0, 0.03, 3),  # whole steps that are not binary fractions
        (100.0, 0.03 + 2e-9, 4),  # beyond the tolerance: the next step
    ],
)
def test_every_reading_of_a_sensor_is_delivered_the_same_steps_late(
    rate: float, latency: float, steps: int
) -> None:
    lags = _lags(rate, 20.0, imu=Imu(rate=rate, latency=latency))["ImuReading"]
    assert steps == _exact_lag(latency, rate)
    assert list(lags) == [steps]
    assert lags[steps] >= 20.0 * rate - steps - 1  # every reading of the run but the last


def test_all_four_sensors_keep_their_own_whole_step_lags() -> None:
    rate = 100.0
    lags = _lags(
        rate, 10.0,
        encoders=WheelEncoders(rate=50.0, latency=0.02 + 1e-9),
        compass=Compass(rate=20.0, latency=0.07 + 1e-9),
        imu=Imu(rate=100.0, latency=0.11 + 1e-9),
        lidar=Lidar(n_beams=4, rate=10.0, latency=0.3 + 1e-9),
    )  # fmt: skip
    want = {
        "EncoderReading": _exact_lag(0.02 + 1e-9, rate),
        "CompassReading": _exact_lag(0.07 + 1e-9, rate),
        "ImuReading": _exact_lag(0.11 + 1e-9, rate),
        "ScanReading": _exact_lag(0.3 + 1e-9, rate),
    }
    assert {kind: list(c) for kind, c in lags.items()} == {k: [v] for k, v in want.items()}


@settings(deadline=None, max_examples=25)
@given(
    rate=st.sampled_from([7.0, 30.0, 50.0, 100.0, 250.0]),
    steps=st.integers(0, 40),
    offset=st.sampled_from([-2e-9, -1e-9, 0.0, 1e-9, 2e-9, 1e-6]),
)
def test_the_lag_is_the_exact_rule_near_whole_steps(
    rate: float, steps: int, offset: float
) -> None:
    latency = max(steps / rate + offset, 0.0)
    # Long enough for 20 steps of readings after the longest lag.
    lags = _lags(rate, (steps + 21) / rate, imu=Imu(rate=rate, latency=latency))["ImuReading"]
    assert list(lags) == [_exact_lag(latency, rate)]
