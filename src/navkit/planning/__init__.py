"""Planning: global planning on cost grids and reactive navigation.

Two halves that never import each other, both re-exported here:

* :mod:`navkit.planning.grid` — global planning on traversal-cost grids (A*,
  distance fields, Field D* with incremental replanning, planning on an
  :class:`~navkit.mapping.OccupancyGrid` in world coordinates);
* :mod:`navkit.planning.reactive` — reactive navigation (potential fields,
  repulsion summed per laser beam, the greedy laser-grid step).
"""

from navkit.planning.grid import *  # noqa: F403
from navkit.planning.grid import __all__ as _grid_all
from navkit.planning.reactive import *  # noqa: F403
from navkit.planning.reactive import __all__ as _reactive_all

__all__ = sorted([*_grid_all, *_reactive_all])
