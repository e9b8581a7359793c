"""Trace.events: in order, the end of the run last even when something happens at its final step."""

from __future__ import annotations

from shapely.geometry import LineString, box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

_ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, encoders=None)
# A wall the footprint (x + 0.2) first crosses at x = 1.0, step 10 at 1 m/s and 10 Hz.
_WORLD = World([box(-5.0, -5.0, 5.0, 5.0).exterior, LineString([(1.15, -1.0), (1.15, 1.0)])])


class _Forward:
    """Drives at 1 m/s; reports done from ``done_at`` (s) on."""

    def __init__(self, done_at: float = float("inf")) -> None:
        self.done = False
        self._done_at = done_at

    def __call__(self, obs: Observation) -> Twist2D:
        self.done = obs.t >= self._done_at - 1e-9
        return Twist2D(1.0, 0.0, 0.0)


def _run(controller: _Forward, duration: float) -> tuple[list[tuple[float, str]], str]:
    sim = Simulation(_WORLD, _ROBOT, controller, start=(0.0, 0.0, 0.0), rate=10.0,
                     control_rate=10.0, duration=duration, end_on_collision=False)  # fmt: skip
    trace = sim.run()
    return [(round(e.t, 9), e.kind) for e in trace.events], trace.metrics.reason


def test_a_collision_at_the_timeout_step_comes_before_the_timeout() -> None:
    events, reason = _run(_Forward(), duration=1.0)
    assert reason == "timeout"
    # The old sort by time alone kept the timeout (noted first) ahead of it.
    assert events == [(1.0, "collision"), (1.0, "timeout")]


def test_a_collision_at_the_last_control_step_comes_before_controller_done() -> None:
    events, reason = _run(_Forward(done_at=1.0), duration=5.0)
    assert reason == "controller done"
    assert events == [(1.0, "collision"), (1.0, "controller done")]
    assert events[-1][1] == reason
