"""ticks_to_distance returns a Python float for a scalar count (its overload says float).

Found by mutation testing (session 14): returning the 0-d array for scalar input
survived every other kinematics test (a 0-d array compares equal to the float).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.kinematics import ticks_to_distance


@pytest.mark.parametrize("ticks", [1024, -3, 2.5, np.int64(7), np.float32(4.0)])
def test_scalar_ticks_give_a_python_float(ticks: float) -> None:
    d = ticks_to_distance(ticks, ticks_per_rev=2048, wheel_radius=0.1)
    assert type(d) is float
    assert d == pytest.approx(2.0 * math.pi * 0.1 * float(ticks) / 2048, rel=1e-15)


def test_array_ticks_give_an_array_of_their_shape() -> None:
    d = ticks_to_distance([[1.0, 2.0]], ticks_per_rev=4, wheel_radius=1.0)
    assert isinstance(d, np.ndarray) and d.shape == (1, 2)
    np.testing.assert_allclose(d, [[math.pi / 2, math.pi]])
