"""``Simulation(reference_path=<a "grid" Path2D>)`` says how to convert the path.

It said "convert a grid path first" without saying how, where the trackers,
given the same path, name ``OccupancyGrid.cell_to_world`` and ``MapPlanner``
(a review of this session's integrator lens found the two messages apart).
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from shapely.geometry import box

from navkit.control import FollowTheCarrot
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D
from navkit.sim import Robot, Simulation, World


def _stop(_observation: object) -> Twist2D:
    return Twist2D(0.0, 0.0, 0.0)


def _simulation(reference: object) -> Simulation:
    world = World(box(-1.0, -1.0, 4.0, 3.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    return Simulation(world, robot, _stop, start=(0.0, 0.0, 0.0), duration=0.1,
                      reference_path=reference)  # fmt: skip


def _grid_path() -> Path2D:
    return Path2D([[0.0, 0.0], [0.0, 5.0], [3.0, 5.0]], "grid", cost=8.0, length=8.0, expanded=4)


def test_a_grid_reference_path_names_the_conversion() -> None:
    with pytest.raises(ValueError, match=r"^reference_path must be in the world frame") as info:
        _simulation(_grid_path())
    message = str(info.value)
    assert "'grid' Path2D" in message
    assert "path.to_world(grid)" in message  # review 53: the path converts itself
    assert "MapPlanner" in message


def test_the_advice_is_the_trackers_own() -> None:
    with pytest.raises(ValueError) as sim_info:
        _simulation(_grid_path())
    with pytest.raises(ValueError) as tracker_info:
        FollowTheCarrot().set_path(_grid_path())
    advice = re.search(r"\(convert .*\)$", str(tracker_info.value))
    assert advice is not None, str(tracker_info.value)
    assert str(sim_info.value).endswith(advice.group(0))


def test_the_converted_path_is_taken() -> None:
    # The advice works: path.to_world(grid), as the message says.
    grid = OccupancyGrid.from_occupancy(np.zeros((40, 50), dtype=bool), resolution=0.1,
                                        origin=(-1.0, -1.0, 0.0))  # fmt: skip
    world = _grid_path().to_world(grid)
    simulation = _simulation(world)
    assert simulation is not None
    np.testing.assert_allclose(world.points[0], [-0.95, -0.95])
