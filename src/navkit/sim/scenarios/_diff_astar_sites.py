"""The places of the diff-astar scenario: a three-room house and a building route.

* The house is built from a floor plan (the paper publishes the route, not the
  plan): an outer 7 × 8 m shell, a partition at x = −2.5 m with two 0.9 m
  doors, a wall at y = −1 m splitting the west half into two rooms, and a
  kitchen counter in the living room. The doors and the counter are placed so
  that A* on the map inflated by 0.3 m finds routes as long as the paper's
  (7.925 and 5.663 m).
* The building route: on the Willow Garage office map (a real robot-built map)
  from (19.05, 38.55) to (51.05, 44.55) m — exactly (32, 6) m apart, both in
  open corridor space — or, without the data, a procedurally built corridor
  building from (0, 0) to (32, 6) m.

Everything heavy (map, world, distance field, planner, routes) is built once
per process and cached.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass
from pathlib import PurePath
from typing import Literal

import numpy as np
import shapely
from shapely.geometry import Polygon, box

from navkit._shared.frozen import frozen_setattr
from navkit.errors import DataNotFoundError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, Path2D
from navkit.sim import World
from navkit.sim.scenarios._data import find_data
from navkit.sim.scenarios._demo_maps import WILLOW
from navkit.sim.scenarios._diff_astar_localizer import LikelihoodField

__all__ = [
    "HOUSE_ROOMS",
    "INFLATION",
    "WILLOW",
    "Site",
    "SiteName",
    "site",
]

SiteName = Literal["house", "willow", "corridor"]

#: The paper's inflation of the map for A*, m.
INFLATION = 0.3
#: The Willow Garage map, inside the data folder.
#: Map resolution of the built places, m.
RESOLUTION = 0.05
#: Wall thickness of the built places, m.
WALL = 0.1

#: The house's rooms: name, (xmin, ymin, xmax, ymax) m (inner faces of the walls
#: at these lines ± 0.05 m), doors.
HOUSE_ROOMS = (
    ("living room (start)", (-2.5, -6.0, 1.0, 2.0),
     "counter 2.5 x 0.5 m at x -2.5..0, y -3.3..-2.8"),
    ("bedroom (waypoint 1)", (-6.0, -1.0, -2.5, 2.0), "door x = -2.5, y -0.25..0.65"),
    ("study (waypoint 2)", (-6.0, -6.0, -2.5, -1.0), "door x = -2.5, y -2.5..-1.6"),
)  # fmt: skip


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Site:
    """A place with its map, world, planner, distance field and planned route.

    Attributes
    ----------
    name : {"house", "willow", "corridor"}
    grid : OccupancyGrid
        The map A* plans on (and the LiDAR sees, for Willow).
    world : World
        What the robot collides with and the LiDAR sees.
    field : LikelihoodField
        The localiser's distance field.
    planner : MapPlanner
        A* on ``grid`` inflated by :data:`INFLATION`.
    waypoints : ndarray (n, 2)
        Start, then the goals in order, world frame, m.
    routes : tuple of Path2D
        A* route of each leg (waypoint k to k + 1).
    offset : tuple of float
        Added to world coordinates to give the table's (the building's start
        becomes (0, 0)).
    speed : float
        The paper's tracking speed here, m/s.
    """

    name: SiteName
    grid: OccupancyGrid
    world: World
    field: LikelihoodField
    planner: MapPlanner
    waypoints: np.ndarray
    routes: tuple[Path2D, ...]
    offset: tuple[float, float]
    speed: float


def _spans(
    lo: float, hi: float, doors: tuple[tuple[float, float], ...]
) -> list[tuple[float, float]]:
    """The solid stretches of a wall from ``lo`` to ``hi`` around its door openings."""
    edges = [lo, *[v for d in doors for v in d], hi]
    return [(a, b) for a, b in zip(edges[::2], edges[1::2], strict=True) if b > a]


def _walls_x(
    y: float, x0: float, x1: float, doors: tuple[tuple[float, float], ...]
) -> list[Polygon]:
    """A wall along y from x0 to x1 with door openings (x ranges)."""
    return [box(a, y - WALL / 2, b, y + WALL / 2) for a, b in _spans(x0, x1, doors)]


def _walls_y(
    x: float, y0: float, y1: float, doors: tuple[tuple[float, float], ...]
) -> list[Polygon]:
    """A wall along x from y0 to y1 with door openings (y ranges)."""
    return [box(x - WALL / 2, a, x + WALL / 2, b) for a, b in _spans(y0, y1, doors)]


def _shell(x0: float, y0: float, x1: float, y1: float) -> list[Polygon]:
    h = WALL / 2
    return [
        box(x0 - h, y0 - h, x1 + h, y0 + h), box(x0 - h, y1 - h, x1 + h, y1 + h),
        box(x0 - h, y0 - h, x0 + h, y1 + h), box(x1 - h, y0 - h, x1 + h, y1 + h),
    ]  # fmt: skip


def house_walls() -> list[Polygon]:
    """The house's walls and counter (see :data:`HOUSE_ROOMS`)."""
    walls = _shell(-6.0, -6.0, 1.0, 2.0)
    walls += _walls_y(-2.5, -6.0, 2.0, ((-2.5, -1.6), (-0.25, 0.65)))
    walls += _walls_x(-1.0, -6.0, -2.5, ())
    walls.append(box(-2.5, -3.3, 0.0, -2.8))  # kitchen counter against the partition
    return walls


