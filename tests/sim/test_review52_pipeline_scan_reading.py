"""A simulated scan reading handed on whole is told to pass its ``.scan`` (review 52, PIPELINE).

A controller in the simulator gets ``obs.scan``, a ``ScanReading`` (its ``stamp``
and its ``scan``), and the next packages want the ``LaserScan`` itself: a mapper,
ray casting, a matcher, the scan repulsion, a potential-field controller. Each
said only "scan must be a LaserScan, got ScanReading" (or, for the
controller's ``obstacles``, "must hold real numbers, got an element of type
ScanReading"), not what to pass. Every message now names ``.scan``, and what
it names is accepted.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.control import PotentialFieldController
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.planning import piecewise_repulsive_force_from_scan, repulsive_force_from_scan
from navkit.sim import Circle, Lidar, Observation, Robot, ScanReading, Simulation, World

HINT = "(a simulated reading: its .scan is the LaserScan, e.g. obs.scan.scan"


def _reading() -> tuple[ScanReading, Observation]:
    """The first scan reading a controller gets in a small room with a post."""
    world = World([box(-2.0, -2.0, 2.0, 2.0).exterior, Circle((1.0, 0.0), 0.3)])
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.15,
        lidar=Lidar(n_beams=90, noise=None),
        encoders=None,
    )
    got: list[Observation] = []

    def controller(obs: Observation) -> Twist2D:
        if obs.scan is not None and not got:
            got.append(obs)
        return Twist2D(0.0, 0.0, 0.0)

    Simulation(world, robot, controller, start=(-1.0, 0.0, 0.0), duration=0.3).run()
    assert got, "the LiDAR delivered no scan"
    assert got[0].scan is not None
    return got[0].scan, got[0]


def _grid() -> OccupancyGrid:
    return OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.1, origin=(-2.0, -2.0, 0.0))


CONSUMERS: dict[str, Callable[[Any, Observation], object]] = {
    "ScanMapper.update": lambda scan, obs: ScanMapper().update(scan),
    "integrate_scan": lambda scan, obs: integrate_scan(_grid(), scan, obs.true_pose),
    "OccupancyGrid.integrate_scan": lambda scan, obs: _grid().integrate_scan(scan, obs.true_pose),
    "ScanMatcher.match": lambda scan, obs: ScanMatcher().match(_grid(), scan, obs.true_pose),
    "repulsive_force_from_scan": lambda scan, obs: repulsive_force_from_scan(scan),
    "piecewise_repulsive_force_from_scan": lambda scan, obs: piecewise_repulsive_force_from_scan(
        scan
    ),
    "PotentialFieldController.step": lambda scan, obs: PotentialFieldController().step(
        obs.true_pose, (1.5, 1.5, 0.0), 0.05, obstacles=scan
    ),
}


@pytest.fixture(scope="module")
def reading() -> tuple[ScanReading, Observation]:
    return _reading()


@pytest.mark.parametrize("consumer", list(CONSUMERS))
def test_a_scan_reading_is_told_to_pass_its_scan(
    consumer: str, reading: tuple[ScanReading, Observation]
) -> None:
    scan_reading, obs = reading
    call = CONSUMERS[consumer]
    with pytest.raises(TypeError) as info:
        call(scan_reading, obs)
    message = str(info.value)
    assert "ScanReading" in message
    assert HINT in message, message
    # What the hint names is taken.
    call(scan_reading.scan, obs)


def test_the_hint_is_given_to_scan_readings_only() -> None:
    """Other wrong types keep their messages, without a hint that does not fit them."""
    with pytest.raises(TypeError, match=r"^scan must be a LaserScan, got ndarray$"):
        integrate_scan(_grid(), np.ones(90), (0.0, 0.0, 0.0))
    with pytest.raises(TypeError, match=r"^scan must be a navkit.mapping.LaserScan, got list$"):
        repulsive_force_from_scan([1.0, 2.0])
