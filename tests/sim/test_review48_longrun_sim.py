"""Long runs of the simulator: 1 kHz for tens of thousands of steps (review 48, LONGRUN).

The simulator's clock is counted, never summed: step ``i`` is at ``i / rate`` exactly,
however long the run (a clock summed as ``t += dt`` is 1e-10 s off after 10^6 steps of
1 ms, and the trace's times would not be the decimals users print). The robot's pose
is stepped exactly on SE(2): a circle driven for 50,000 steps stays on its circle to
1e-11 m, its heading wrapped at every step. The trace takes about 80 bytes a step
(time, pose, estimate, command) and nothing else grows with the steps.
"""

from __future__ import annotations

import gc
import math
import tracemalloc

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, Trace, World

_RATE = 1000.0


def _circle(duration: float, rate: float = _RATE, start: tuple[float, float] = (0.0, 0.0)) -> Trace:
    # No sensors: nothing random, the true pose alone (1 m/s at 0.5 rad/s: radius 2 m).
    robot = Robot(drive=DiffDrive(track=0.4, wheel_radius=0.05), footprint=0.2, encoders=None)

    def circle(obs: Observation) -> Twist2D:
        return Twist2D(1.0, 0.0, 0.5)

    sim = Simulation(
        World(), robot, circle, start=(*start, 0.0), duration=duration, rate=rate,
        control_rate=20.0, stop_at_goal=False,
    )  # fmt: skip
    return sim.run()


def test_a_long_circle_keeps_its_clock_and_its_circle() -> None:
    trace = _circle(50.0)
    steps = trace.times.shape[0] - 1
    assert steps == 50_000
    # The clock: i / rate, bit for bit, to the last step (the run's duration itself).
    np.testing.assert_array_equal(trace.times, np.arange(steps + 1) / _RATE)
    assert trace.times[-1] == 50.0
    poses = trace.poses
    radius = np.hypot(poses[:, 0], poses[:, 1] - 2.0)
    assert float(np.abs(radius - 2.0).max()) < 1e-11
    theta = poses[:, 2]
    assert bool(np.all((theta > -math.pi) & (theta <= math.pi)))
    exact = np.remainder(0.5 * trace.times + math.pi, 2.0 * math.pi) - math.pi
    off = np.remainder(theta - exact + math.pi, 2.0 * math.pi) - math.pi
    assert float(np.abs(off).max()) < 1e-11
    # The distance sums the steps' chords, 2 r sin(ω dt / 2) each, without drift.
    assert trace.metrics.distance == pytest.approx(steps * 4.0 * math.sin(0.00025), rel=1e-12)


def test_trace_memory_is_linear_in_the_steps() -> None:
    # About 80 bytes a step (four float64 rows of 1 + 3 + 3 + 3), the same per step
    # for a run four times as long: nothing else grows with the steps.
    _circle(0.5)
    peaks = []
    for duration in (10.0, 40.0):
        gc.collect()
        tracemalloc.start()
        try:
            trace = _circle(duration)
            current, _ = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
        peaks.append(current)
        del trace
    per_step = (peaks[1] - peaks[0]) / 30_000
    assert 70.0 < per_step < 100.0
