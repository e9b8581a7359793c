"""Global planning on traversal-cost grids: A*, distance fields, Field D*, map planning.

Planners work on per-cell traversal-cost grids indexed ``[row, col]`` (finite
values >= 1, ``np.inf`` impassable; :func:`navkit.mapping.traversal_costs` builds
them from an occupancy grid). Units are SI; grid cells are ``(row, col)``, world
points ``(x, y)``.
"""

from navkit.planning.grid._astar import GridPath, astar
from navkit.planning.grid._distance_field import distance_field
from navkit.planning.grid._field_dstar import FieldDStar, FieldPath, field_dstar
from navkit.planning.grid._map_planner import WorldPath, plan_path

__all__ = [
    "FieldDStar",
    "FieldPath",
    "GridPath",
    "WorldPath",
    "astar",
    "distance_field",
    "field_dstar",
    "plan_path",
]
