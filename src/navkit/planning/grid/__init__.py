"""Global planning on traversal-cost grids: A*, distance fields, Field D*, map planning.

Planners work on per-cell traversal-cost grids indexed ``[row, col]`` (finite
values in ``[1, 1e12]``, ``np.inf`` impassable; :func:`navkit.mapping.traversal_costs` builds
them from an occupancy grid). Units are SI. Every planner returns a
:class:`Path2D` whose ``frame`` says what its points are: ``"grid"`` —
continuous ``(row, col)`` with integers at cell centres — or ``"world"`` —
``(x, y)`` in metres. Cells are ``*_cell`` ``(row, col)``, Field D* corner nodes
``*_node`` ``(i, j)`` (at continuous ``(i - 0.5, j - 0.5)``), world points
``*_xy``.

One-shot functions (:func:`astar`, :func:`distance_field`, :func:`field_dstar`,
:func:`plan_path`) validate their input on every call; the prepared planners
(:class:`AStarPlanner`, :class:`FieldDStar`, :class:`MapPlanner`) do it once and
answer many queries.

Ranges, the same for every planner: finite costs in ``[1, 1e12]`` (or ``inf``)
on at most ``2**31 - 1`` cells (Field D*: corner nodes), ``heuristic_weight`` in
``[0, 1e6]``; Field D* path costs below ``2**52`` cost units × cells (float64
resolution, see :class:`FieldDStar`), its ``resolution`` in ``[1e-6, 1e6]`` m
and world points within ``±1e9`` m; ``robot_radius`` in ``[0, 1e6]`` m. Flags
are ``True`` or ``False`` only and cells pairs of integers. Bad input raises
``ValueError`` or ``TypeError`` naming the argument; an unreachable goal
:class:`navkit.NoPathError`.
"""

from navkit.planning.grid._astar import AStarPlanner, astar
from navkit.planning.grid._distance_field import distance_field
from navkit.planning.grid._field_dstar import FieldDStar, field_dstar
from navkit.planning.grid._map_planner import CellPlanner, MapPlanner, plan_path
from navkit.planning.grid._path import Path2D

__all__ = [
    "AStarPlanner",
    "CellPlanner",
    "FieldDStar",
    "MapPlanner",
    "Path2D",
    "astar",
    "distance_field",
    "field_dstar",
    "plan_path",
]
