"""Readers for real robot log files.

``read_carmen`` turns a CARMEN log (FLASER / ROBOTLASER1 lines, gzip'd or not)
into :class:`~navkit.mapping.LaserScan` objects with their laser and robot poses
and timestamps; ROS map_server maps are read by
:meth:`navkit.mapping.OccupancyGrid.load`.
"""

from navkit.mapping._carmen import CarmenLog, read_carmen

__all__ = ["CarmenLog", "read_carmen"]
