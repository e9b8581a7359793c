"""``PlanarFusion(history=)`` keeps the steps late measurements need when |t| < history (review 32).

The steps kept for ``history`` go once older than ``history + _TRIM_RTOL
(|t| + history)``: beyond the late measurement's own age slack, which grows
with ``|now| + |stamp| + history``. A mutant trimming at ``history +
_TRIM_RTOL (|t| - history)`` survived the suite, whose windows all had ``|t| >=
history`` (the slack then only a little smaller): with stamps near zero and a
window longer than the time itself that limit falls *below* ``history``, a step
exactly ``history`` old went, and odometry that late, still accepted, was
fused after that stamp's yaw update instead of before it. Oracle: a filter
fed the same updates in stamp order, odometry before yaw at one stamp (the
tie order of :meth:`MeasurementLog.from_streams`), bit for bit, as review 27's
test has it for positive stamps. Checked: the test fails on that mutant of
``_fusion.py`` and passes on HEAD.
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


@pytest.mark.parametrize("rate", [7.0, 30.0])
@pytest.mark.parametrize("t0", [-0.45, -1.3])
def test_stamps_exactly_history_late_around_zero_keep_the_tie_order(t0: float, rate: float) -> None:
    n = 12
    wrong = []
    for lag in range(1, 12):
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
    assert wrong == []
