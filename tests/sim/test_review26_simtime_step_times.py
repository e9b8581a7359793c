"""Simulation step times are ``i / rate``, not ``i * dt`` (review 26, SIMTIME).

The simulator made step ``i``'s time as ``i * dt`` with ``dt = 1 / rate``: one
float off the decimal in 33 % of the rows at 10 Hz (14 % at 100 Hz), so that
``Simulation(..., duration=0.3, rate=10)`` reported ``Metrics.duration``
0.30000000000000004 and step 35 of 100 Hz read 0.35000000000000003. Users print
and compare these times (trace rows, events, ``time_to_goal``, reading stamps,
the delivery times an estimator is given). They are now ``i / rate``, the
correctly rounded decimal for a whole number of hertz.

Only the reported times changed: the steps a sensor fires on, and those a
delayed reading is delivered at, are still chosen as before; the last tests
check them against exact rational step counting.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from shapely.geometry import box

from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Compass,
    Imu,
    Lidar,
    Observation,
    Reading,
    Robot,
    ScanReading,
    Simulation,
    WheelEncoders,
    World,
)

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
# A wall at x = 5 m; the robot starts at the origin facing it.
ROOM = World(box(-1.0, -3.0, 5.0, 3.0).exterior)
BARE = Robot(drive=DIFF, footprint=0.2, encoders=None)
RATES = (10.0, 30.0, 100.0, 7.0)
#: A step of each rate whose ``i * dt`` is not ``i / rate`` (3 * 0.1 = 0.30000000000000004).
OFF_GRID_STEP = {10.0: 3, 30.0: 23, 100.0: 35, 7.0: 5}


def _step_of(t: float, rate: float) -> int:
    """The step whose time ``t`` is, checked to be exactly ``step / rate``."""
    step = round(t * rate)
    assert t == step / rate, (t, step, rate)
    return step


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.5, 0.0, 0.0)


def test_off_grid_steps_are_off_grid_with_a_multiplied_step() -> None:
    # The premise of the tests below: these steps tell the two roundings apart.
    for rate, i in OFF_GRID_STEP.items():
        assert i * (1.0 / rate) != i / rate


@pytest.mark.parametrize("rate", RATES)
def test_trace_rows_and_the_timeout_are_at_i_over_rate(rate: float) -> None:
    trace = Simulation(ROOM, BARE, lambda obs: Twist2D(0.0, 0.0, 0.3), start=(0.0, 0.0, 0.0),
                       rate=rate, control_rate=rate, duration=6.0).run()  # fmt: skip
    n = round(6.0 * rate)
    assert len(trace) == n + 1
    assert trace.times.tolist() == [i / rate for i in range(n + 1)]
    m = trace.metrics
    assert m.reason == "timeout" and m.duration == n / rate == 6.0
    (timeout,) = trace.events
    assert timeout.kind == "timeout" and timeout.t == 6.0


def test_a_run_of_three_tenths_of_a_second_at_10_hz_lasts_0_3_s() -> None:
    trace = Simulation(ROOM, BARE, _forward, start=(0.0, 0.0, 0.0), rate=10.0,
                       control_rate=10.0, duration=0.3).run()  # fmt: skip
    assert trace.metrics.duration == 0.3 and repr(trace.metrics.duration) == "0.3"
    assert trace.times.tolist() == [0.0, 0.1, 0.2, 0.3]
    assert [e.t for e in trace.events] == [0.3]


@pytest.mark.parametrize("rate", RATES)
def test_controller_done_event_time_is_its_steps(rate: float) -> None:
    stop = OFF_GRID_STEP[rate]

    class Stopper:
        def __init__(self) -> None:
            self.calls = 0
            self.done = False

        def __call__(self, obs: Observation) -> Twist2D:
            assert obs.t == self.calls / rate  # control at every step
            self.calls += 1
            self.done = self.calls > stop
            return Twist2D(0.0, 0.0, 0.0)

    trace = Simulation(ROOM, BARE, Stopper(), start=(0.0, 0.0, 0.0), rate=rate,
                       control_rate=rate, duration=10.0).run()  # fmt: skip
    (done,) = trace.events
    assert done.kind == "controller done" and done.t == stop / rate
    assert trace.metrics.duration == stop / rate == float(trace.times[-1])


def _off_grid_step(rate: float, at_least: int) -> int:
    """The first step from ``at_least`` on whose ``i * dt`` is off the decimal."""
    i = at_least
    while i * (1.0 / rate) == i / rate:
        i += 1
    return i


@pytest.mark.parametrize("rate", RATES)
def test_goal_and_collision_times_are_their_steps(rate: float) -> None:
    # At 0.5 m/s (0.5 / rate m a step from step 1 on), the goal (0.1 m tolerance) and
    # the wall (at 4.8 m for the 0.2 m disc) half a step's travel short of an off-grid
    # step's position, reached there.
    s = _off_grid_step(rate, 20)
    goal_x = 0.1 + 0.5 * (s - 0.5) / rate
    goal = Simulation(ROOM, BARE, _forward, start=(0.0, 0.0, 0.0), goal=(goal_x, 0.0),
                      rate=rate, control_rate=rate).run()  # fmt: skip
    m = goal.metrics
    assert m.reached and len(goal) == s + 1
    assert m.time_to_goal == m.duration == float(goal.times[-1]) == s / rate
    start_x = 4.8 - 0.5 * (s - 0.5) / rate
    crash = Simulation(ROOM, BARE, _forward, start=(start_x, 0.0, 0.0), rate=rate,
                       control_rate=rate).run()  # fmt: skip
    (hit,) = crash.events
    assert hit.kind == "collision" and crash.metrics.reason == "collision"
    assert len(crash) == s + 1 and hit.t == crash.metrics.duration == s / rate


class _Log:
    """An Estimator noting every delivery: (kind, stamp, delivery time)."""

    pose = None

    def __init__(self) -> None:
        self.seen: list[tuple[str, float, float]] = []

    def observe(self, t: float, reading: Reading) -> None:
        self.seen.append((type(reading).__name__, reading.stamp, t))


def _sensing_run(rate: float, duration: float) -> tuple[_Log, list[float], list[ScanReading]]:
    """Every sensor, at rates that do not divide the physics rate, some of them late."""
    robot = Robot(
        drive=DIFF, footprint=0.2,
        encoders=WheelEncoders(rate=rate / 2, latency=3.0 / rate),
        compass=Compass(rate=rate / 3, latency=0.25),
        imu=Imu(rate=rate),
        lidar=Lidar(n_beams=8, rate=rate / 7, latency=1.0 / 3.0),
    )  # fmt: skip
    log = _Log()
    control_t: list[float] = []

    def turn(obs: Observation) -> Twist2D:
        control_t.append(obs.t)
        return Twist2D(0.0, 0.0, 0.5)

    trace = Simulation(
        ROOM, robot, turn, start=(0.0, 0.0, 0.0), estimator=log, rate=rate,
        control_rate=rate / 4, duration=duration, record_scans=True,
    ).run()  # fmt: skip
    return log, control_t, list(trace.scans)


@pytest.mark.parametrize("rate", RATES)
def test_reading_stamps_delivery_and_control_times_are_steps(rate: float) -> None:
    log, control_t, scans = _sensing_run(rate, 4.0)
    kinds = {kind for kind, _, _ in log.seen}
    assert kinds == {"EncoderReading", "CompassReading", "ImuReading", "ScanReading"}
    for _, stamp, t in log.seen:
        _step_of(stamp, rate)
        _step_of(t, rate)
    for t in control_t:
        _step_of(t, rate)
    # The recorded scans: those delivered, then those still on their way at the end.
    delivered = [stamp for kind, stamp, _ in log.seen if kind == "ScanReading"]
    assert [s.stamp for s in scans][: len(delivered)] == delivered
    for scan in scans:
        _step_of(scan.stamp, rate)
    # The IMU samples every step: its stamps are exactly the steps' times.
    imu = [stamp for kind, stamp, _ in log.seen if kind == "ImuReading"]
    assert imu == [i / rate for i in range(len(imu))]
    assert any(i * (1.0 / rate) != i / rate for i in range(len(imu)))


def test_planar_fusion_is_given_decimal_times() -> None:
    # 35 steps of 100 Hz: 35 * 0.01 is 0.35000000000000003; the last IMU reading is
    # delivered at 0.35 s and the filter's time is that.
    robot = Robot(drive=DIFF, footprint=0.2, imu=Imu(), compass=Compass())
    fusion = PlanarFusion(pose=(0.0, 0.0, 0.0), t0=0.0)
    Simulation(ROOM, robot, _forward, start=(0.0, 0.0, 0.0), estimator=fusion,
               duration=0.35).run()  # fmt: skip
    assert fusion.t == 0.35


# --------------------------------------------------- the steps are those of before
def _first_step(when: Fraction, rate: float) -> int:
    """The first step at or after ``when`` within the simulator's 1e-9 s, in exact rationals.

    The tolerance is documented: a sensor at ``rate / 3`` Hz is due at
    ``k / fl(rate / 3)``, a hair off step ``3 k``, and fires there.
    """
    return max(math.ceil((when - Fraction(1, 10**9)) * Fraction(rate)), 0)


@pytest.mark.parametrize("rate", RATES)
def test_sensors_fire_and_deliver_on_the_exactly_counted_steps(rate: float) -> None:
    duration = 40.0
    log, control_t, _ = _sensing_run(rate, duration)
    n = round(duration * rate)
    sensors = {
        "EncoderReading": (rate / 2, Fraction(3.0 / rate)),
        "CompassReading": (rate / 3, Fraction(0.25)),
        "ImuReading": (rate, Fraction(0)),
        "ScanReading": (rate / 7, Fraction(1.0 / 3.0)),
    }
    # Steps read by rounding (not _step_of): the same before and after the change.
    for kind, (sensor_rate, latency) in sensors.items():
        got = [(round(s * rate), round(t * rate)) for k, s, t in log.seen if k == kind]
        taken = [_first_step(k / Fraction(sensor_rate), rate) for k in range(n + 1)]
        taken = [i for i in taken if i <= n]
        want = [(i, _first_step(Fraction(i) / Fraction(rate) + latency, rate)) for i in taken]
        # Delivered before the run's end only (the last step's deliveries included).
        assert got == [(i, j) for i, j in want if j <= n], kind
    steps = [round(t * rate) for t in control_t]
    assert steps == [_first_step(k / Fraction(rate / 4), rate) for k in range(len(steps))]
    assert steps[-1] <= n < _first_step(len(steps) / Fraction(rate / 4), rate)


def test_times_are_the_exact_step_count_over_a_long_run() -> None:
    # 10^5 steps of 100 Hz: no drift, every row i / rate.
    trace = Simulation(ROOM, BARE, lambda obs: Twist2D(0.0, 0.0, 0.1), start=(0.0, 0.0, 0.0),
                       duration=1000.0).run()  # fmt: skip
    np.testing.assert_array_equal(trace.times, np.arange(100_001) / 100.0)
    assert trace.metrics.duration == 1000.0
