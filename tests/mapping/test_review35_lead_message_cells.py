"""ROS map cells are refused as log-odds however they arrive, not only as an ndarray.

rclpy gives a ``nav_msgs/OccupancyGrid``'s ``data`` as ``array.array('b')``;
rows of it, a memoryview of int8 cells or an object whose ``__array__`` gives
int8 or uint8 were taken as log-odds silently (free cells 0 = unknown), while
the same cells as an ndarray were refused with a pointer to ``grid_from_msg``.
"""

from __future__ import annotations

import array
from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid

_CELLS = np.array([[0, 100, -1], [0, 0, 100]], dtype=np.int8)


class _Cells:
    def __init__(self, cells: np.ndarray[Any, Any]) -> None:
        self._cells = cells

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray[Any, Any]:
        return self._cells


@pytest.mark.parametrize(
    "value",
    [
        [array.array("b", row.tolist()) for row in _CELLS],
        memoryview(_CELLS),
        _Cells(_CELLS),
        _Cells(_CELLS.astype(np.uint8)),
        [[np.int8(0), np.int8(100)]],
    ],
    ids=["array.array rows", "memoryview", "__array__ int8", "__array__ uint8", "int8 scalars"],
)
def test_message_cells_in_any_container_are_refused(value: object) -> None:
    with pytest.raises(
        TypeError, match=r"logodds must hold log-odds, got dtype u?int8.*grid_from_msg"
    ):
        OccupancyGrid(value, resolution=0.1)  # type: ignore[arg-type]


def test_the_same_values_as_plain_numbers_are_still_log_odds() -> None:
    grid = OccupancyGrid(_CELLS.tolist(), resolution=0.1)
    np.testing.assert_array_equal(grid.logodds, _CELLS.astype(np.float32))
    wider = OccupancyGrid(memoryview(_CELLS.astype(np.int16)), resolution=0.1)
    np.testing.assert_array_equal(wider.logodds, _CELLS.astype(np.float32))


def test_a_value_numpy_cannot_convert_gets_the_general_error() -> None:
    with pytest.raises((TypeError, ValueError), match="logodds"):
        OccupancyGrid([[0.0, 1.0], [2.0]], resolution=0.1)  # type: ignore[arg-type]
