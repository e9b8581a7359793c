"""World.bounds and World.collides on the cases no earlier test reached (mutation testing).

Surviving mutants: bounds without the grid's far corner (wrong for a rotated
map), collides deciding "inside a solid" by the pose rather than by a point of
a polygon footprint, wrapping negative cells of a footprint off the map onto
the map's far side, and placing the moving discs at t = 0 for that decision.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.affinity import rotate, translate
from shapely.geometry import Polygon, box

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.sim import MovingObstacle, World


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, -2.5, math.pi / 2])
def test_bounds_of_a_rotated_map_are_its_corners_extent(theta: float) -> None:
    rows, cols, res, ox, oy = 3, 5, 0.5, 1.0, 2.0
    grid = OccupancyGrid.from_occupancy(
        np.zeros((rows, cols), dtype=bool), resolution=res, origin=Pose2D(ox, oy, theta)
    )
    # The map's rectangle (cols*res by rows*res from its origin corner), rotated by
    # the origin's yaw about that corner: shapely computes its extent independently.
    rect = rotate(box(0.0, 0.0, cols * res, rows * res), theta, origin=(0.0, 0.0),
                  use_radians=True)
    want = translate(rect, ox, oy).bounds
    assert World(grid=grid).bounds == pytest.approx(want, abs=1e-12)


# A footprint 2..3 m ahead of the robot's reference point (e.g. a towed cart).
_AHEAD = [(2.0, -0.5), (3.0, -0.5), (3.0, 0.5), (2.0, 0.5)]


def test_an_offset_footprint_is_judged_by_its_own_points_not_the_pose() -> None:
    pose = (0.0, 0.0, 0.0)
    footprint = Polygon(_AHEAD)
    # The pose lies inside a solid box the footprint is clear of ...
    around_pose = box(-1.0, -1.0, 1.0, 1.0)
    assert not footprint.intersects(around_pose)
    assert World([around_pose]).collides(_AHEAD, pose) is False
    # ... and the footprint lies wholly inside a solid box that leaves the pose out.
    around_cart = box(1.5, -2.0, 3.5, 2.0)
    assert around_cart.contains(footprint) and not around_cart.contains(Polygon(
        [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]))
    assert World([around_cart]).collides(_AHEAD, pose) is True
    # Rotated a half turn the cart is behind the pose, clear of that box.
    assert World([around_cart]).collides(_AHEAD, (0.0, 0.0, math.pi)) is False


def test_a_robot_off_the_map_below_its_origin_is_free() -> None:
    # "outside the map is free": the cell (-1, -1) is no cell, whatever the map's
    # last row and column hold.
    occ = np.zeros((4, 4), dtype=bool)
    occ[3, 3] = True
    world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=1.0))
    assert world.clearance(0.1, (-0.5, -0.5, 0.0)) > 0.1
    assert world.collides(0.1, (-0.5, -0.5, 0.0)) is False
    assert world.collides(0.1, (3.5, 3.5, 0.0)) is True  # the occupied cell itself


def test_a_robot_inside_a_moving_disc_collides_at_the_query_time() -> None:
    ball = MovingObstacle.constant_velocity(1.0, start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.0))
    world = World(moving=[ball])
    # At t = 10 s the disc is centred on (10, 0): a small robot there is wholly
    # inside it (0.9 m from its rim) and collides; at t = 0 the disc is far away.
    assert world.clearance(0.1, (10.0, 0.0, 0.0), t=10.0) == pytest.approx(0.9, abs=1e-12)
    assert world.collides(0.1, (10.0, 0.0, 0.0), t=10.0) is True
    assert world.collides(0.1, (10.0, 0.0, 0.0), t=0.0) is False
    assert world.collides(0.1, (0.0, 0.0, 0.0), t=0.0) is True
