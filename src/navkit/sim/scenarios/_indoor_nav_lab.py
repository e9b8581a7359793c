"""The indoor-navigation paper's lab: floor plan, map, world, targets and routes.

The lab is a 14.4 × 12 m room (walls 0.1 m thick, inside the outline) with a
4.8 × 4.4 m side room partitioned off in its north-east corner, entered through
a 1.0 m door in the side room's south wall. Furniture (optional): two lab
benches, a central table, shelves along the walls, a desk, and a table and
cabinet in the side room. The floor plan's grid and world are built once per
process and cached; the maps the robot plans on are in :mod:`._indoor_nav_mapping`.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from shapely.geometry import Polygon, box

from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D
from navkit.sim import World

__all__ = [
    "BODY_RADIUS",
    "DOOR",
    "LAB_HEIGHT",
    "LAB_WIDTH",
    "MAP_TOUR",
    "PLAN_INFLATION_SCANS",
    "PLAN_RADIUS",
    "PLAN_RADIUS_SCANS",
    "PLAN_ROUTES",
    "ROOM_SPANS",
    "SIDE_ROOM",
    "TARGETS",
    "TOUR_START",
    "TRACK_PATHS",
    "WALL",
    "anchored",
    "heading_share",
    "lab_grid",
    "lab_obstacles",
    "lab_world",
]

LAB_WIDTH = 14.4  # m, x
LAB_HEIGHT = 12.0  # m, y
WALL = 0.1  # m
#: Side room (xmin, ymin, xmax, ymax), m: 4.8 × 4.4 m in the north-east corner.
SIDE_ROOM = (LAB_WIDTH - 4.8, LAB_HEIGHT - 4.4, LAB_WIDTH, LAB_HEIGHT)
#: Door in the side room's south wall (x from, x to), m.
DOOR = (SIDE_ROOM[0] + 1.4, SIDE_ROOM[0] + 2.4)

#: The simulated robot's body radius and the planners' inflation, m: the
#: 0.15 m difference is the margin left for localisation error. On the map
#: built from scans, whose walls and furniture lie up to ~0.2 m off, the
#: planners keep more clearance: 0.05 m more inflation (more would close the
#: side room's door) and costs decaying out to 0.8 m (Nav2's inflation), so
#: paths keep away from obstacles where there is room (with the plan's 0.35 m
#: alone the localisation tour grazes a bench).
BODY_RADIUS = 0.2
PLAN_RADIUS = 0.35
PLAN_RADIUS_SCANS = 0.4
PLAN_INFLATION_SCANS = 0.8

#: Start pose of the localisation tour, (x, y, theta).
TOUR_START = (1.0, 1.0, 0.0)
#: The 10 target points of the localisation tour, visited in order, m.
TARGETS: tuple[tuple[float, float], ...] = (
    (6.8, 1.2),
    (9.6, 3.0),
    (13.2, 2.6),
    (11.4, 6.0),
    (11.8, 9.6),
    (8.4, 10.8),
    (4.4, 8.4),
    (1.2, 5.2),
    (6.6, 4.6),
    (2.0, 1.8),
)
#: The four ON-OFF tracking paths: start pose (x, y, θ) and goal pose (x, y, θ).
TRACK_PATHS: tuple[tuple[tuple[float, float, float], tuple[float, float, float]], ...] = (
    ((1.0, 1.0, 0.0), (13.4, 2.4, math.pi / 2)),
    ((1.2, 5.0, 0.0), (11.6, 10.2, math.pi)),
    ((13.4, 5.0, math.pi), (1.4, 8.4, math.pi / 2)),
    ((8.6, 11.2, -math.pi / 2), (4.0, 4.8, 0.0)),
)
#: Start and goal points of the planning comparison: the tracking paths' and
#: four more across the lab, m.
PLAN_ROUTES: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = (
    *(((s[0], s[1]), (g[0], g[1])) for s, g in TRACK_PATHS),
    ((1.4, 11.2), (13.0, 1.4)),
    ((7.0, 1.0), (13.2, 9.4)),
    ((1.2, 3.0), (8.0, 8.4)),
    ((11.0, 3.6), (2.6, 11.0)),
)
#: The mapping tour (the operator's route, driven once to build the map): waypoints
#: through the lab, into the side room through its door and around it, back out and
#: round the lab's west half; each leg is planned on the floor plan, m.
MAP_TOUR: tuple[tuple[float, float], ...] = (
    TOUR_START[:2],
    (6.8, 1.4),
    (10.4, 2.0),
    (13.2, 1.6),
    (13.2, 5.6),
    (11.5, 6.6),
    (11.5, 8.4),  # through the door
    (13.4, 9.0),
    (11.0, 11.0),
    (11.5, 8.4),
    (11.5, 6.6),  # and out
    (7.0, 4.6),
    (1.2, 4.6),
    (1.4, 8.4),
    (6.6, 8.8),
    (8.6, 11.2),
    (1.6, 11.2),
)
#: The rooms' inside dimensions (wall face to wall face), m, and where to measure
#: them on a map: name -> (true span, axis the span runs along, the other
#: coordinate of each measuring line, a point of the room on the span's axis).
#: The lines keep clear of the furniture.
ROOM_SPANS: dict[str, tuple[float, str, tuple[float, ...], float]] = {
    "lab width": (LAB_WIDTH - 2 * WALL, "x", (1.2, 1.6, 2.0, 4.0, 4.6, 5.0), 7.0),
    "lab depth": (LAB_HEIGHT - 2 * WALL, "y", (1.0, 1.4, 1.8, 6.4, 6.8, 7.2), 4.6),
    "side room width": (SIDE_ROOM[2] - SIDE_ROOM[0] - WALL, "x", (7.85, 7.95, 10.05, 10.15), 12.0),
    "side room depth": (SIDE_ROOM[3] - SIDE_ROOM[1] - WALL, "y", (10.4, 10.7, 12.3, 12.6), 9.0),
}


def lab_obstacles(furniture: bool) -> tuple[Polygon, ...]:
    """Walls (and furniture) of the lab as shapely boxes, world metres.

    Examples
    --------
    >>> len(lab_obstacles(False)), len(lab_obstacles(True)) > 7
    (7, True)
    """
    x0, y0, _, _ = SIDE_ROOM
    walls = (
        box(0.0, 0.0, LAB_WIDTH, WALL),
        box(0.0, LAB_HEIGHT - WALL, LAB_WIDTH, LAB_HEIGHT),
        box(0.0, 0.0, WALL, LAB_HEIGHT),
        box(LAB_WIDTH - WALL, 0.0, LAB_WIDTH, LAB_HEIGHT),
        box(x0 - WALL, y0 - WALL, x0, LAB_HEIGHT),  # side room, west wall
        box(x0 - WALL, y0 - WALL, DOOR[0], y0),  # side room, south wall left of the door
        box(DOOR[1], y0 - WALL, LAB_WIDTH, y0),  # ... and right of it
    )
    if not furniture:
        return walls
    items = (
        box(2.0, 2.6, 6.0, 3.4),  # lab bench
        box(2.0, 6.2, 6.0, 7.0),  # lab bench
        box(7.6, 5.4, 8.8, 7.6),  # central table
        box(WALL, 9.4, 0.7, LAB_HEIGHT - WALL),  # shelves, west wall
        box(11.2, WALL, LAB_WIDTH - WALL, 0.7),  # cabinets, south wall
        box(3.0, 9.8, 5.6, 10.6),  # desk
        box(12.9, 10.4, LAB_WIDTH - WALL, LAB_HEIGHT - WALL),  # side room table
        box(x0, 8.2, x0 + 0.6, 9.8),  # side room cabinet
    )
    return walls + items


@lru_cache(maxsize=8)
def lab_grid(resolution: float, furniture: bool) -> OccupancyGrid:
    """The lab's occupancy grid (a cell touching an obstacle is occupied), cached.

    Examples
    --------
    >>> lab_grid(0.1, True).shape
    (120, 144)
    """
    return OccupancyGrid.from_polygons(
        list(lab_obstacles(furniture)), bounds=(0.0, 0.0, LAB_WIDTH, LAB_HEIGHT),
        resolution=resolution,
    )  # fmt: skip


@lru_cache(maxsize=4)
def lab_world(furniture: bool) -> World:
    """The lab as a simulator world (exact boxes), cached.

    Examples
    --------
    >>> lab_world(True).collides(0.2, (1.0, 1.0, 0.0))
    False
    """
    return World(list(lab_obstacles(furniture)))


def anchored(path: Path2D, start: tuple[float, float], goal: tuple[float, float]) -> Path2D:
    """``path`` with its end points moved from cell centres to the exact start and goal.

    Examples
    --------
    >>> path = Path2D(np.array([[0.05, 0.05], [1.05, 0.05]]), "world", cost=1.0, length=1.0,
    ...               expanded=2)
    >>> anchored(path, (0.0, 0.0), (1.0, 0.0)).length
    1.0
    """
    pts = np.array(path.points, dtype=np.float64)
    pts[0] = start
    pts[-1] = goal
    seg = np.diff(pts, axis=0)
    length = float(np.sum(np.hypot(seg[:, 0], seg[:, 1])))
    return Path2D(pts, "world", cost=path.cost, length=length, expanded=path.expanded)


def heading_share(points_xy: np.ndarray, *, tolerance: float = 1e-6) -> float:
    """Share of a polyline's segments whose heading is not a multiple of 45°.

    Zero-length segments are skipped; ``tolerance`` is in radians.

    Examples
    --------
    >>> heading_share(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [2.0, 2.0], [3.0, 2.5]]))
    0.25
    """
    seg = np.diff(np.asarray(points_xy, dtype=np.float64), axis=0)
    seg = seg[np.hypot(seg[:, 0], seg[:, 1]) > 1e-12]
    if seg.shape[0] == 0:
        return 0.0
    angle = np.arctan2(seg[:, 1], seg[:, 0])
    step = math.pi / 4
    off = np.abs(angle - step * np.round(angle / step))
    return float(np.mean(off > tolerance))
