"""A batch that sets the clock sets its origin, the scale of the late-stamp slack.

Mutation gap (MUTANT6): ``update_batch`` without ``_set_origin`` (the clock
unset, the log's first row setting it) passed every test. Its origin stayed
0.0, and the age slack missed the rounding of stamps ``t0 + k / rate`` on a
clock crossing zero (review 33's case, t0 = -0.35 s at 30 Hz): a measurement
exactly ``history`` late was refused. The oracle is the filter given the same
measurements in stamp order.
"""

from __future__ import annotations

import numpy as np

from navkit.estimation import MeasurementLog, PlanarFusion

T0, RATE = -0.35, 30.0


def _odometry(fusion: PlanarFusion, t: float) -> bool:
    result = fusion.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    return bool(result.accepted)


def _start(history: float) -> PlanarFusion:
    fusion = PlanarFusion(history=history)  # no t0: the batch's first row sets the clock
    log = MeasurementLog.from_streams(odometry=([T0], [1.0], [0.1]))
    assert fusion.update_batch(log).accepted.all()
    assert fusion.t == T0
    return fusion


def test_a_stamp_exactly_history_late_after_a_batch_set_the_clock_is_fused() -> None:
    stamps = [T0 + k / RATE for k in range(13)]
    now, late = stamps[12], stamps[11]
    assert now - late > 1 / RATE  # the age rounds above history
    fusion = _start(history=1 / RATE)
    in_order = _start(history=0.0)
    for t in stamps[1:]:
        assert _odometry(fusion, t)
    for t in stamps[1:12]:
        assert _odometry(in_order, t)
    yaw_in_order = in_order.update_yaw(late, 0.02, variance=1e-3)
    assert _odometry(in_order, now)
    result = fusion.update_yaw(late, 0.02, variance=1e-3)
    assert result.accepted, result.reason
    assert result.nis == yaw_in_order.nis
    np.testing.assert_array_equal(fusion.x, in_order.x)
    np.testing.assert_array_equal(fusion.P, in_order.P)
