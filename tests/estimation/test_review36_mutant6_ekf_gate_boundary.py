"""The EKF's gate rejects a NIS *above* it: one equal to the gate is accepted.

Mutation gap (MUTANT6): the update kernel's ``nis > gate`` made ``nis >= gate``
passed every test. The NIS here is exact in float64 by hand: x = 0, P = I,
H = [1 0], R = [[1]], z = 2 gives y = 2, S = P₀₀ + R = 2 and NIS = y² / S = 2
(no prediction: P and the state are as given).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

H = np.array([[1.0, 0.0]])


def _update(gate: float) -> tuple[bool, float, np.ndarray]:
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    result = ekf.update(np.array([2.0]), lambda x: H @ x, H, np.eye(1), gate=gate)
    return result.accepted, result.nis, ekf.x


def test_a_nis_equal_to_the_gate_is_accepted() -> None:
    accepted, nis, x = _update(2.0)
    assert nis == 2.0
    assert accepted
    # K = P Hᵀ S⁻¹ = [1/2, 0]: x = K y = [1, 0].
    np.testing.assert_array_equal(x, [1.0, 0.0])


@pytest.mark.parametrize("gate", [math.nextafter(2.0, 0.0), 1.0])
def test_a_nis_above_the_gate_is_rejected(gate: float) -> None:
    accepted, nis, x = _update(gate)
    assert nis == 2.0
    assert not accepted
    np.testing.assert_array_equal(x, [0.0, 0.0])

