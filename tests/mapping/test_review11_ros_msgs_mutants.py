"""OccupancyGridMsgFields keeps to its documented shapes (mutation testing).

Accepting an ``origin_position`` / ``origin_orientation`` longer than the
message's fields, or a 2-D ``data`` whose first axis happens to have
``width * height`` entries, left every earlier test passing.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import OccupancyGridMsgFields

_POS = (0.0, 0.0, 0.0)
_QUAT = (0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize(
    ("position", "orientation", "name", "n", "got"),
    [
        ((0.0, 0.0, 0.0, 0.0), _QUAT, "origin_position", 3, 4),
        ((0.0, 0.0), _QUAT, "origin_position", 3, 2),
        (_POS, (0.0, 0.0, 0.0, 1.0, 0.0), "origin_orientation", 4, 5),
        (_POS, (0.0, 0.0, 1.0), "origin_orientation", 4, 3),
    ],
)
def test_origin_tuples_must_have_the_message_lengths(
    position: Any, orientation: Any, name: str, n: int, got: int
) -> None:
    with pytest.raises(ValueError, match=rf"^{name} must hold {n} numbers, got {got}"):
        OccupancyGridMsgFields(2, 1, 0.1, position, orientation, [0, 100])


@pytest.mark.parametrize(
    ("width", "height", "data"),
    [(1, 1, [[5]]), (1, 2, [[0], [100]]), (2, 1, np.zeros((2, 1), dtype=np.int8))],
)
def test_data_must_be_flat(width: int, height: int, data: Any) -> None:
    # "data : array_like of int, shape (width * height,)": row-major and flat, as
    # the message's int8[] field; a column of the right length is no such array.
    with pytest.raises(ValueError, match=r"^data must have shape"):
        OccupancyGridMsgFields(width, height, 0.1, _POS, _QUAT, data)


def test_flat_data_of_the_right_length_is_kept_flat() -> None:
    fields = OccupancyGridMsgFields(1, 2, 0.1, _POS, _QUAT, [0, 100])
    assert fields.data.shape == (2,)
    assert fields.origin_position == _POS and fields.origin_orientation == _QUAT
