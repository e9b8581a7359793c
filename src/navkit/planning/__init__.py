"""Planning: global planning on cost grids and reactive navigation.

Two halves that never import each other, both re-exported here:

* :mod:`navkit.planning.grid` — global planning on traversal-cost grids (A*,
  distance fields, Field D* with incremental replanning, planning on an
  :class:`~navkit.mapping.OccupancyGrid` in world coordinates);
* :mod:`navkit.planning.reactive` — reactive navigation (potential fields,
  repulsion summed per laser beam, the greedy laser-grid step).
"""

# ruff: noqa: F405  (the names listed in __all__ come from the star imports)
from navkit.planning.grid import *  # noqa: F403
from navkit.planning.reactive import *  # noqa: F403

# A literal list, not one computed from the halves' ``__all__``: type checkers
# read only a literal ``__all__``, so ``from navkit.planning import *`` in user
# code would otherwise import nothing under mypy (a test keeps it in sync).
__all__ = [
    "AStarPlanner",
    "AttractiveField",
    "BlendedAttraction",
    "CellPlanner",
    "CompositeField",
    "ConicAttraction",
    "FieldDStar",
    "GreedyStep",
    "KhatibRepulsion",
    "MapPlanner",
    "ParaboloidAttraction",
    "Path2D",
    "PiecewiseAttraction",
    "PiecewiseRepulsion",
    "PotentialField",
    "SampledField",
    "astar",
    "distance_field",
    "field_dstar",
    "greedy_step",
    "piecewise_repulsive_force_from_scan",
    "plan_path",
    "repulsive_force_from_scan",
    "sample_field",
]
