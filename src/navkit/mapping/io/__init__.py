"""Files and messages: ROS map_server maps, ROS messages, ROS bags, CARMEN laser logs, MovingAI.

* :func:`read_map` / :func:`write_map`: ROS map_server maps (YAML + PGM or, with
  Pillow, other images), as :class:`~navkit.mapping.OccupancyGrid`;
  ``OccupancyGrid.load`` and ``OccupancyGrid.save`` call them;
  :func:`map_image_path` gives the image file a map's YAML names.
* :func:`grid_from_msg` / :func:`grid_to_msg_fields`: ``nav_msgs/OccupancyGrid``
  messages (or look-alikes); :func:`scan_from_msg`: ``sensor_msgs/LaserScan``.
  ROS is never imported.
* :func:`read_carmen`: a CARMEN log (FLASER / ROBOTLASER1 lines, gzip'd or not)
  as :class:`~navkit.mapping.LaserScan` objects with their laser and robot poses
  (one :class:`~navkit.geometry.Pose2D` per scan) and times (:class:`CarmenLog`).
* :func:`read_bag_odometry`, :func:`read_bag_imu`, :func:`read_bag_scans`,
  :func:`bag_topics`: ``nav_msgs/Odometry``, ``sensor_msgs/Imu`` and
  ``sensor_msgs/LaserScan`` messages of ROS 1 and ROS 2 bags as time-stamped
  arrays (:class:`BagOdometry`, :class:`BagImu`, :class:`BagScans`), without
  ROS (the ``ros`` extra: ``rosbags``).
* :func:`read_movingai_map`, :func:`read_movingai_scenarios`: the MovingAI
  grid-pathfinding benchmarks (``.map`` terrain as :class:`MovingAIMap`, with a
  cost grid for the grid planners; ``.scen`` problems with their optimal
  lengths as :class:`MovingAIScenarios`, cells ``(row, col)``).

Every reader names its array of times, in seconds, ``times`` (a bag's header
stamps, a CARMEN line's ``timestamp`` field). ROS message helpers keep the
message's own field names: :class:`OccupancyGridMsgFields` ``width`` and
``height`` are ``info.width`` and ``info.height``, cell counts (columns and
rows), whereas :attr:`OccupancyGrid.width <navkit.mapping.OccupancyGrid.width>`
and ``height`` are extents in metres.

Every malformed file raises ``ValueError`` naming the file (and line, for
logs) and the problem — never a decoder's own exception (``UnicodeDecodeError``,
Pillow's errors, ``gzip.BadGzipFile``, ``EOFError``, ``OverflowError``). A
missing file raises ``FileNotFoundError``; a file the operating system refuses
to read its ``OSError`` (e.g. ``PermissionError``); a non-PGM image without
Pillow ``ImportError``. Image sizes are checked from the header before
decoding; a map's YAML and image are checked to be regular files on the
descriptor they are then read from. Saving is atomic and never writes over the
map's image or another image file. ROS bags are read with ``rosbags``, through
paths whose opens check on the descriptor that a ROS 1 bag, a ROS 2 bag's
``metadata.yaml`` and its MCAP files are regular files (a FIFO put in their
place is refused, never read); a ROS 2 bag's SQLite files are opened by SQLite
by name, so a FIFO swapped in for one while it is being opened would block the
read. ROS 2 bags compressed with zstd are decompressed by rosbags with no bound
on their size (a ``file``-mode bag whole into a temporary folder), so read those
only from a trusted source.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> import numpy as np
>>> from navkit.mapping import OccupancyGrid
>>> grid = OccupancyGrid.from_occupancy(np.eye(2, dtype=bool), resolution=0.1)
>>> with tempfile.TemporaryDirectory() as folder:
...     image = write_map(grid, Path(folder) / "map.yaml")
...     read_map(Path(folder) / "map.yaml").occupied().tolist()
[[True, False], [False, True]]
>>> grid_to_msg_fields(grid, mode="trinary").data
array([100,   0,   0, 100], dtype=int8)
"""

from navkit.mapping import MapMode
from navkit.mapping.io._bags import (
    BagImu,
    BagOdometry,
    BagScans,
    bag_topics,
    read_bag_imu,
    read_bag_odometry,
    read_bag_scans,
)
from navkit.mapping.io._carmen import CarmenLog, read_carmen
from navkit.mapping.io._map_files import map_image_path, read_map, write_map
from navkit.mapping.io._movingai import (
    MovingAIMap,
    MovingAIScenarios,
    read_movingai_map,
    read_movingai_scenarios,
)
from navkit.mapping.io._ros_msgs import (
    OccupancyGridMsgFields,
    grid_from_msg,
    grid_to_msg_fields,
    scan_from_msg,
)

__all__ = [
    "BagImu",
    "BagOdometry",
    "BagScans",
    "CarmenLog",
    "MapMode",
    "MovingAIMap",
    "MovingAIScenarios",
    "OccupancyGridMsgFields",
    "bag_topics",
    "grid_from_msg",
    "grid_to_msg_fields",
    "map_image_path",
    "read_bag_imu",
    "read_bag_odometry",
    "read_bag_scans",
    "read_carmen",
    "read_map",
    "read_movingai_map",
    "read_movingai_scenarios",
    "scan_from_msg",
    "write_map",
]
