"""``PlanarFusion(history=)``: exactly-late stamps on clocks that cross zero (review 33).

The age slack scaled with ``|now| + |stamp| + history``, but a stamp
``t0 + k / rate`` is rounded at ``|t0|`` too (``k / rate`` is as large as
``|t0|`` where the sum is near 0): with ``t0 = -0.35`` at 30 Hz an age 4.9e-17
over ``history`` met a slack of 4.4e-17, and a measurement exactly ``history``
late was refused. The slack now takes the clock's origin into its scale.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from test_review27_last_fusion_tie_after_trim import _odometry, _state, _yaw

from navkit.estimation import FusionStatus, PlanarFusion
from navkit.estimation._fusion import _AGE_RTOL


def test_the_reported_stamp_at_30_hz_from_minus_035_s_is_fused() -> None:
    t0, rate = -0.35, 30.0
    fusion = PlanarFusion(t0=t0, history=1 / rate)
    for k in range(13):
        assert _odometry(fusion, t0 + k / rate)
    now, stamp = t0 + 12 / rate, t0 + 11 / rate
    assert now - stamp > 1 / rate  # the rounding that refused it
    result = fusion.update_yaw(stamp, 0.0, variance=1e-3)
    assert result.accepted, result.reason


@settings(max_examples=150, deadline=None)
@given(
    rate=st.sampled_from([7.0, 10.0, 30.0, 50.0, 100.0, 250.0, 1000.0]),
    n=st.integers(2, 200),
    data=st.data(),
    set_t0=st.booleans(),
)
def test_any_clock_fuses_stamps_exactly_history_late_and_refuses_older_ones(
    rate: float, n: int, data: st.DataObject, set_t0: bool
) -> None:
    # Clocks crossing 0 between the late stamp and the newest (or just before): the
    # stamps there are rounded at |t0|, far above their own size (about 1 in 9 such
    # draws was refused before the fix).
    lag = data.draw(st.integers(1, min(n - 1, 3)), label="lag")
    crossing = data.draw(st.integers(n - lag - 1, n - 1), label="crossing")
    t0 = -(crossing + data.draw(st.floats(0.0, 1.0, exclude_max=True), label="frac")) / rate
    stamps = [t0 + k / rate for k in range(n + 1)]
    late = n - lag
    history = lag / rate
    fusion = PlanarFusion(t0=t0 if set_t0 else None, history=history)
    expected = PlanarFusion(t0=t0 if set_t0 else None)
    for k, t in enumerate(stamps):
        if k != late:
            assert _odometry(fusion, t)
        assert _yaw(fusion, t, k)
        assert _odometry(expected, t) and _yaw(expected, t, k)
    # Exactly history late: fused where the in-order filter fused it (odometry before
    # the yaw update of its stamp), bit for bit.
    result = fusion.update_odometry(
        stamps[late], 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4
    )
    assert result.accepted, (t0, rate, lag, result.reason)
    assert _state(fusion) == _state(expected)
    # Older by more than the rounding (the documented slack, 2**-51 of the scale, is
    # twice the rounding's bound): refused, the filter unchanged.
    now = stamps[-1]
    slack = _AGE_RTOL * (abs(t0) + abs(now) + abs(stamps[late]) + history)
    before = _state(fusion)
    old = fusion.update_yaw(stamps[late] - 4.0 * slack, 0.0, variance=1e-3)
    assert old.status == FusionStatus.OUT_OF_ORDER, (t0, rate, lag)
    assert _state(fusion) == before
