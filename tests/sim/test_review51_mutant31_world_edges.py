"""Review 51 (MUTANT31): the World helpers FOUND3's 1c34944 moved out of ``__init__``.

``_solid_rings`` and ``_has_edges`` now build a new world's index and an old
pickle's alike. Two mutants of them passed every world test, each killed here:

* the solid rings keeping only edges that are neither horizontal nor vertical
  (``&`` for ``|`` in the filter of zero-length edges): a LiDAR inside an
  axis-aligned solid box then read the box's far walls instead of 0;
* ``_solid_start`` (an old pickle's only) built without the solid circles:
  the 908ac92 world the tests load has none;
* ``_has_edges`` ignoring moving polygons: in a world with an occupancy grid
  and no static edges, a LiDAR then looked through a moving obstacle.

And one of INLINE's dfaec1d (``** 2`` written as products in the circle
distances): the farthest vertex of a polygon footprint from a circular room's
centre measured with the centre's x in its y offset; every test's room was
centred at the origin, where the two are the same.
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
import pytest
from shapely.affinity import rotate
from shapely.geometry import Polygon, box

from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, MovingObstacle, World

ANGLES = np.linspace(-np.pi, np.pi, 12, endpoint=False)


def test_a_lidar_inside_an_axis_aligned_solid_reads_zero() -> None:
    square = box(2.0, 1.0, 2.5, 1.5)
    for solid in (square, rotate(square, 30.0)):
        world = World([solid, box(0.0, 0.0, 4.0, 3.0).exterior])
        ranges = world.raycast((2.25, 1.25, 0.3), ANGLES, range_max=6.0)
        np.testing.assert_array_equal(ranges, np.zeros(ANGLES.shape))
        outside = world.raycast((1.0, 1.25, 0.0), np.array([0.0]), range_max=6.0)
        assert 0.9 < outside[0] < 1.01  # the box's left wall, a metre off


def test_a_moving_polygon_is_seen_in_a_world_with_a_grid_and_no_static_edges() -> None:
    occupied = np.zeros((40, 40), dtype=bool)
    occupied[:, 39] = True  # a wall 3.9 m east
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    square = Polygon([(0.0, 0.0), (0.4, 0.0), (0.4, 0.4), (0.0, 0.4)])
    crate = MovingObstacle.constant_velocity(square, start_xy=(2.0, 1.0), velocity_xy=(0.0, 0.0))
    world = World(grid=grid, moving=[crate])
    ranges = world.raycast((1.0, 1.2, 0.0), np.array([0.0, np.pi / 2]), range_max=6.0, t=0.0)
    assert abs(ranges[0] - 1.0) < 1e-9  # the crate's west side, not the wall behind it
    alone = World(grid=grid).raycast((1.0, 1.2, 0.0), np.array([0.0]), range_max=6.0)
    assert alone[0] > 2.8  # without the crate: the wall


_SQUARE = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]


@pytest.mark.parametrize("pose", [(1.5, -1.0, 0.0), (0.0, -3.5, 0.4), (2.5, -2.0, -1.1)])
def test_a_polygon_in_an_off_centre_circular_room_is_its_farthest_vertex(
    pose: tuple[float, float, float],
) -> None:
    cx, cy, r = 1.0, -2.0, 5.0
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    far = max(math.hypot(x + c * vx - s * vy - cx, y + s * vx + c * vy - cy) for vx, vy in _SQUARE)
    world = World([Circle((cx, cy), r, solid=False)])
    assert world.clearance(_SQUARE, pose) == pytest.approx(r - far, rel=1e-12)


ADDED = ("_solid_rings", "_solid_start", "_solid_items", "_has_edges", "_edges_only")


def test_a_world_state_without_its_added_slots_loads_with_its_solid_circles() -> None:
    fresh = World(
        [Circle((1.0, 1.0), 0.4), Circle((2.6, 1.4), 0.3), box(0.0, 0.0, 4.0, 3.0).exterior]
    )
    instance, slots = cast("tuple[Any, dict[str, Any]]", fresh.__getstate__())
    old = World.__new__(World)
    old.__setstate__((instance, {k: v for k, v in slots.items() if k not in ADDED}))
    for name in ADDED[:3]:
        np.testing.assert_array_equal(getattr(old, name), getattr(fresh, name))
        assert not getattr(old, name).flags.writeable
    for pose in [(1.0, 1.0, 0.0), (2.6, 1.4, 1.0), (1.8, 1.2, -0.5)]:
        np.testing.assert_array_equal(
            old.raycast(pose, ANGLES, range_max=6.0), fresh.raycast(pose, ANGLES, range_max=6.0)
        )
    inside = old.raycast((2.6, 1.4, 0.0), ANGLES, range_max=6.0)
    np.testing.assert_array_equal(inside, np.zeros(ANGLES.shape))
