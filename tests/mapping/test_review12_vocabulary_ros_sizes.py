"""``width`` and ``height``: metres on an ``OccupancyGrid``, cells in ROS messages.

The ROS message helpers keep ``nav_msgs/MapMetaData``'s field names, so
``grid_to_msg_fields(grid).width`` is a column count where ``grid.width`` is an
extent in metres (as the mapping guide and the docstrings now say).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_from_msg, grid_to_msg_fields


def test_message_sizes_are_cells_and_grid_sizes_metres() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=0.5, resolution=0.25)  # 2 rows x 8 cols
    fields = grid_to_msg_fields(grid)
    assert (fields.width, fields.height) == (grid.shape[1], grid.shape[0]) == (8, 2)
    assert (grid.width, grid.height) == (2.0, 0.5)
    assert isinstance(fields.width, int) and isinstance(grid.width, float)
    info = SimpleNamespace(
        width=fields.width,
        height=fields.height,
        resolution=fields.resolution,
        origin=SimpleNamespace(
            position=SimpleNamespace(**dict(zip("xyz", fields.origin_position, strict=True))),
            orientation=SimpleNamespace(
                **dict(zip("xyzw", fields.origin_orientation, strict=True))
            ),
        ),
    )
    back = grid_from_msg(SimpleNamespace(info=info, data=fields.data.tolist()))
    assert back.shape == grid.shape and back.width == grid.width
    np.testing.assert_array_equal(back.logodds, grid.logodds)
