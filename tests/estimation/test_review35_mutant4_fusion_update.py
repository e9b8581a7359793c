"""A PlanarFusion update whose new state would overflow is not applied (``OVERFLOW``).

Review 35 (mutation testing, MUTANT4). The step checks the updated state
finite after a finite NIS (``if z != 0.0: return OVERFLOW, nis`` in
``_fusion_kernels._planar_step``); deleting that check passed the suite,
whose overflow tests all overflowed the residual or the NIS first, so the
filter could commit an infinite position. Reaching it takes a finite NIS and
a gain that carries a huge speed residual into a position at the top of the
float64 range: after a prediction over 1e101 s the position's covariance with
the speed is dt·P_vv, so the gain of a speed reading on x is about dt. Oracle:
that gain and the updated x computed here from the prediction written out
(P_vv' = P_vv + dt² P_aa, P_xv' = dt P_vv'), where x + K y exceeds the largest
float; the prediction (kept) is compared with a twin filter's plain predict.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion

_X0 = [1.7976931e308, 0.0, 0.0, 0.0, 0.0, 0.0]
_P0 = np.diag([1e-100, 1e-100, 1e-100, 1e100, 1e-100, 1e-100])
_DT = 1e101
_V = 1e204


def _filter(x: float = _X0[0]) -> PlanarFusion:
    return PlanarFusion([x, *_X0[1:]], _P0, process_noise=np.zeros(6), t0=0.0)


def _gain() -> float:
    # x' = x + v dt + a dt²/2 (heading 0), v' = v + a dt; P diagonal: P_xx, P_vv, P_aa.
    p_vv, p_aa = 1e100, 1e-100
    pv = p_vv + _DT * _DT * p_aa
    pxv = _DT * p_vv + (_DT * _DT / 2) * (_DT * p_aa)
    return pxv / (pv + 1.0)  # K of a speed reading of variance 1 on x


def test_the_oracle_says_the_update_overflows_with_a_finite_nis() -> None:
    s = 1e100 + _DT * _DT * 1e-100 + 1.0
    assert math.isfinite((_V / s) * _V)  # the NIS
    assert math.isinf(_X0[0] + _gain() * _V)


def test_an_update_overflowing_the_state_keeps_the_prediction_online() -> None:
    f = _filter()
    out = f.update_speed(_DT, _V, variance=1.0)
    assert out.status == FusionStatus.OVERFLOW
    assert not out.accepted
    assert math.isfinite(out.nis)
    twin = _filter()
    twin.predict(_DT)
    assert np.isfinite(f.x).all()
    np.testing.assert_array_equal(f.x, twin.x)
    np.testing.assert_array_equal(f.P, twin.P)
    assert f.t == _DT


def test_an_update_overflowing_the_state_keeps_the_prediction_in_a_batch() -> None:
    log = MeasurementLog(
        [_DT, 2 * _DT],
        [[0.0, _V, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]],
        np.ones((2, 4)),
        [[False, True, False, False], [False, False, True, False]],
    )
    result = _filter().update_batch(log)
    assert result.status[0] == FusionStatus.OVERFLOW
    assert math.isfinite(result.nis[0])
    assert np.isfinite(result.states).all()
    twin = _filter()
    twin.predict(_DT)
    np.testing.assert_array_equal(result.states[0], twin.x)
    np.testing.assert_array_equal(result.covariances[0], twin.P)


@pytest.mark.parametrize("v", [1e150, -1e150])
def test_a_smaller_speed_residual_is_applied(v: float) -> None:
    # The same filter from x = 0 takes a reading whose update stays finite: x = K y.
    f = _filter(0.0)
    out = f.update_speed(_DT, v, variance=1.0)
    assert out.accepted
    assert f.x[0] == pytest.approx(_gain() * v, rel=1e-12)
