"""``PlanarFusion(history=)``: a window reaching back to the clock's origin keeps its first step.

The steps kept go once older than ``history + _TRIM_RTOL (|t| + |t0| + history)``
(``_record``; ``|t0| + history`` is worked out when the filter is made or
copied, and when its clock is set). A mutant making that scale
``|t0| - history`` where the filter is made (or copied) survived the suite
(review 38, mutation): its tests of stamps exactly ``history`` late fed a P0
without correlations, and at the origin, before any prediction, an odometry and
a yaw update then commute bit for bit, so fusing the late odometry after the
origin's yaw step (the step trimmed) went unseen. With a correlated P0 the order
shows: late odometry stamped at ``t0``, exactly ``history`` late (its age rounded
above ``history``), must give the numbers of a filter fed in stamp order,
odometry before yaw at a stamp (:meth:`MeasurementLog.from_streams`'s order).
"""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

from navkit.estimation import PlanarFusion

# A correlated initial covariance: updates of different components at one stamp do
# not commute bit for bit.
_A = np.random.default_rng(5).normal(size=(6, 6))
_P0 = _A @ _A.T * 0.1 + np.eye(6) * 0.05

# (t0, rate, n): n steps at t0 + k / rate, the window n / rate (back to t0 exactly).
_CASES = [
    (-0.06, 3.3, 2),
    (-0.03, 10.0, 3),
    (-0.035, 7.0, 3),
    (-0.166, 7.0, 3),
    (-0.14, 3.3, 4),
    (-0.64, 3.0, 5),
    (-0.3, 6.0, 5),
    (-0.07, 11.0, 7),
]


def _state(f: PlanarFusion) -> tuple[float | None, bytes, bytes]:
    return f.t, f.x.tobytes(), f.P.tobytes()


def _odometry(f: PlanarFusion, t: float) -> bool:
    return f.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4).accepted


def _yaw(f: PlanarFusion, t: float, k: int) -> bool:
    return f.update_yaw(t, 0.01 * k, variance=1e-3).accepted


def _run(t0: float, rate: float, n: int, renew: str) -> tuple[PlanarFusion, PlanarFusion]:
    fusion = PlanarFusion(t0=t0, P0=_P0, history=n / rate)
    expected = PlanarFusion(t0=t0, P0=_P0)
    for k in range(n + 1):
        t = t0 + k / rate
        if k:  # the odometry at t0 comes late
            assert _odometry(fusion, t)
        assert _yaw(fusion, t, k)
        assert _odometry(expected, t) and _yaw(expected, t, k)
        if k == 0 and renew == "copy":
            fusion = copy.deepcopy(fusion)
        elif k == 0 and renew == "pickle":
            fusion = pickle.loads(pickle.dumps(fusion))
    return fusion, expected


@pytest.mark.parametrize("renew", ["", "copy", "pickle"])
@pytest.mark.parametrize(("t0", "rate", "n"), _CASES)
def test_late_odometry_at_the_origin_goes_before_its_yaw(
    t0: float, rate: float, n: int, renew: str
) -> None:
    t = t0 + n / rate
    assert t - t0 > n / rate  # the origin's age rounds above the window: the slack's case
    fusion, expected = _run(t0, rate, n, renew)
    assert _state(fusion) != _state(expected)  # the odometry at t0 is still missing
    assert _odometry(fusion, t0)
    assert _state(fusion) == _state(expected)


def test_the_order_at_the_origin_shows_with_this_p0() -> None:
    """The oracle's premise: yaw then odometry at t0 differs from odometry then yaw."""
    a = PlanarFusion(t0=0.0, P0=_P0)
    b = PlanarFusion(t0=0.0, P0=_P0)
    assert _odometry(a, 0.0) and _yaw(a, 0.0, 0)
    assert _yaw(b, 0.0, 0) and _odometry(b, 0.0)
    assert _state(a) != _state(b)
