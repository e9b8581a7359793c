"""ROS map cells given to OccupancyGrid as log-odds are refused (review 34).

``OccupancyGrid(data)`` with a nav_msgs/OccupancyGrid's int8 cells (0 free,
100 occupied, -1 unknown) or a Nav2 costmap's uint8 cells took them as log-odds
silently (found by the integrator lens): free cells (0) came out unknown, -1
nearly unknown, a costmap's lethal 254 occupied and its free 0 unknown. A
boolean mask was already refused naming ``from_occupancy``; these are now
refused naming the message reader.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_from_msg
from ros_fakes import OccupancyGrid as OccupancyGridMsg


@pytest.mark.parametrize("dtype", [np.int8, np.uint8])
def test_message_cells_are_refused_naming_the_reader(dtype: type) -> None:
    cells = np.zeros((4, 5), dtype=dtype)
    cells[0] = 100
    before = cells.copy()
    with pytest.raises(TypeError, match=r"logodds .*int8|logodds .*uint8") as info:
        OccupancyGrid(cells, resolution=0.1)
    assert "grid_from_msg" in str(info.value)
    np.testing.assert_array_equal(cells, before)


def test_the_percentages_conversion_the_message_names_gives_the_map() -> None:
    # The message's own advice, followed: free cells free, 100 occupied, -1 unknown.
    cells = np.array([[0, 100, -1], [0, 0, 100]], dtype=np.int8)
    grid = OccupancyGrid.from_probabilities(np.where(cells < 0, 0.5, cells / 100), resolution=0.1)
    np.testing.assert_array_equal(grid.occupied(), cells == 100)
    np.testing.assert_array_equal(grid.free(), cells == 0)
    np.testing.assert_array_equal(grid.unknown(), cells < 0)


@pytest.mark.parametrize("dtype", [np.int16, np.int32, np.int64, np.uint16, np.float32])
def test_other_real_arrays_are_still_log_odds(dtype: type) -> None:
    values = np.array([[0, 3], [-2, 1]]).astype(dtype)
    grid = OccupancyGrid(values, resolution=0.1)
    np.testing.assert_array_equal(grid.logodds, values.astype(np.float32))


def test_a_message_read_with_the_reader_is_the_map() -> None:
    cells = np.array([[0, 100, -1], [0, 0, 100]], dtype=np.int8)
    msg = OccupancyGridMsg()
    msg.info.resolution, msg.info.width, msg.info.height = 0.1, 3, 2
    msg.info.origin.orientation.w = 1.0
    msg.data = cells.ravel().tolist()
    grid = grid_from_msg(msg)
    np.testing.assert_array_equal(grid.occupied(), cells == 100)
    np.testing.assert_array_equal(grid.free(), cells == 0)
    np.testing.assert_array_equal(grid.unknown(), cells < 0)
