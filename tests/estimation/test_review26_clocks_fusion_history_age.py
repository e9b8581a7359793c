"""``PlanarFusion(history=)``: a measurement exactly ``history`` late is fused (review 26).

The window compared the rounded age ``t - stamp`` with ``history``: at 1.0 s a
stamp 0.7 is 0.3 s old, but ``1.0 - 0.7`` is 0.30000000000000004, so with
``history=0.3`` it was refused (58 of 192 stamps ``t0 + k / rate`` exactly
``history`` late, at t0 = 0 and at epoch stamps). The age now has a slack of a
few float spacings of the stamps, in the window's check and in its trimming.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import FusionStatus, PlanarFusion


def _state(f: PlanarFusion) -> tuple[float | None, bytes, bytes]:
    return f.t, f.x.tobytes(), f.P.tobytes()


def test_a_stamp_history_late_by_its_decimal_age_is_fused_in_stamp_order() -> None:
    stamps = [k / 10 for k in range(11)]
    fusion = PlanarFusion(t0=0.0, history=0.3)
    for t in stamps:
        fusion.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    assert 1.0 - 0.7 > 0.3  # the rounding that refused it
    result = fusion.update_yaw(0.7, 0.05, variance=1e-3)
    assert result.accepted, result.reason
    expected = PlanarFusion(t0=0.0)
    for t in stamps:
        expected.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
        if t == 0.7:  # odometry first at one stamp (from_streams's order)
            expected.update_yaw(0.7, 0.05, variance=1e-3)
    assert _state(fusion) == _state(expected)


@pytest.mark.parametrize("t0", [0.0, 12345.678, 1.7e9, 1.7e9 + 0.37])
@pytest.mark.parametrize("rate", [10.0, 20.0, 30.0, 100.0, 1000.0])
def test_every_stamp_exactly_history_late_is_taken_and_one_later_is_not(
    t0: float, rate: float
) -> None:
    n = 20
    for lag in range(1, 9):
        history = lag / rate
        fusion = PlanarFusion(t0=t0, history=history)
        for k in range(n + 1):
            fusion.update_odometry(t0 + k / rate, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
        result = fusion.update_yaw(t0 + (n - lag) / rate, 0.0, variance=1e-3)
        assert result.accepted, (t0, rate, lag, result.reason)
        # Half a period older than the window: refused, the filter unchanged.
        before = _state(fusion)
        old = fusion.update_yaw(t0 + (n - lag - 0.5) / rate, 0.0, variance=1e-3)
        assert old.status == FusionStatus.OUT_OF_ORDER
        assert _state(fusion) == before


def test_the_steps_kept_reach_back_as_far_as_the_window() -> None:
    # Trimmed by the same check: a stamp accepted by the slack finds the step it
    # goes before even after many later steps have trimmed the history.
    fusion = PlanarFusion(t0=0.0, history=0.3)
    for k in range(1, 1000):
        fusion.update_yaw_rate(k / 10, 0.0, variance=1e-4)
    assert fusion.t == 99.9 and 99.9 - 99.6 > 0.3
    assert fusion.update_yaw(99.6, 0.0, variance=1e-3).accepted
    assert np.isfinite(fusion.x).all()
