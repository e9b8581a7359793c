"""A subclass of Path2D or LaserScan passed whole where points are wanted (review 35).

Review 34's hint ("a whole path: pass path.points ...") looked for the names in
the type's MRO, to cover subclasses, but first required the type itself to be
defined in navkit: a user's ``class Route(Path2D)`` got the bare "got an
element of type Route". The hint now follows any navkit ``Path2D`` or
``LaserScan`` among the bases; a user's own class of the same name is not one.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid
from navkit.planning import Path2D

GRID = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.1)
POINTS = np.array([[0.05, 0.05], [0.25, 0.15]])


class Route(Path2D):
    """A user's path type."""


class Sweep(LaserScan):
    """A user's scan type."""


def test_a_subclass_of_path2d_gets_the_paths_hint() -> None:
    route = Route(POINTS, "world", 0.2, 0.2, 2)
    with pytest.raises(TypeError, match=r"type Route \(a whole path: pass path\.points"):
        GRID.world_to_cell(route)


def test_a_subclass_of_laserscan_gets_the_scans_hint() -> None:
    sweep = Sweep([1.0, 1.5], angle_min=-0.5, angle_increment=1.0, range_min=0.1,
                  range_max=5.0)  # fmt: skip
    with pytest.raises(TypeError, match=r"type Sweep \(a whole scan: pass its end points"):
        LocalGrid.from_points(sweep)


def test_a_users_own_class_of_that_name_gets_no_hint() -> None:
    class Path2D:  # not navkit's
        pass

    with pytest.raises(TypeError) as info:
        GRID.world_to_cell(Path2D())
    assert "a whole path" not in str(info.value)
    assert "got an element of type Path2D" in str(info.value)
