"""Ragged counter readings are a wrong shape (``ValueError``), as every array's are.

docs/getting-started.md: "A wrong shape, including a ragged nesting such as
``[[1, 2], [3]]``, is a ``ValueError``". The float converters said so; the
integer counter readings (``tick_delta``, the wheel odometry's ticks) raised a
``TypeError`` instead.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit._shared.validation import integer_readings
from navkit.kinematics import tick_delta

RAGGED: list[Any] = [
    [[1, 2], [3]],
    [[1, 2], 3],
    ([1], [2, 3], [4]),
    [np.array([1, 2]), np.array([3])],
]


@pytest.mark.parametrize("value", RAGGED)
def test_integer_readings_refuse_ragged_as_a_shape(value: Any) -> None:
    with pytest.raises(ValueError, match=r"ticks must be a rectangular array.*ragged"):
        integer_readings(value, "ticks")


@pytest.mark.parametrize("value", RAGGED)
@pytest.mark.parametrize("which", ["previous", "current"])
def test_tick_delta_names_the_ragged_argument(value: Any, which: str) -> None:
    args = {"previous": 0, "current": 0, which: value}
    with pytest.raises(ValueError, match=rf"^{which} must be a rectangular array"):
        tick_delta(args["previous"], args["current"], bits=16)


@pytest.mark.parametrize("value", [[1.5, 2], "12", [object()], [1, None]])
def test_non_integer_readings_are_still_a_type_error(value: Any) -> None:
    with pytest.raises(TypeError, match="ticks must hold integer counter readings"):
        integer_readings(value, "ticks")


def test_rectangular_readings_still_read() -> None:
    out = tick_delta([[65535, 0], [1, 2]], [[2, 65535], [1, 0]], bits=16)
    assert np.asarray(out).tolist() == [[3, -1], [0, -2]]
