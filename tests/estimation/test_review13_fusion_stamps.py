"""PlanarFusion fed ROS time stamps: epoch seconds, nanosecond integers, float32, long runs.

A ROS 2 node stamps messages with epoch time (about 1.78e9 s in 2026, where float64
values lie 2**-22 s = 2.4e-7 s apart) or with integer nanoseconds (1.78e18, beyond
2**53, the last integer float64 holds exactly). Checked:

* stamp shifts: every prediction's ``dt`` is the exact difference of two float64
  stamps (two stamps within a factor 2 of each other subtract exactly), so a run
  shifted by one of its own stamps gives the same numbers bit for bit;
* long runs: the filter time is the stamp itself, never a running sum, so the
  rounding of the stamps (up to 2.4e-7 s on each ``dt`` of a 1 kHz stream, a
  0.024 % jitter) does not accumulate;
* integer nanoseconds and float32 stamps used to be taken silently: 1.78e18 read as
  seconds (a robot at 1 m/s "travelled" 10^6 m between two messages 1 ms apart),
  stamps 1 ns apart rounded to one float (a zero ``dt``), float32 epoch stamps
  rounded to 128 s (every ``dt`` 0 or 128 s). Now refused with a ValueError naming
  the argument;
* stamps equal, 1 ns back (rounded: equal or one spacing back, never a negative
  ``dt``) and hours apart.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.estimation import FusionResult, FusionStatus, MeasurementLog, PlanarFusion

EPOCH = 1.78e9
EPOCH_NS = 1_780_000_000_123_456_789
CSV = "robot-localization-odom-imu-bags/csv_extract"


def _odometry_rows(t: Any) -> tuple[Any, ...]:
    n = len(t)
    return (t, np.ones(n), np.full(n, 0.1))


def _stamp(ns: int) -> float:
    """ROS ``sec`` + ``nanosec`` as float64 seconds (as navkit's bag readers compute it)."""
    return float(ns // 1_000_000_000) + float(ns % 1_000_000_000) * 1e-9


def _columns(path: Path, names: tuple[str, ...]) -> dict[str, np.ndarray]:
    header = path.read_text().split("\n", 1)[0].split(",")
    cols = [header.index(name) for name in names]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=cols)
    return {name: data[:, i] for i, name in enumerate(names)}


# ----------------------------------------------------------------- shifts and long runs
def test_real_epoch_stamps_shifted_to_zero_give_the_same_run(shared_data: Path) -> None:
    """test1 (2015, stamps 1.43e9 s): odometry and gyro at their stamps, and shifted."""
    odo = _columns(shared_data / CSV / "test1_wheel_odom.csv", ("stamp", "vx", "wz"))
    imu = _columns(shared_data / CSV / "test1_imu.csv", ("stamp", "wz"))
    start = float(min(odo["stamp"].min(), imu["stamp"].min()))
    assert start > 1e9

    def run(shift: float) -> FusionResult:
        log = MeasurementLog.from_streams(
            odometry=(odo["stamp"] - shift, odo["vx"], odo["wz"]),
            odometry_variance=(1e-3, 0.03),
            yaw_rate=(imu["stamp"] - shift, imu["wz"]),
        )
        return PlanarFusion(t0=start - shift).update_batch(log)

    epoch, zero = run(0.0), run(start)
    assert epoch.states.shape[0] == 3952 + 11865
    assert bool(epoch.accepted.all())
    np.testing.assert_array_equal(epoch.states, zero.states)
    np.testing.assert_array_equal(epoch.covariances, zero.covariances)


@settings(max_examples=25, deadline=None)
@given(
    offset=st.floats(1e9, 2e9),
    gaps=st.lists(st.floats(0.0, 0.5), min_size=1, max_size=30),
    online=st.booleans(),
)
def test_a_shift_by_the_first_stamp_changes_nothing(
    offset: float, gaps: list[float], online: bool
) -> None:
    stamps = offset + np.cumsum(gaps)
    shifted = stamps - stamps[0]  # exact: the stamps are within a factor 2 of each other
    results = []
    for t in (stamps, shifted):
        fusion = PlanarFusion([0.0, 0.0, 0.3, 1.0, 0.2, 0.1], t0=float(t[0]))
        if online:
            for i, ti in enumerate(t.tolist()):
                fusion.update_odometry(
                    ti, 1.0 + 0.01 * i, 0.2, v_variance=1e-3, omega_variance=1e-3
                )
        else:
            fusion.update_batch(MeasurementLog.from_streams(odometry=_odometry_rows(t)))
        assert fusion.t == t[-1]
        results.append((fusion.x.copy(), fusion.P.copy()))
    np.testing.assert_array_equal(results[0][0], results[1][0])
    np.testing.assert_array_equal(results[0][1], results[1][1])


test_a_shift_by_the_first_stamp_changes_nothing_thoroughly = slow_twin(
    test_a_shift_by_the_first_stamp_changes_nothing, max_examples=150
)


def test_a_long_1khz_run_at_epoch_stamps_does_not_drift() -> None:
    """10^5 odometry rows at 1 kHz stamped at 1.78e9 s against the same from 0 s.

    Each epoch ``dt`` is off by up to one float64 spacing there (2**-22 s = 2.4e-7 s,
    0.024 % of 1 ms), but the time is never summed: the filter ends at the last
    stamp, and the pose within 1e-6 m of the run from 0 (the last stamps of the two
    runs differ by at most a spacing, 2.4e-7 s at 1 m/s; the jitter of each
    ``dt`` is second order in the pose).
    """
    n = 100_000
    k = np.arange(1, n + 1)
    epoch_t = EPOCH + k * 1e-3
    zero_t = k * 1e-3
    steps = np.diff(epoch_t)
    assert np.ptp(steps) == 2.0**-22  # the jitter is there: dt takes two values
    x0 = [0.0, 0.0, 0.0, 1.0, 0.1, 0.0]
    a = PlanarFusion(x0, t0=EPOCH)
    b = PlanarFusion(x0, t0=0.0)
    a.update_batch(MeasurementLog.from_streams(odometry=_odometry_rows(epoch_t)))
    b.update_batch(MeasurementLog.from_streams(odometry=_odometry_rows(zero_t)))
    assert a.t == epoch_t[-1] and abs((a.t - EPOCH) - 100.0) <= 2.0**-22
    np.testing.assert_allclose(a.x[:2], b.x[:2], rtol=0.0, atol=1e-6)
    assert abs(a.x[2] - b.x[2]) < 1e-7
    np.testing.assert_allclose(a.P, b.P, rtol=1e-6, atol=1e-12)


# ------------------------------------------------------------------ nanosecond integers
ONLINE = {
    "update_odometry": lambda f, t: f.update_odometry(
        t, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4
    ),
    "update_speed": lambda f, t: f.update_speed(t, 1.0, variance=1e-4),
    "update_yaw": lambda f, t: f.update_yaw(t, 0.1, variance=1e-4),
    "update_yaw_rate": lambda f, t: f.update_yaw_rate(t, 0.1, variance=1e-4),
    "update_acceleration": lambda f, t: f.update_acceleration(t, 0.1, variance=1e-4),
    "predict": lambda f, t: f.predict(t),
}


@pytest.mark.parametrize("method", list(ONLINE))
@pytest.mark.parametrize("stamp", [EPOCH_NS, np.int64(EPOCH_NS), np.uint64(EPOCH_NS), -EPOCH_NS])
@pytest.mark.parametrize("clock", ["set", "unset"])
def test_nanosecond_integers_are_refused_online(method: str, stamp: Any, clock: str) -> None:
    fusion = PlanarFusion(t0=EPOCH if clock == "set" else None)
    before = fusion._buf.tobytes()
    with pytest.raises(ValueError, match=r"\bt\b.*2\*\*53.*nanosecond"):
        ONLINE[method](fusion, stamp)
    assert fusion._buf.tobytes() == before
    assert fusion.t == (EPOCH if clock == "set" else None)


@pytest.mark.parametrize("stamp", [EPOCH_NS, np.int64(EPOCH_NS), np.array(EPOCH_NS), 2**53 + 1])
def test_nanosecond_integers_are_refused_as_t0(stamp: Any) -> None:
    with pytest.raises(ValueError, match=r"t0.*2\*\*53"):
        PlanarFusion(t0=stamp)


def test_integer_seconds_up_to_2_53_are_taken_exactly() -> None:
    for stamp in (1_780_000_000, np.int64(2**53), -(2**53)):
        fusion, twin = PlanarFusion(t0=float(stamp) - 1.0), PlanarFusion(t0=float(stamp) - 1.0)
        fusion.update_odometry(stamp, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
        twin.update_odometry(float(stamp), 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
        assert fusion._buf.tobytes() == twin._buf.tobytes()


@pytest.mark.parametrize(
    "times",
    [
        np.array([EPOCH_NS, EPOCH_NS + 1, EPOCH_NS + 1_000_000], dtype=np.int64),
        np.array([EPOCH_NS, EPOCH_NS + 1, EPOCH_NS + 1_000_000], dtype=np.uint64),
        [EPOCH_NS, EPOCH_NS + 1, EPOCH_NS + 1_000_000],  # NumPy makes this int64
        [0.5, 1.0, EPOCH_NS],  # NumPy would round the integer into a float64 array
        np.array([1, 2, 10**30], dtype=object),
    ],
    ids=["int64", "uint64", "list of ints", "list of floats and an int", "object"],
)
def test_nanosecond_integers_are_refused_in_logs(times: Any) -> None:
    n = len(times)
    values = np.zeros((n, 4))
    observed = np.zeros((n, 4), dtype=bool)
    observed[:, 1] = True
    with pytest.raises(ValueError, match=r"times.*2\*\*53"):
        MeasurementLog(times, values, np.ones((n, 4)), observed)
    with pytest.raises(ValueError, match=r"yaw_rate\[0\] \(times\).*2\*\*53"):
        MeasurementLog.from_streams(yaw_rate=(times, np.zeros(n)))
    with pytest.raises(ValueError, match=r"times.*2\*\*53"):
        FusionResult(
            times, np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros(n, np.int8), values[:, 0]
        )


def test_nanosecond_stamps_converted_to_seconds_keep_their_order() -> None:
    """sec + nanosec * 1e-9 rounds monotonically: stamps 1 ns apart are equal or in order."""
    ns = EPOCH_NS + np.arange(2000)
    t = np.array([_stamp(int(v)) for v in ns])
    assert np.all(np.diff(t) >= 0.0) and np.any(np.diff(t) == 0.0)
    result = PlanarFusion(t0=t[0]).update_batch(
        MeasurementLog.from_streams(odometry=(t, np.ones(2000)))
    )
    assert bool(result.accepted.all())
    assert math.isclose(result.states[-1, 0], 2000e-9, rel_tol=0.0, abs_tol=3e-7)


# ---------------------------------------------------------------------------- float32
def test_float32_epoch_stamps_are_refused() -> None:
    t32 = (EPOCH + np.arange(5) * 0.01).astype(np.float32)
    assert np.all(np.diff(t32.astype(np.float64)) == 0.0)  # what would have been fused
    with pytest.raises(ValueError, match=r"odometry\[0\] \(times\).*float32.*float64"):
        MeasurementLog.from_streams(odometry=_odometry_rows(t32))
    with pytest.raises(ValueError, match=r"times.*float32"):
        MeasurementLog(t32, np.zeros((5, 4)), np.ones((5, 4)), np.ones((5, 4), dtype=bool))
    with pytest.raises(ValueError, match=r"yaw\[0\] \(times\), element 2, .*float32"):
        MeasurementLog.from_streams(yaw=([1.0, 2.0, np.float32(EPOCH)], [0.0, 0.0, 0.0]))
    fusion = PlanarFusion(t0=EPOCH - 1.0)
    before = fusion._buf.tobytes()
    for method in ONLINE:
        with pytest.raises(ValueError, match=r"\bt\b.*float32"):
            ONLINE[method](fusion, t32[0])
    with pytest.raises(ValueError, match=r"\bt\b.*float16"):
        fusion.update_yaw(np.float16(100.0), 0.0, variance=1e-3)
    with pytest.raises(ValueError, match=r"t0.*float32"):
        PlanarFusion(t0=t32[0])
    assert fusion._buf.tobytes() == before


def test_float32_stamps_that_resolve_a_millisecond_are_taken() -> None:
    """Below 2**14 s float32 is at most 2**-10 s (0.98 ms) coarse: taken, as float64.

    From 2**14 s on it is 2**-9 s (1.95 ms) coarse: refused.
    """
    below = np.nextafter(np.float32(2**14), np.float32(0.0))
    t32 = np.linspace(0.0, 16000.0, 50).astype(np.float32)
    t32[-1] = below
    a = MeasurementLog.from_streams(odometry=_odometry_rows(t32))
    b = MeasurementLog.from_streams(odometry=_odometry_rows(t32.astype(np.float64)))
    np.testing.assert_array_equal(a.times, b.times)
    fusion, twin = PlanarFusion(t0=0.0), PlanarFusion(t0=0.0)
    fusion.update_yaw(below, 0.0, variance=1e-3)
    twin.update_yaw(float(below), 0.0, variance=1e-3)
    assert fusion._buf.tobytes() == twin._buf.tobytes()
    t32[-1] = 2**14
    with pytest.raises(ValueError, match=r"element 49, .*0\.00195312 s coarse"):
        MeasurementLog.from_streams(odometry=_odometry_rows(t32))
    with pytest.raises(ValueError, match=r"\bt\b.*float32"):
        fusion.update_yaw(np.float32(2**14), 0.0, variance=1e-3)
    # float16 is 2**-10 s coarse just below 2 s, and refused from 2 s on.
    fusion.update_yaw(np.float16(1.999), 0.0, variance=1e-3)
    with pytest.raises(ValueError, match=r"\bt\b.*float16"):
        fusion.update_yaw(np.float16(2.0), 0.0, variance=1e-3)


# ------------------------------------------------------------------------ monotonicity
def test_equal_stamps_one_nanosecond_back_and_hours_apart() -> None:
    base = EPOCH_NS
    fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.0, 0.0], t0=_stamp(base))
    x_before = fusion.x.copy()
    # An equal stamp: no prediction (dt 0), the update applies.
    assert fusion.update_yaw(_stamp(base), 0.0, variance=1e-3).accepted
    np.testing.assert_array_equal(fusion.x[:2], x_before[:2])
    # Stamps 1 ns back: equal once rounded (dt 0) or one spacing back (out of order),
    # never a negative dt.
    outcomes = set()
    for back in range(1, 400):
        t = _stamp(base - back)
        result = fusion.update_yaw(t, 0.0, variance=1e-3)
        outcomes.add(result.accepted)
        if t < fusion.t:
            assert result.status == FusionStatus.OUT_OF_ORDER
        else:
            assert result.accepted and t == fusion.t
    assert outcomes == {True, False}
    # Three hours later: one prediction over the gap, finite, covariance grown by Q dt.
    p_before = fusion.P.copy()
    t_late = _stamp(base + 3 * 3600 * 10**9)
    assert fusion.update_yaw(t_late, 0.0, variance=1e-3).accepted
    assert fusion.t == t_late
    assert math.isclose(fusion.x[0] - x_before[0], 3 * 3600.0, rel_tol=1e-6)
    assert fusion.P[0, 0] >= p_before[0, 0] + 0.05 * 3 * 3600 and np.all(np.isfinite(fusion.P))
