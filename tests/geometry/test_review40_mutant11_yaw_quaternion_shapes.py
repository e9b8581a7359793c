"""``yaw_to_quaternion`` of an array of yaws: shape (..., 4), each row the scalar call's.

Review 40 (mutation testing, MUTANT11). The stack's ``axis=-1`` read as ``axis=0``
passed every geometry test (they convert one yaw at a time, where both give shape
(4,)): an array of N yaws then came back (4, N), not the documented (..., 4).
Oracle: the quaternion of a yaw about z written out, (0, 0, sin(ψ/2), cos(ψ/2)),
and the scalar calls.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw, yaw_to_quaternion


@pytest.mark.parametrize("shape", [(3,), (4,), (2, 3), (1, 4), (0,)])
def test_rows_are_the_scalar_quaternions(shape: tuple[int, ...]) -> None:
    yaws = np.random.default_rng(40).uniform(-math.pi, math.pi, shape)
    q = yaw_to_quaternion(yaws)
    assert q.shape == (*shape, 4)
    for index in np.ndindex(shape):
        psi = float(yaws[index])
        assert q[index].tolist() == yaw_to_quaternion(psi).tolist()
        expected = [0.0, 0.0, math.sin(psi / 2), math.cos(psi / 2)]
        np.testing.assert_allclose(q[index], expected, rtol=0, atol=1e-15)
    if q.size:
        np.testing.assert_allclose(quaternion_to_yaw(q), yaws, rtol=0, atol=1e-14)
