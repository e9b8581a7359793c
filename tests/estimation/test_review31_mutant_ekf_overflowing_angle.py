"""An angle residual whose difference overflows is the difference of the wrapped angles.

Review 31 (mutants). Where ``z - h(x)`` of an angle measurement overflows
(angles near ±1.8e308), the EKF kernel takes ``wrap(wrap(z) - wrap(h))``, as
``angle_diff`` does. No test reached that branch with both angles wrapped:
dropping the wrap of ``z`` (so that ``z - wrap(h)`` is ``z`` again, ``h``
absorbed) passed the suite. Oracle: ``math.fmod`` by the float 2π and one fold
into (-π, π], computed here. Checked: the test fails on that mutant of
``_ekf_kernels.py`` and passes on HEAD.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter


def _wrapped(a: float) -> float:
    r = math.fmod(a, 2.0 * math.pi)
    if r > math.pi:
        return r - 2.0 * math.pi
    if r <= -math.pi:
        return r + 2.0 * math.pi
    return r


@pytest.mark.parametrize(("z", "h"), [(1.7e308, -1.7e308), (-1.6e308, 1.5e308)])
def test_an_overflowing_angle_residual_wraps_both_angles(z: float, h: float) -> None:
    assert math.isinf(z - h)
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    out = ekf.update([z], lambda x: np.array([h]), np.eye(1), [[1.0]], angle_measurements=(0,))
    expected = _wrapped(_wrapped(z) - _wrapped(h))
    assert out.accepted
    assert out.residual.shape == (1,)
    assert out.residual[0] == pytest.approx(expected, abs=1e-12)
