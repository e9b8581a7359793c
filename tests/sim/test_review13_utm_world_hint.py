"""A world in UTM coordinates is refused with the way out (review 13, large coordinates).

The simulator keeps world coordinates within ±1e6 m (its LiDAR's on-line tolerance
is absolute); a map in UTM (a northing of 4.5e6 m) got only "must lie within
±1e+06 m". The message now says to simulate in a local frame, and doing so works.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.sim import World

UTM = Pose2D(500123.45, 4500678.9, 0.0)


def _grid(origin: Pose2D) -> OccupancyGrid:
    p = np.zeros((20, 20))
    p[5:8, 5:8] = 1.0
    return OccupancyGrid.from_probabilities(p, resolution=0.1, origin=origin)


def test_a_utm_grid_is_refused_with_the_local_frame_advice() -> None:
    with pytest.raises(ValueError, match=r"grid origin must lie within .*local frame"):
        World(grid=_grid(UTM))


def test_utm_obstacles_are_refused_with_the_local_frame_advice() -> None:
    square = shapely.box(UTM.x, UTM.y, UTM.x + 1.0, UTM.y + 1.0)
    with pytest.raises(ValueError, match=r"obstacles must lie within .*local frame"):
        World([square])


def test_the_advice_works_a_shifted_grid_is_the_same_world() -> None:
    local = World(grid=_grid(Pose2D(0.0, 0.0, 0.0)))
    # The block of cells 5..7 lies at 0.5..0.8 m: a pose there collides, one outside does not.
    assert local.collides(0.05, Pose2D(0.65, 0.65, 0.0), t=0.0)
    assert not local.collides(0.05, Pose2D(1.5, 1.5, 0.0), t=0.0)
