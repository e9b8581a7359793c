"""Review 46: sensor latency, delivered exactly ``latency`` later (to the physics step).

The reference is the Simulation docstring's rule in exact rationals: a reading
taken at step ``i`` (``stamp = i / rate``) is delivered at the first step whose
time is at or after ``stamp + latency - 1e-9`` s, the same whole number of
steps after its own for every reading of a sensor; readings delivered at one
step go stream by stream (scans, encoders, compass, IMU), each stream's in the
order taken.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Lidar,
    Reading,
    Robot,
    ScanReading,
    Simulation,
    WheelEncoders,
    World,
)
from navkit.sim._latency import DelayLine

_RANK = {ScanReading: 0, EncoderReading: 1, CompassReading: 2, ImuReading: 3}


class Log:
    """An estimator that keeps (delivery time, reading) of everything it is given."""

    def __init__(self) -> None:
        self.pose: Pose2D | None = None
        self.seen: list[tuple[float, Reading]] = []

    def observe(self, t: float, reading: Reading) -> None:
        self.seen.append((t, reading))


def delivery_step(stamp: float, latency: float, rate: float) -> Fraction:
    """Time of the first step at or after ``stamp + latency - 1e-9`` (exact rationals)."""
    i = round(Fraction(stamp) * Fraction(rate))
    assert Fraction(i) / Fraction(rate) == Fraction(i / rate) or i / rate == stamp
    lag = max(math.ceil((Fraction(latency) - Fraction(1, 10**9)) * Fraction(rate)), 0)
    return Fraction(i + lag) / Fraction(rate)


def run_logged(rate: float, latencies: tuple[float, float, float, float],
               duration: float = 2.0) -> list[tuple[float, Reading]]:  # fmt: skip
    lat_scan, lat_enc, lat_cmp, lat_imu = latencies
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1,
        lidar=Lidar(n_beams=4, noise=None, latency=lat_scan, rate=min(10.0, rate)),
        encoders=WheelEncoders(rate=rate / 3.0, latency=lat_enc),
        compass=Compass(rate=rate / 2.0, latency=lat_cmp),
        imu=Imu(rate=rate, latency=lat_imu),
    )  # fmt: skip
    log = Log()
    Simulation(World(box(-5.0, -5.0, 5.0, 5.0).exterior), robot,
               lambda obs: Twist2D(0.1, 0.0, 0.2), start=(0.0, 0.0, 0.0), estimator=log,
               rate=rate, control_rate=rate / 5.0, duration=duration).run()  # fmt: skip
    return log.seen


def check(seen: list[tuple[float, Reading]], rate: float,
          latencies: tuple[float, float, float, float]) -> None:  # fmt: skip
    assert seen
    by_kind = dict(zip((ScanReading, EncoderReading, CompassReading, ImuReading), latencies,
                       strict=True))  # fmt: skip
    for t, reading in seen:
        want = delivery_step(reading.stamp, by_kind[type(reading)], rate)
        assert Fraction(t) == Fraction(float(want)), (type(reading).__name__, reading.stamp, t)
        assert t >= reading.stamp
    for (t0, r0), (t1, r1) in itertools.pairwise(seen):
        assert t0 <= t1
        if t0 == t1:
            assert _RANK[type(r0)] <= _RANK[type(r1)]
            if type(r0) is type(r1):
                assert r0.stamp < r1.stamp


@pytest.mark.parametrize(
    ("rate", "latencies"),
    [
        (100.0, (0.5, 0.08, 0.025, 0.0)),  # the paper's LiDAR and odometry; half a step
        (30.0, (0.1, 0.07, 1.0 / 30.0, 0.2)),  # a step that is no binary fraction
        (100.0, (0.03, 0.03 + 2e-9, 0.03 - 2e-9, 0.0299999)),  # at the tolerance's edges
        (100.0, (0.0, 0.0, 0.0, 0.0)),  # same-step delivery, one step, all four streams
    ],
)
def test_readings_arrive_latency_later_at_the_first_step_after(
    rate: float, latencies: tuple[float, float, float, float]
) -> None:
    check(run_logged(rate, latencies), rate, latencies)


@settings(max_examples=15, deadline=None)
@given(
    rate=st.sampled_from([50.0, 100.0, 30.0, 64.0]),
    latencies=st.tuples(*[st.floats(0.0, 0.3, allow_subnormal=False)] * 4),
)
def test_any_latency_arrives_at_the_first_step_after(
    rate: float, latencies: tuple[float, float, float, float]
) -> None:
    check(run_logged(rate, latencies, duration=1.0), rate, latencies)


def test_observation_holds_a_reading_from_its_delivery_on() -> None:
    """The controller's latest compass is the one taken ``latency`` before (whole steps)."""
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1, encoders=None,
                  compass=Compass(rate=100.0, latency=0.05))  # fmt: skip
    seen = []
    Simulation(World(), robot, lambda obs: seen.append(obs) or Twist2D(0.0, 0.0, 0.5),
               start=(0.0, 0.0, 0.0), rate=100.0, control_rate=100.0,
               duration=1.0).run()  # fmt: skip
    for obs in seen:
        if obs.t < 0.05 - 1e-9:
            assert obs.compass is None
        else:
            assert obs.compass is not None
            assert obs.compass.stamp == round(obs.t - 0.05, 12)
            # Heading then: 90° - 0.5 rad/s times the stamp (counter-clockwise turn).
            want = math.degrees(math.pi / 2 - 0.5 * obs.compass.stamp) % 360.0
            assert obs.compass.heading_deg == pytest.approx(want, abs=1e-9)


def test_delay_line_holds_items_to_their_due_time_in_order() -> None:
    line: DelayLine[str] = DelayLine(0.3)
    for due, item in [(0.3, "a"), (0.3, "b"), (0.4, "c"), (0.4 + 5e-10, "d"), (0.5, "e")]:
        line.push_at(due, item)
    assert line.delay == 0.3
    assert line.pop_due(0.3 - 2e-9) == []
    assert line.pop_due(0.3 - 5e-10) == [(0.3, "a"), (0.3, "b")]  # within 1e-9: due
    assert line.pop_due(0.4) == [(0.4, "c"), (0.4 + 5e-10, "d")]
    assert len(line) == 1
    assert line.pop_due(1.0) == [(0.5, "e")]
    assert line.pop_due(2.0) == []