def corridor_walls() -> list[Polygon]:
    """A corridor building: a 2 m corridor along y = 0, one north along x = 32, offices.

    The footprint is x −1.5..35, y −5..7.5 m. The main corridor (y −1..1)
    has offices 4 m wide on both sides, each with a 0.9 m door; the side
    corridor (x 31..33) runs north to the goal at (32, 6) m.
    """
    walls = _shell(-1.5, -5.0, 35.0, 7.5)
    north = tuple((x + 1.55, x + 2.45) for x in np.arange(-1.0, 27.0, 4.0).tolist())
    south = tuple((x + 1.55, x + 2.45) for x in np.arange(-1.0, 31.0, 4.0).tolist())
    walls += _walls_x(1.0, -1.5, 31.0, north)
    walls += _walls_x(-1.0, -1.5, 35.0, south)
    walls += _walls_y(31.0, 1.0, 7.5, ((3.55, 4.45),))
    walls += _walls_y(33.0, 1.0, 7.5, ((2.05, 2.95), (5.05, 5.95)))
    walls += _walls_x(4.0, 33.0, 35.0, ())
    for x in np.arange(3.0, 31.0, 4.0):
        walls += _walls_y(float(x), 1.0, 7.5, ())
        walls += _walls_y(float(x), -5.0, -1.0, ())
    return walls


def _built(
    name: SiteName, walls: list[Polygon], waypoints: list[tuple[float, float]], speed: float
) -> Site:
    union = shapely.union_all(walls)
    xmin, ymin, xmax, ymax = union.bounds
    # Bounds half a cell off the 0.05 m lattice: wall faces fall mid-cell, so
    # the conservative rasterisation widens each wall by half a cell, not one.
    half = RESOLUTION / 2
    bounds = (xmin - 0.5 - half, ymin - 0.5 - half, xmax + 0.5, ymax + 0.5)
    grid = OccupancyGrid.from_polygons(walls, bounds=bounds, resolution=RESOLUTION)
    world = World(walls)
    field = LikelihoodField.from_boxes(grid, shapely.bounds(walls))
    offset = (0.0, 0.0)
    return _finish(name, grid, world, field, waypoints, offset, speed)


def _finish(
    name: SiteName,
    grid: OccupancyGrid,
    world: World,
    field: LikelihoodField,
    waypoints: list[tuple[float, float]],
    offset: tuple[float, float],
    speed: float,
) -> Site:
    planner = MapPlanner(grid, robot_radius=INFLATION)
    points = np.array(waypoints, dtype=np.float64)
    routes = tuple(planner.plan(a, b) for a, b in itertools.pairwise(points))
    points.flags.writeable = False
    return Site(name, grid, world, field, planner, points, routes, offset, speed)


@functools.lru_cache(maxsize=4)
def site(name: SiteName, data_dir: str | None = None) -> Site:
    """The place ``name``, built once per process.

    Parameters
    ----------
    name : {"house", "willow", "corridor"}
        Which place.
    data_dir : str, optional
        The data folder (for ``"willow"``; see :func:`find_data`).

    Returns
    -------
    Site
        Map, world, field, planner and routes.

    Raises
    ------
    DataNotFoundError
        ``"willow"`` without the Willow Garage map.

    Examples
    --------
    >>> [round(r.length, 2) for r in site("house").routes]
    [7.97, 5.68]
    """
    if name == "house":
        return _built("house", house_walls(), [(-1.0, -4.0), (-4.0, 0.0), (-4.0, -2.0)], 0.18)
    if name == "corridor":
        return _built("corridor", corridor_walls(), [(0.0, 0.0), (32.0, 6.0)], 0.25)
    if name == "willow":
        grid = OccupancyGrid.load(find_data(WILLOW, data_dir=data_dir))
        start = (19.05, 38.55)
        return _finish(
            "willow", grid, World(grid=grid), LikelihoodField.from_grid(grid),
            [start, (start[0] + 32.0, start[1] + 6.0)], (-start[0], -start[1]), 0.25,
        )  # fmt: skip
    raise ValueError(f"name must be 'house', 'willow' or 'corridor', got {name!r}")


def resolve_building(
    building: str, data_dir: str | None
) -> tuple[Literal["willow", "corridor"], str | None]:
    """The building to use and the data folder to read it from, both fixed now.

    ``"willow"`` or ``"corridor"`` as asked; for ``"auto"`` the Willow Garage
    map when it is found, else the corridor building. With the map found, the
    folder is the absolute data folder it was found in: without it each process
    of a sweep would look again, at its own ``$NAVKIT_DATA`` and working
    directory (see :func:`find_data`), and might run another building.

    Parameters
    ----------
    building : {"auto", "willow", "corridor"}
        The scenario's option.
    data_dir : str, optional
        The data folder as given.

    Returns
    -------
    building : {"willow", "corridor"}
        The building.
    data_dir : str or None
        The folder to pass to :func:`site`: ``data_dir`` as given unless the
        Willow Garage map was found (``building="willow"`` without it raises in
        :func:`site`).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as empty:  # a data folder without the map
    ...     resolve_building("auto", empty)[0]
    'corridor'
    """
    if building == "corridor":
        return "corridor", data_dir
    try:
        found = find_data(WILLOW, data_dir=data_dir).resolve()
    except DataNotFoundError:
        return ("willow" if building == "willow" else "corridor"), data_dir
    return "willow", str(found.parents[len(PurePath(WILLOW).parts) - 1])


def heading_of(path: Path2D) -> float:
    """Heading of a route's first segment, rad (0 for a one-point route).

    Examples
    --------
    >>> round(heading_of(site("house").routes[0]), 3)  # north-east, round the counter
    0.785
    """
    pts = path.points
    if pts.shape[0] < 2:
        return 0.0
    d = pts[1] - pts[0]
    return math.atan2(float(d[1]), float(d[0]))
