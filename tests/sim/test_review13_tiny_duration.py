"""A Simulation whose duration is shorter than a billionth of a step (review 13).

``Simulation``'s ``duration`` doc: the run times out "at the first physics step at
or after it, step ``ceil(duration * rate)``", so any positive duration runs at
least one step. The step count is ``ceil(duration * rate - 1e-9)`` (the slack
absorbs rounding such as 0.07 * 100 = 7.000000000000001), which is 0 for
``duration * rate <= 1e-9``: such a run ends at t = 0 with one sample, a
"timeout" after no physics at all. The count is now at least one step.
"""

from __future__ import annotations

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.4, 0.0, 0.0)


def _run(duration: float) -> tuple[list[float], float]:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    trace = Simulation(World(), robot, _forward, start=(0.0, 0.0, 0.0), duration=duration).run()
    return trace.times.tolist(), trace.metrics.duration


def test_a_duration_of_a_millionth_of_a_step_runs_one_step() -> None:
    assert _run(1e-8) == ([0.0, 0.01], 0.01)  # 100 Hz physics: step 1 at 0.01 s


def test_any_positive_duration_runs_at_least_one_step() -> None:
    assert _run(1e-12) == ([0.0, 0.01], 0.01)
