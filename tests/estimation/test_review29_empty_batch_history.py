"""An empty ``update_batch`` changes nothing, the ``history`` of late measurements included.

Review 29 (stateful review): documented in ``update_batch``; a non-empty log
clears the history (its rows are not kept), an empty one returns before that.
"""

from __future__ import annotations

import pickle

import numpy as np

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion

EMPTY = MeasurementLog.from_streams(odometry=(np.array([]), np.array([]), np.array([])))
ODOM = {"v_variance": 0.01, "omega_variance": 0.01}


def _fused() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    fusion.update_odometry(0.5, 1.0, 0.0, **ODOM)
    return fusion


def test_an_empty_log_keeps_the_history_a_late_measurement_needs() -> None:
    fusion, untouched = _fused(), _fused()
    before = pickle.dumps(fusion)
    assert len(fusion.update_batch(EMPTY).times) == 0
    assert pickle.dumps(fusion) == before
    late = fusion.update_odometry(0.3, 1.0, 0.1, **ODOM)
    assert late.status == FusionStatus.ACCEPTED
    want = untouched.update_odometry(0.3, 1.0, 0.1, **ODOM)
    assert late.nis == want.nis
    assert np.array_equal(fusion.x, untouched.x) and np.array_equal(fusion.P, untouched.P)


def test_a_log_with_rows_clears_it() -> None:
    fusion = _fused()
    log = MeasurementLog.from_streams(
        odometry=(np.array([0.6]), np.array([1.0]), np.array([0.0])), odometry_variance=(0.01, 0.01)
    )
    fusion.update_batch(log)
    assert fusion.update_odometry(0.3, 1.0, 0.1, **ODOM).status == FusionStatus.OUT_OF_ORDER
