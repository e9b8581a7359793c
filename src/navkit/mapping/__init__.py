"""Occupancy grids, laser scans, ray casting, costmaps and rasterised obstacles.

Conventions: units are SI (m, rad); world points are ``(x, y)`` (``points_xy``);
grid cells are ``(row, col)`` indexing ``array[row, col]`` with row 0 at the
lowest y, as in ROS ``nav_msgs/OccupancyGrid``; continuous grid coordinates are
float ``(row, col)`` with integers at cell centres.

* :class:`OccupancyGrid`: log-odds storage, grid ⇄ world coordinates, views and
  inflation; its methods ``from_polygons``, ``costmap``, ``traversal_costs``,
  ``integrate_scan``, ``load`` and ``save`` are conveniences calling
  :func:`rasterize_polygons`, :func:`costmap`, :func:`traversal_costs`,
  :func:`integrate_scan` and :mod:`navkit.mapping.io`.
* :class:`LaserScan` and the robot-centred :class:`LocalGrid`.
* :func:`distance_transform`: the exact Euclidean distance transform of any
  boolean mask of cells (``OccupancyGrid.obstacle_distance``'s, of other cells).
* :func:`validate_costs`: the grid planners' traversal-cost convention.
* :mod:`navkit.mapping.io`: map files, ROS messages and CARMEN logs.

Ranges, checked where objects are built (``ValueError`` naming the argument
and the range; ``TypeError`` for a wrong type: complex numbers, strings and
booleans are not numbers, flags must be ``bool``):

* grids hold at most ``OccupancyGrid.MAX_CELLS`` = 2**28 cells; sizes are
  checked before anything is allocated and the message says how many cells
  (and bytes) a request would need;
* ``resolution`` in [1e-6, 1e6] m; grid origin x, y within ±1e9 m; log-odds
  (stored, ``hit``, ``miss``, ``clamp``) within ±1e6;
* ``robot_radius``, ``inflation_radius``, ``half_width`` in [0, 1e6] m;
  ``cost_scaling_factor`` in (0, 1e12] 1/m; ``cost_weight`` in [0, 1e9];
  ``unknown_cost`` in [1, 1e9] or ``inf``; thresholds in [0, 1] with
  ``free_thresh < occupied_thresh``;
* laser ``range_max`` at most 1e9 m; beam angles within ±2π, spanning at
  most a full turn (more means degrees given as radians: the message says so;
  1e-5 rad of slack for angles rounded to float32 in ROS messages);
* world points and grid coordinates may be any finite numbers: cells of far
  points are clamped to ±2**62, and coordinates beyond ±2**62 cells are refused.

Inside these ranges finite input never gives NaN; ``inf`` appears only where
documented (impassable traversal costs).

Examples
--------
>>> grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.5)
>>> scan = LaserScan([1.2], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=3.0)
>>> integrate_scan(grid, scan, (0.25, 0.25, 0.0))
3
>>> grid.occupied().astype(int)
array([[0, 0, 1, 0],
       [0, 0, 0, 0]])
>>> traversal_costs(grid, unknown_cost=1.0).tolist()
[[1.0, 1.0, inf, 1.0], [1.0, 1.0, 1.0, 1.0]]
"""

from navkit.mapping._costs import costmap, traversal_costs, validate_costs
from navkit.mapping._distance_transform import distance_transform
from navkit.mapping._grid import MapMode, OccupancyGrid
from navkit.mapping._local_grid import LocalGrid
from navkit.mapping._rasterize import rasterize_polygons
from navkit.mapping._raycast import integrate_scan
from navkit.mapping._scan import LaserScan
from navkit.mapping._scan_mapper import ScanMapper
from navkit.mapping._scan_matcher import ScanMatcher, ScanMatchReason, ScanMatchResult

__all__ = [
    "LaserScan",
    "LocalGrid",
    "MapMode",
    "OccupancyGrid",
    "ScanMapper",
    "ScanMatchReason",
    "ScanMatchResult",
    "ScanMatcher",
    "costmap",
    "distance_transform",
    "integrate_scan",
    "rasterize_polygons",
    "traversal_costs",
    "validate_costs",
]
