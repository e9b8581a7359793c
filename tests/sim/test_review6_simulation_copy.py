"""A copy of a Simulation has its own random generator: running one leaves the other alone."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Imu, Lidar, Observation, Robot, Simulation, Trace, World

_WORLD = World(box(-10.0, -10.0, 10.0, 10.0).exterior)
_ROBOT = Robot(
    drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=0.1,
    lidar=Lidar(n_beams=8, dropout=0.2), compass=Compass(noise=0.1), imu=Imu(gyro_noise=0.1),
)  # fmt: skip


def _turn(_: Observation) -> Twist2D:
    return Twist2D(0.3, 0.0, 0.2)


def _simulation() -> Simulation:
    return Simulation(_WORLD, _ROBOT, _turn, start=(0.0, 0.0, 0.0), duration=2.0, seed=7,
                      record_scans=True)  # fmt: skip


def _same(a: Trace, b: Trace) -> bool:
    return np.array_equal(a.poses, b.poses) and all(
        np.array_equal(x.scan.ranges, y.scan.ranges, equal_nan=True)
        for x, y in zip(a.scans, b.scans, strict=True)
    )


@pytest.mark.parametrize(
    "duplicate",
    [copy.copy, copy.deepcopy, lambda sim: pickle.loads(pickle.dumps(sim))],
    ids=["copy", "deepcopy", "pickle"],
)
def test_a_copy_and_its_original_run_alike_and_apart(duplicate: Callable[[Any], Any]) -> None:
    reference = _simulation().run()
    original = _simulation()
    twin = duplicate(original)
    assert _same(twin.run(), reference)
    # The shallow copy shared the generator: the original's slip and noise then
    # continued where the copy's run had left it.
    assert _same(original.run(), reference)
    with pytest.raises(RuntimeError, match="runs once"):
        twin.run()


def test_a_shallow_copy_shares_the_configuration() -> None:
    original = _simulation()
    twin = copy.copy(original)
    assert twin._world is original._world and twin._robot is original._robot
    assert twin._rng is not original._rng
