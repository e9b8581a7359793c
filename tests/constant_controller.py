"""A controller that commands one twist, and a run of it in an empty world.

Shared by the simulation tests (``tests/sim``).
"""

from __future__ import annotations

from typing import Any

from navkit.geometry import Twist2D
from navkit.sim import Observation, Robot, Simulation, Trace, World


class Constant:
    """Commands one twist and keeps every observation."""

    def __init__(self, twist: Twist2D) -> None:
        self.twist = twist
        self.seen: list[Observation] = []

    def __call__(self, obs: Observation) -> Twist2D:
        self.seen.append(obs)
        return self.twist

    def readings(self, kind: type) -> list[Any]:
        """Every new reading of type ``kind`` of the observations seen, in order."""
        return [r for obs in self.seen for r in obs.new if isinstance(r, kind)]


def run_constant(robot: Robot, twist: Twist2D, duration: float,
                 **kwargs: Any) -> tuple[Trace, Constant]:  # fmt: skip
    """Run ``robot`` from the origin of an empty world commanding ``twist``: trace, controller."""
    ctrl = Constant(twist)
    sim = Simulation(World(), robot, ctrl, start=(0.0, 0.0, 0.0), duration=duration, **kwargs)
    return sim.run(), ctrl
