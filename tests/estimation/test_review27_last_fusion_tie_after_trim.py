"""``PlanarFusion(history=)``: a late measurement taken by the age slack keeps the tie order.

Review 26 let a measurement exactly ``history`` late in whichever way its age
rounds (``1.0 - 0.7`` is 0.30000000000000004 > 0.3), but the steps kept for the
window were still trimmed without that slack. A step with the measurement's own
stamp that had rounded out of the window was gone, and the late measurement,
accepted, was fused *after* it, not before it as the tie order (odometry before
yaw at one stamp, :meth:`MeasurementLog.from_streams`'s) and the docs ("the same
numbers, bit for bit") say: late odometry at 0.7 s went after the yaw update at
0.7 s (review 27, a fresh-eyes review of review 26).
"""

from __future__ import annotations

import pytest

from navkit.estimation import PlanarFusion


def _state(f: PlanarFusion) -> tuple[float | None, bytes, bytes]:
    return f.t, f.x.tobytes(), f.P.tobytes()


def _odometry(f: PlanarFusion, t: float) -> bool:
    return f.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4).accepted


def _yaw(f: PlanarFusion, t: float, k: int) -> bool:
    return f.update_yaw(t, 0.01 * k, variance=1e-3).accepted


def test_late_odometry_at_one_decimal_stamp_goes_before_that_stamps_yaw() -> None:
    stamps = [k / 10 for k in range(11)]
    fusion = PlanarFusion(t0=0.0, history=0.3)
    expected = PlanarFusion(t0=0.0)
    for k, t in enumerate(stamps):
        if t != 0.7:
            assert _odometry(fusion, t)
        assert _yaw(fusion, t, k)
        assert _odometry(expected, t) and _yaw(expected, t, k)  # stamp order, odometry first
    assert 1.0 - 0.7 > 0.3  # the yaw step at 0.7 s rounded out of the window
    assert _odometry(fusion, 0.7)
    assert _state(fusion) == _state(expected)


def _tie_order_breaks(t0: float, rate: float, lags: range) -> list[tuple[int, bool]]:
    """The lags whose late odometry, stamped ``t0 + k / rate``, was refused or misordered.

    For each lag, odometry ``lag / rate`` late (exactly ``history``) against a
    filter fed the same updates in stamp order, odometry before yaw at a stamp.
    """
    n = 12
    wrong = []
    for lag in lags:
        late = n - lag
        fusion = PlanarFusion(t0=t0, history=lag / rate)
        expected = PlanarFusion(t0=t0)
        for k in range(n + 1):
            t = t0 + k / rate
            if k != late:
                assert _odometry(fusion, t)
            assert _yaw(fusion, t, k)
            assert _odometry(expected, t) and _yaw(expected, t, k)
        accepted = _odometry(fusion, t0 + late / rate)
        if not accepted or _state(fusion) != _state(expected):
            wrong.append((lag, accepted))
    return wrong


@pytest.mark.parametrize("t0", [0.0, 12345.678, 1.7e9])
@pytest.mark.parametrize("rate", [10.0, 30.0, 100.0])
def test_every_stamp_exactly_history_late_keeps_the_tie_order(t0: float, rate: float) -> None:
    assert _tie_order_breaks(t0, rate, range(1, 9)) == []


@pytest.mark.parametrize("rate", [7.0, 30.0])
@pytest.mark.parametrize("t0", [-0.45, -1.3])
def test_stamps_exactly_history_late_around_zero_keep_the_tie_order(t0: float, rate: float) -> None:
    """Windows longer than the time itself (review 32, mutation).

    The steps kept go once older than ``history + _TRIM_RTOL (|t| + history)``;
    a mutant trimming at ``history + _TRIM_RTOL (|t| - history)`` survived the
    suite, whose windows all had ``|t| >= history``: near zero that limit falls
    below ``history``, a step exactly ``history`` old went, and the late
    odometry was fused after that stamp's yaw update.
    """
    assert _tie_order_breaks(t0, rate, range(1, 12)) == []
