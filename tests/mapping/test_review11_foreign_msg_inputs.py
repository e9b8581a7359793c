"""Masked arrays in ROS message fields (review 11).

``OccupancyGridMsgFields`` read a masked ``data`` array (or a masked origin
coordinate) as its data: a cell masked as "no value" became whatever number
was underneath.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping.io import OccupancyGridMsgFields


def _fields(**kw: object) -> OccupancyGridMsgFields:
    args: dict[str, object] = {
        "width": 2,
        "height": 2,
        "resolution": 0.1,
        "origin_position": (0.0, 0.0, 0.0),
        "origin_orientation": (0.0, 0.0, 0.0, 1.0),
        "data": np.array([0, 100, -1, 0], dtype=np.int8),
    }
    args.update(kw)
    return OccupancyGridMsgFields(**args)  # type: ignore[arg-type]


def test_masked_cells_are_refused() -> None:
    data = np.ma.array(np.array([0, 100, -1, 0], dtype=np.int8), mask=[False, True, False, False])
    with pytest.raises(ValueError, match=r"^data has masked entries"):
        _fields(data=data)


def test_a_masked_origin_coordinate_is_refused() -> None:
    origin = np.ma.array([0.0, 1.0, 0.0], mask=[False, True, False])
    with pytest.raises(ValueError, match=r"^origin_position\[1\] has masked entries"):
        _fields(origin_position=origin)


def test_masked_arrays_without_masked_entries_are_their_data() -> None:
    plain = _fields()
    masked = _fields(
        data=np.ma.array(plain.data), origin_position=np.ma.array(plain.origin_position)
    )
    assert np.array_equal(masked.data, plain.data)
    assert masked.origin_position == plain.origin_position


def test_a_two_d_memoryview_origin_is_a_type_error() -> None:
    with pytest.raises(TypeError, match=r"^origin_position\[0\] must be a real number"):
        _fields(origin_position=np.zeros((3, 1)).data)
