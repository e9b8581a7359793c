"""The simulator's step tolerance near its duration limit of 10^7 s (review 49).

Its schedules take a sensor's or the controller's ``k``-th sample at the first
physics step ``i`` with ``i * dt + tol >= k / rate``. ``tol`` was 1e-9 s; the
roundings of ``i * dt`` and ``k / rate`` grow with the time (together up to about
``3 * 2**-53`` of it), past 1e-9 s beyond about 1e6 s, so a sample due at a
step (physics at 0.0027 Hz, a compass at 0.0009 Hz: every third step) was taken
one step, 370 s, late at 407 of its 9000 samples, from 6.7e6 s on. ``tol`` is
now the larger of 1e-9 s and ``2**-50`` of the time: the same below 1.1e6 s
(every scenario's run), above it enough for the roundings, and far below a step
(at most 8.9e-9 s, steps are at least 1e-4 s).

The other uses of a 1e-9 tolerance were checked at the limit and are left as
they are: the number of steps (``ceil(duration * rate - 1e-9)``, in steps: a
duration of a whole number of steps counts that number, tested below), the
latency's steps (exact rational arithmetic on a latency of at most 10^4 s),
and the delivery, estimate and event times (the same ``i / rate`` floats on
both sides of each comparison: equal, whatever the time).
"""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, CompassReading, Observation, Robot, Simulation, World
from navkit.sim._segment_kernels import due_step
from navkit.sim._simulation import _lag_steps, _step_count

_PHYSICS = 0.0027  # Hz: 27000 steps of 370 s in 10^7 s
_SENSOR = 0.0009  # Hz: every third step


def _exact(text: str) -> Fraction:
    return Fraction(Decimal(text))


def test_due_step_takes_coincident_samples_on_their_step_up_to_the_limit() -> None:
    dt = 1.0 / _PHYSICS
    late = [k for k in range(1, 9001) if due_step(k, _SENSOR, dt) != 3 * k]
    assert late == []
    # 1.3 Hz physics, 0.7 Hz control: a coincidence every 13 steps; from step 9.54e6
    # (7.3e6 s) on, every one of the last 35227 up to 10^7 steps was late.
    for k in (5_138_028, 5_139_400, 5_384_610):
        i = Fraction(k) * _exact("1.3") / _exact("0.7")
        assert i.denominator == 1
        assert due_step(k, 0.7, 1.0 / 1.3) == int(i)


def test_due_step_is_never_early_by_more_than_the_tolerance() -> None:
    rng = np.random.default_rng(49)
    for _ in range(300):
        physics = float(rng.uniform(0.001, 2.0))
        sensor = physics / float(rng.integers(1, 9)) * float(rng.uniform(0.5, 1.0))
        k = int(rng.integers(1, int(1e7 * sensor) + 1))
        i = due_step(k, sensor, 1.0 / physics)
        when = Fraction(k) / Fraction(sensor)
        tol = max(Fraction(1, 10**9), Fraction(2.0**-50) * when)
        step = Fraction(i) / Fraction(physics)
        # Not before the sample time by more than the tolerance (plus the step's
        # own rounding), and the step before was too early.
        assert step >= when - tol - Fraction(2.0**-50) * when
        assert Fraction(i - 1) / Fraction(physics) < when


def _old_due_step(k: int, rate: float, dt: float) -> int:
    """due_step before review 49 (an absolute 1e-9 s)."""
    when = k / rate
    i = max(math.ceil((when - 1e-9) / dt) - 1, 0)
    while i * dt + 1e-9 < when:
        i += 1
    return i


def test_due_step_is_unchanged_below_a_million_seconds() -> None:
    rng = np.random.default_rng(7)
    for _ in range(2000):
        physics = float(rng.choice([100.0, 50.0, 30.0, 20.0, 10.0, 7.0, 1.3, 0.7]))
        sensor = float(rng.choice([20.0, 15.0, 10.0, 5.0, 3.0, 1.0, 0.7, 0.3]))
        if sensor > physics:
            continue
        k = int(rng.integers(0, int(1e6 * sensor)))
        assert due_step(k, sensor, 1.0 / physics) == _old_due_step(k, sensor, 1.0 / physics)


class _Still:
    """Stands still and notes when it was called and the compass readings it saw."""

    def __init__(self) -> None:
        self.calls: list[float] = []
        self.stamps: list[float] = []

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls.append(obs.t)
        self.stamps += [r.stamp for r in obs.new if isinstance(r, CompassReading)]
        return Twist2D(0.0, 0.0, 0.0)


def test_a_run_to_the_limit_samples_and_controls_on_their_steps() -> None:
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.2,
        encoders=None,
        compass=Compass(rate=_SENSOR),
    )
    controller = _Still()
    sim = Simulation(
        World(), robot, controller, start=(0.0, 0.0, 0.0),
        rate=_PHYSICS, control_rate=_SENSOR, duration=1e7,
    )  # fmt: skip
    trace = sim.run()
    assert trace.metrics.reason == "timeout"
    want = [3 * k / _PHYSICS for k in range(9001)]
    assert controller.calls == want
    # Without latency a reading reaches the controller at the step it is taken.
    assert controller.stamps == want


@pytest.mark.parametrize("rate", ["10000", "100", "30", "1.3", "0.7", "0.0027"])
def test_whole_numbers_of_steps_count_as_such_up_to_the_limit(rate: str) -> None:
    # Durations of exactly n steps (as decimals) near 10^7 steps or 10^7 s.
    r = _exact(rate)
    for n in (4_194_304, 8_388_607, 8_388_609, 9_999_991, 10_000_000):
        duration = Fraction(n) / r
        if duration > 10**7:
            n = int(Fraction(10**7) * r)
            duration = Fraction(n) / r
        text = f"{Decimal(duration.numerator) / Decimal(duration.denominator):.15g}"
        d = float(text)
        if Fraction(d) * r == n or Fraction(Decimal(text)) == duration:
            assert _step_count(d, float(rate)) == n, (rate, n, text)


def test_latency_steps_at_the_largest_latency() -> None:
    # 10^4 s (the largest latency) at 0.7 Hz: 7000 steps exactly.
    assert _lag_steps(1e4, 0.7) == 7000
    assert _lag_steps(1e4 + 2e-9, 0.7) == 7001
