"""Occupancy grids, ROS map files, laser scans and laser-to-grid ray casting.

Conventions: units are SI (m, rad); world points are ``(x, y)``; grid cells are
``(row, col)`` indexing ``array[row, col]`` with row 0 at the lowest y, as in ROS
``nav_msgs/OccupancyGrid``. Readers for real log files live in
:mod:`navkit.mapping.io`.
"""

from navkit.mapping._carmen import CarmenLog, read_carmen
from navkit.mapping._grid import OccupancyGrid, OccupancyGridFields
from navkit.mapping._scan import LaserScan, LocalGrid

__all__ = [
    "CarmenLog",
    "LaserScan",
    "LocalGrid",
    "OccupancyGrid",
    "OccupancyGridFields",
    "read_carmen",
]
