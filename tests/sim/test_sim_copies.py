"""Copies and pickles of the simulator's worlds, obstacles and robots."""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, Lidar, MovingObstacle, Robot, World

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]
COPY_IDS = ["copy", "deepcopy", "pickle"]


def _moving_world() -> World:
    # A ball rolling along +x from x = 3 m at 1 m/s, a solid box and a map corner.
    ball = MovingObstacle.constant_velocity(0.5, start_xy=(3.0, 0.0), velocity_xy=(1.0, 0.0))
    grid = OccupancyGrid(np.full((2, 2), 5.0), resolution=0.5, origin=(-6.0, -1.0, 0.0))
    static = [box(-1.0, 2.0, 1.0, 3.0), Circle(np.array([0.0, -4.0]), 0.5)]
    return World(static, grid=grid, moving=[ball])


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_a_copied_world_and_its_original_answer_alike_and_apart(
    make_copy: Callable[[World], World],
) -> None:
    world = _moving_world()
    angles = np.array([0.0, 0.5 * math.pi, math.pi, -0.5 * math.pi])
    # Last placed at t = 0, as the copy then is.
    expected = {t: world.raycast((0.0, 0.0, 0.0), angles, range_max=50.0, t=t) for t in (5, 0)}
    twin = make_copy(world)
    # Each moves the ball in turn: neither may see it where the other last put it.
    np.testing.assert_array_equal(
        twin.raycast((0.0, 0.0, 0.0), angles, range_max=50.0, t=5.0), expected[5]
    )
    np.testing.assert_array_equal(
        world.raycast((0.0, 0.0, 0.0), angles, range_max=50.0, t=0.0), expected[0]
    )
    np.testing.assert_array_equal(
        twin.raycast((0.0, 0.0, 0.0), angles, range_max=50.0, t=0.0), expected[0]
    )
    assert expected[0][0] == pytest.approx(2.5) and expected[5][0] == pytest.approx(7.5)
    lidar = Lidar(n_beams=8, noise=None)
    np.testing.assert_array_equal(
        lidar.scan(twin, (0.0, 0.0, 0.0), t=2.0).ranges,
        lidar.scan(world, (0.0, 0.0, 0.0), t=2.0).ranges,
    )
    assert twin.collides(0.1, (0.0, 2.5, 0.0)) and not twin.collides(0.1, (0.0, 1.0, 0.0))
    assert twin.clearance(0.1, (0.0, 1.0, 0.0), t=0.0) == world.clearance(0.1, (0.0, 1.0, 0.0))


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_copied_worlds_keep_their_arrays_read_only(make_copy: Callable[[World], World]) -> None:
    twin = make_copy(_moving_world())
    for arr in (twin.segments, twin.circles, twin.solid_circles):
        assert not arr.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            arr[...] = 0.0


@pytest.mark.parametrize("make_copy", COPIES, ids=COPY_IDS)
def test_copied_obstacles_and_robots_keep_their_arrays_read_only(
    make_copy: Callable[[Any], Any],
) -> None:
    square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=square,
        wheel_radius_error=np.array([0.01, -0.02]),
    )  # fmt: skip
    ball = MovingObstacle.scripted(0.2, [(0.0, 0.0), (1.0, 0.0)], speed=0.5, after="loop")
    pillar = Circle(np.array([1.0, 2.0]), 0.5)
    cases = (
        (robot, ("footprint", "wheel_radius_error")),
        (ball, ("path_xy", "times")),
        (pillar, ("center_xy",)),
    )
    for obj, names in cases:
        twin = make_copy(obj)
        for name in names:
            arr = getattr(twin, name)
            np.testing.assert_array_equal(arr, getattr(obj, name))
            assert not arr.flags.writeable, (type(obj).__name__, name)
    np.testing.assert_array_equal(make_copy(ball).position_at(3.0), ball.position_at(3.0))
