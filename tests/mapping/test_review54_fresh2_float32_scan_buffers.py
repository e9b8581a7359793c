"""Float32 ranges as a buffer or another library's array compare in float32 (review 54, FRESH2).

bcb53cd reads a reading of a float32 (or float16) ranges array equal to
``range_max`` in that precision (5.6 m written as 5.599999904632568) as
``range_max``, "no return", where it read as a return 5.6 m away and mapping
marked an obstacle at its end. The dtype was asked of ndarrays, NumPy scalars,
lists, tuples and ``array.array`` only: the same float32 readings as a
``memoryview`` (of an ``array.array('f')``, a ctypes or a message buffer) or as
an array of another library that NumPy converts (``__array__``, whose own
``dtype`` is no NumPy dtype) were read as float64 and were returns again.
"""

from __future__ import annotations

import array
from typing import Any

import numpy as np
import pytest

from navkit._shared.float32 import narrow_float_dtype
from navkit.mapping import LaserScan

ANGLES = {"angle_min": -0.1, "angle_increment": 0.1}


class _Foreign:
    """An array of another library: NumPy converts it, its dtype is its own."""

    def __init__(self, values: np.ndarray) -> None:
        self._values = values
        self.dtype = f"foreign.{values.dtype}"  # not a NumPy dtype

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return self._values if dtype is None else self._values.astype(dtype)

    def __len__(self) -> int:
        return len(self._values)


def _readings(kind: str, dtype: str) -> Any:
    values = np.array([5.6, 1.0, 5.6], dtype=dtype)
    if kind == "memoryview":
        if dtype == "float32":
            return memoryview(array.array("f", values.tolist()))
        return values.data  # array.array has no half floats: a NumPy array's buffer
    return _Foreign(values)


@pytest.mark.parametrize("kind", ["memoryview", "foreign"])
@pytest.mark.parametrize("dtype", ["float32", "float16"])
def test_readings_at_range_max_are_no_return(kind: str, dtype: str) -> None:
    ranges = _readings(kind, dtype)
    assert narrow_float_dtype(ranges) == np.dtype(dtype)
    scan = LaserScan(ranges, range_min=0.05, range_max=5.6, **ANGLES)
    assert scan.valid_mask().tolist() == [False, True, False]
    assert scan.ranges.tolist() == [5.6, 1.0, 5.6]


def test_float64_buffers_are_left_as_they_are() -> None:
    buffer = memoryview(array.array("d", [float(np.float32(5.6)), 1.0]))
    assert narrow_float_dtype(buffer) is None
    scan = LaserScan(buffer, range_min=0.05, range_max=5.6, **ANGLES)
    assert scan.valid_mask().tolist() == [True, True]  # 5.5999999 m, typed in float64


def test_a_foreign_array_numpy_cannot_convert_is_no_narrow_dtype() -> None:
    class Broken:
        dtype = "foreign.float32"

        def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
            raise TypeError("no conversion")

    assert narrow_float_dtype(Broken()) is None
