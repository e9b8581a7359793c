"""Review 47 (DEGEN): RegulatedPurePursuit's map clearance just inside and outside the map.

The public docstring now says what the private ``_GridClearance`` did all along:
a robot outside the map is not regulated, however near the walls at its edge.
"""

from __future__ import annotations

import numpy as np

from navkit.control import RegulatedPurePursuit
from navkit.mapping import OccupancyGrid


def _wall_at_the_edge() -> OccupancyGrid:
    """A 2 m square map at 0.1 m whose last row (y in [1.9, 2.0)) is a wall."""
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[-1, :] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(0.0, 0.0, 0.0))


def _speed(y: float, clearance: OccupancyGrid | None) -> float:
    rpp = RegulatedPurePursuit(clearance=clearance)
    rpp.set_path([(0.0, y), (5.0, y)])
    return rpp.step((0.5, y, 0.0), 0.05).vx


def test_a_robot_beside_the_wall_inside_the_map_is_slowed() -> None:
    assert _speed(1.85, _wall_at_the_edge()) < _speed(1.85, None)


def test_a_robot_just_outside_the_map_is_not_regulated() -> None:
    # 2.0 + 1e-9 lies outside the last row: as far as the grid knows, no obstacle.
    assert _speed(2.0 + 1e-9, _wall_at_the_edge()) == _speed(2.0 + 1e-9, None)
