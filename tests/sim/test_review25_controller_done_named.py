"""A controller whose ``done`` has no truth value is named in the error (review 25)."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, World


class _ArrayDone:
    done = np.array([False, True])

    def __call__(self, _obs: object) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)


def test_an_array_done_is_named() -> None:
    world = World([box(0.0, 0.0, 4.0, 3.0).exterior])
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    sim = Simulation(world, robot, _ArrayDone(), start=(1.0, 1.0, 0.0), duration=0.2)
    with pytest.raises(TypeError, match="controller's done must be true or false, got ndarray"):
        sim.run()
