"""A ``done`` held in a str or a Python container is refused (review 30).

Their truth value is whether they are empty, so ``[False]`` and ``"False"``
ended a run at its first step as "controller done", and ``[]`` never did.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, World
from navkit.sim._done import done_flag

SLIPS = [
    [False], [True], [], (False,), "False", "", b"0", bytearray(b""), {"done": False}, {0},
    frozenset(),
]  # fmt: skip


@pytest.mark.parametrize("done", SLIPS, ids=repr)
def test_each_is_a_type_error_naming_the_flag(done: object) -> None:
    kind = type(done).__name__
    with pytest.raises(TypeError, match=rf"^tracker\.done must be true or false, got a {kind} "):
        done_flag(done, "tracker.done")


@pytest.mark.parametrize("done", [[False], "False"], ids=repr)
def test_a_run_does_not_end_on_one(done: object) -> None:
    class Controller:
        def __call__(self, _obs: object) -> Twist2D:
            return Twist2D(0.1, 0.0, 0.0)

        @property
        def done(self) -> object:
            return done

    world = World([box(-1.0, -1.0, 4.0, 3.0).exterior])
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    sim = Simulation(world, robot, Controller(), start=(0.0, 0.0, 0.0), duration=0.3)
    with pytest.raises(TypeError, match="the controller's done must be true or false"):
        sim.run()


def test_numpy_one_element_arrays_still_decide() -> None:
    flag: Callable[[object, str], bool] = done_flag
    assert flag(np.array([True]), "done") is True
    assert flag(np.array([False]), "done") is False
