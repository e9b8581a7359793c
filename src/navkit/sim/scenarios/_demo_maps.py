"""The demo's maps and tours: the Willow Garage office, or a synthetic office built in code."""

from __future__ import annotations

from shapely.geometry import box
from shapely.geometry.base import BaseGeometry

from navkit.mapping import OccupancyGrid

__all__ = ["OFFICE_TOUR", "WILLOW", "WILLOW_TOUR", "office_grid"]

#: The Willow Garage map, inside the data folder (see ``find_data``).
WILLOW = "ros-map-server-maps/willow_garage_2010/willow-2010-02-18-0.10.yaml"

#: Waypoints of the tour on the Willow Garage map, world (x, y) in m, on cell
#: centres (the planners' paths run between cell centres): an open area in the
#: south of the office, north-east through a side corridor, then west along
#: the corridors into the room west of the start (about 42 m in three legs).
WILLOW_TOUR: tuple[tuple[float, float], ...] = (
    (30.05, 9.05),
    (35.05, 16.55),
    (24.55, 20.05),
    (18.55, 17.55),
)

#: Waypoints of the tour of the synthetic office (see :func:`office_grid`):
#: from the south-west room along the corridor into the north-east room, down
#: into the south-east room, and back west to the middle south room.
OFFICE_TOUR: tuple[tuple[float, float], ...] = (
    (2.05, 3.05),
    (19.05, 11.55),
    (20.55, 3.05),
    (11.55, 3.05),
)

_WALL = 0.15  # m, wall thickness
_WIDTH, _HEIGHT = 24.0, 14.0  # m


def _wall_x(
    y: float, x0: float, x1: float, doors: tuple[tuple[float, float], ...]
) -> list[BaseGeometry]:
    """A horizontal wall at ``y`` from ``x0`` to ``x1``, broken by ``doors`` (x ranges)."""
    pieces: list[BaseGeometry] = []
    start = x0
    for a, b in doors:
        pieces.append(box(start, y - _WALL / 2, a, y + _WALL / 2))
        start = b
    pieces.append(box(start, y - _WALL / 2, x1, y + _WALL / 2))
    return pieces


def office_grid() -> OccupancyGrid:
    """A 24 × 14 m office at 0.1 m: six rooms either side of a 2 m corridor, furniture.

    Returns
    -------
    OccupancyGrid
        Walls and furniture occupied, the rest free (origin at (0, 0)).

    Examples
    --------
    >>> office_grid().shape
    (140, 240)
    """
    w, h, t = _WIDTH, _HEIGHT, _WALL
    shapes: list[BaseGeometry] = [
        box(0.0, 0.0, w, t), box(0.0, h - t, w, h), box(0.0, 0.0, t, h), box(w - t, 0.0, w, h),
    ]  # fmt: skip
    # The corridor, y in [6, 8]: doors into the three south rooms and the two north rooms.
    shapes += _wall_x(6.0, 0.0, w, ((3.0, 4.2), (11.0, 12.2), (18.6, 19.8)))
    shapes += _wall_x(8.0, 0.0, w, ((6.0, 7.2), (15.0, 16.2)))
    shapes += [box(8.0 - t / 2, 0.0, 8.0 + t / 2, 6.0), box(16.0 - t / 2, 0.0, 16.0 + t / 2, 6.0)]
    shapes += [box(12.0 - t / 2, 8.0, 12.0 + t / 2, h)]
    # Furniture: desks, a meeting table, cupboards.
    shapes += [
        box(1.0, 0.8, 3.2, 1.6), box(5.0, 3.0, 7.0, 4.2), box(9.5, 1.0, 13.5, 1.8),
        box(17.2, 4.2, 18.4, 5.4), box(21.5, 0.6, 23.2, 1.6), box(2.0, 10.0, 5.0, 11.5),
        box(8.0, 12.6, 11.0, 13.6), box(15.5, 9.8, 17.5, 12.0), box(21.5, 9.0, 23.6, 10.0),
    ]  # fmt: skip
    return OccupancyGrid.from_polygons(shapes, bounds=(0.0, 0.0, w, h), resolution=0.1)
