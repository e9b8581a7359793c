"""PlanarFusion on robot_localization's real bags, their streams perturbed in memory (review 46).

The lens: would a robot_localization user trust this? The bags' streams are
copied and then reordered, duplicated, cut, wrapped, given NaN or the ROS
"unknown covariance" marks; each perturbation must give the documented
handling or a clear exception naming the argument, never a NaN in the state.

Arrival order
    Played back live, each message arrives at its bag record time, not its
    header stamp. test1's IMU stamps lag their arrival by 21-36 ms, its
    odometry by under 1 ms, so in arrival order an IMU reading is often older
    than an odometry message already fused: without ``history`` it is refused
    (``OUT_OF_ORDER``; 6154 of test1's 23730 IMU readings; 636 of test2's
    readings, 634 of them odometry and one IMU message's yaw and yaw rate), as
    robot_localization refuses a measurement older than its last update
    unless ``smooth_lagged_data`` is on. With ``history=0.2`` (robot_localization's
    ``history_length``) every reading is fused and the filter ends bit for bit
    where the stamp-sorted batch does.

Output timer
    A node that publishes at 30 Hz by predicting the filter to each tick makes
    even more readings late (19411 of 27682 on test1, the end 55 m off);
    predicting a copy leaves the filter alone (``PlanarFusion.predict``'s notes).
"""

from __future__ import annotations

import copy
import math
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion, UpdateResult
from navkit.geometry import quaternion_to_yaw, rpy_to_quaternion, wrap_angle
from navkit.mapping.io import BagImu, BagOdometry

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from rl_bags import read_bag

pytest.importorskip("rosbags")


@dataclass
class Streams:
    """One bag's wheel speed and IMU yaw / yaw rate in base_link, with their variances."""

    odom: BagOdometry
    imu: BagImu
    yaw: np.ndarray
    rate: np.ndarray

    @property
    def t0(self) -> float:
        return float(min(self.odom.times[0], self.imu.times[0]))

    @property
    def x0(self) -> list[float]:
        return [0.0, 0.0, float(self.yaw[0]), 0.0, 0.0, 0.0]

    def kwargs(self, **change: Any) -> dict[str, Any]:
        """``from_streams`` arguments (speed, IMU yaw, gyro), with some arrays replaced."""
        a: dict[str, Any] = {
            "ot": self.odom.times,
            "v": self.odom.twists[:, 0],
            "vv": self.odom.twist_covariances[:, 0, 0],
            "it": self.imu.times,
            "yaw": self.yaw,
            "yv": self.imu.orientation_covariances[:, 2, 2],
            "w": self.rate,
            "wv": self.imu.angular_velocity_covariances[:, 2, 2],
        }
        a.update(change)
        return {
            "odometry": (a["ot"], a["v"]),
            "odometry_variance": (a["vv"], 1.0),
            "yaw": (a["it"], a["yaw"]),
            "yaw_variance": a["yv"],
            "yaw_rate": (a["it"], a["w"]),
            "yaw_rate_variance": a["wv"],
        }

    def log(self, **change: Any) -> MeasurementLog:
        return MeasurementLog.from_streams(**self.kwargs(**change))

    def rows(self, odom: np.ndarray, imu: np.ndarray) -> MeasurementLog:
        """The log of the odometry messages ``odom`` and IMU messages ``imu`` (indices or masks)."""
        return self.log(
            ot=self.odom.times[odom],
            v=self.odom.twists[odom, 0],
            vv=self.odom.twist_covariances[odom, 0, 0],
            it=self.imu.times[imu],
            yaw=self.yaw[imu],
            yv=self.imu.orientation_covariances[imu, 2, 2],
            w=self.rate[imu],
            wv=self.imu.angular_velocity_covariances[imu, 2, 2],
        )


def _load(shared_data: Path, name: str) -> Streams:
    odom, imu, base = read_bag(shared_data, name)
    yaw = np.asarray(quaternion_to_yaw(base.orientations), dtype=np.float64)
    return Streams(odom, imu, yaw, base.angular_velocities[:, 2].copy())


@pytest.fixture(scope="module")
def test1(shared_data: Path) -> Streams:
    return _load(shared_data, "test1")


@pytest.fixture(scope="module")
def test2(shared_data: Path) -> Streams:
    return _load(shared_data, "test2")


def _frozen(s: Streams) -> list[np.ndarray]:
    arrays = [s.odom.times, s.odom.twists, s.imu.times, s.imu.orientations, s.yaw, s.rate]
    return [a.copy() for a in arrays]


def _assert_unchanged(s: Streams, before: list[np.ndarray]) -> None:
    for a, b in zip(_frozen(s), before, strict=True):
        np.testing.assert_array_equal(a, b)


# ------------------------------------------------------------------ arrival order
@pytest.mark.parametrize("name", ["test1", "test2"])
def test_arrival_order_late_readings_refused_or_replayed(name: str, request: Any) -> None:
    s: Streams = request.getfixturevalue(name)
    o, i = s.odom, s.imu
    # One message arrives at its record time; an IMU message carries a yaw and a yaw rate.
    messages = sorted(
        [(float(rt), 0, k) for k, rt in enumerate(o.record_times)]
        + [(float(rt), 1, k) for k, rt in enumerate(i.record_times)]
    )
    ov = o.twist_covariances[:, 0, 0]
    yv = i.orientation_covariances[:, 2, 2]
    wv = i.angular_velocity_covariances[:, 2, 2]
    readings: list[tuple[str, float, float, float]] = []  # kind, stamp, value, variance
    for _, imu, k in messages:
        if imu:
            t = float(i.times[k])
            readings.append(("yaw", t, float(s.yaw[k]), float(yv[k])))
            readings.append(("yaw_rate", t, float(s.rate[k]), float(wv[k])))
        else:
            readings.append(("speed", float(o.times[k]), float(o.twists[k, 0]), float(ov[k])))
    batch = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log())
    assert np.all(batch.status == FusionStatus.ACCEPTED)

    def feed(fusion: PlanarFusion, kind: str, t: float, value: float, var: float) -> UpdateResult:
        update = {
            "speed": fusion.update_speed,
            "yaw": fusion.update_yaw,
            "yaw_rate": fusion.update_yaw_rate,
        }[kind]
        return update(t, value, variance=var)

    # Without history: a reading is refused exactly when it is older than the newest
    # stamp taken so far (counted here independently of the filter), and a refused
    # reading leaves the state and time as they were.
    plain = PlanarFusion(s.x0, t0=s.t0)
    newest = s.t0
    refused = expected = 0
    for kind, t, value, var in readings:
        expected += t < newest
        newest = max(newest, t)
        x_before, t_before = plain.x.copy(), plain.t
        result = feed(plain, kind, t, value, var)
        if not result.accepted:
            refused += 1
            assert result.status == FusionStatus.OUT_OF_ORDER
            np.testing.assert_array_equal(plain.x, x_before)
            assert plain.t == t_before
        assert np.all(np.isfinite(plain.x))
    assert refused == expected > 100  # the streams really arrive out of stamp order

    # With robot_localization's history_length: every reading fused, as the batch.
    lagged = PlanarFusion(s.x0, t0=s.t0, history=0.2)
    for kind, t, value, var in readings:
        assert feed(lagged, kind, t, value, var).accepted
    np.testing.assert_array_equal(lagged.x, batch.states[-1])
    np.testing.assert_array_equal(lagged.P, batch.covariances[-1])
    # The refused readings cost accuracy: the plain filter ends elsewhere.
    assert not np.array_equal(plain.x, batch.states[-1])


# ------------------------------------------------------------------ reordered, duplicated
def test_shuffled_streams_give_the_same_run(test2: Streams) -> None:
    s = test2
    before = _frozen(s)
    base = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log())
    rng = np.random.default_rng(46)
    po, pi = rng.permutation(len(s.odom)), rng.permutation(len(s.imu))
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(s.rows(po, pi))
    np.testing.assert_array_equal(result.times, base.times)
    np.testing.assert_array_equal(result.states, base.states)
    np.testing.assert_array_equal(result.covariances, base.covariances)
    _assert_unchanged(s, before)


def test_duplicated_imu_messages(test2: Streams) -> None:
    """Each IMU message twice at its stamp: no prediction between the copies.

    Two independent linear updates of variance 2R at one time are one update of
    variance R (information form), so doubled variances must reproduce the run;
    the same variances count the message twice (the yaw variance roughly halves).
    """
    s = test2
    base = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log())
    twice = np.repeat
    it = twice(s.imu.times, 2)
    yv = s.imu.orientation_covariances[:, 2, 2]
    wv = s.imu.angular_velocity_covariances[:, 2, 2]
    doubled = s.log(
        it=it, yaw=twice(s.yaw, 2), w=twice(s.rate, 2), yv=2 * twice(yv, 2), wv=2 * twice(wv, 2)
    )
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(doubled)
    assert len(result.times) == len(base.times) + 2 * len(s.imu)
    assert np.all(result.status == FusionStatus.ACCEPTED)
    sd = np.sqrt(np.diag(base.covariances[-1]))
    diff = result.states[-1] - base.states[-1]
    diff[2] = wrap_angle(float(diff[2]))
    assert np.all(np.abs(diff) < 1e-9 * sd + 1e-12)
    np.testing.assert_allclose(result.covariances[-1], base.covariances[-1], rtol=1e-9, atol=1e-18)

    same = s.log(it=it, yaw=twice(s.yaw, 2), w=twice(s.rate, 2), yv=twice(yv, 2), wv=twice(wv, 2))
    counted_twice = PlanarFusion(s.x0, t0=s.t0).update_batch(same)
    ratio = counted_twice.covariances[-1][2, 2] / base.covariances[-1][2, 2]
    assert 0.4 < ratio < 0.75


# ------------------------------------------------------------------ gaps
def test_gap_predicts_the_unicycle_and_grows_the_covariance(test2: Streams) -> None:
    """5 s without any message (a dropped link): prediction only, as the docstring's model."""
    s = test2
    start, stop = 70.0, 75.0
    ko = (s.odom.times < start) | (s.odom.times >= stop)
    ki = (s.imu.times < start) | (s.imu.times >= stop)
    cut = s.rows(ko, ki)
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(cut)
    assert np.all(result.status == FusionStatus.ACCEPTED)
    assert np.all(np.isfinite(result.states)) and np.all(np.isfinite(result.covariances))
    k = int(np.searchsorted(result.times, stop))
    t_before, t_after = float(result.times[k - 1]), float(result.times[k])
    assert t_after - t_before > stop - start

    # The state at the gap's start, predicted across it.
    fusion = PlanarFusion(s.x0, t0=s.t0)
    head = MeasurementLog(cut.times[:k], cut.values[:k], cut.variances[:k], cut.observed[:k])
    fusion.update_batch(head)
    x, p = fusion.x.copy(), fusion.P.copy()
    np.testing.assert_array_equal(x, result.states[k - 1])
    fusion.predict(t_after)
    dt = t_after - t_before
    _, _, th, v, w, a = x
    travel = v * dt + a * dt * dt / 2.0
    mid = th + w * dt / 2.0
    expected = [x[0] + travel * math.cos(mid), x[1] + travel * math.sin(mid)]
    np.testing.assert_allclose(fusion.x[:2], expected, rtol=0, atol=1e-9)
    assert fusion.x[3] == pytest.approx(v + a * dt, abs=1e-12)
    # Process noise per second times the gap, at least, on every variance (robot_localization's).
    q = np.array([0.05, 0.05, 0.06, 0.025, 0.02, 0.01])
    assert np.all(np.diag(fusion.P) >= np.diag(p) + q * dt * (1 - 1e-12))
    # The first reading after the gap pulls the heading back: its variance drops again.
    assert result.covariances[k + 3][2, 2] < 0.1 * fusion.P[2, 2]


def test_corrupt_stamp_is_one_time_gap(test2: Streams) -> None:
    s = test2
    t = s.odom.times.copy()
    t[500] = 1e300
    keep = np.arange(len(t)) != 500
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log(ot=t))
    dropped = PlanarFusion(s.x0, t0=s.t0).update_batch(
        s.log(ot=t[keep], v=s.odom.twists[keep, 0], vv=s.odom.twist_covariances[keep, 0, 0])
    )
    assert result.status[-1] == FusionStatus.TIME_GAP
    assert np.all(result.status[:-1] == FusionStatus.ACCEPTED)
    np.testing.assert_array_equal(result.states[:-1], dropped.states)
    np.testing.assert_array_equal(result.states[-1], dropped.states[-1])


def test_out_of_order_rows_in_a_log(test2: Streams) -> None:
    """Rows of a hand-made log not in time order: the older ones are skipped, nothing else."""
    s = test2
    log = s.log()
    rng = np.random.default_rng(7)
    order = np.arange(len(log))
    for j in rng.choice(len(log) - 1, size=40, replace=False):
        order[j], order[j + 1] = order[j + 1], order[j]
    mixed = MeasurementLog(
        log.times[order], log.values[order], log.variances[order], log.observed[order]
    )
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(mixed)
    running = np.maximum.accumulate(mixed.times)
    older = np.concatenate(([False], mixed.times[1:] < running[:-1]))
    assert older.sum() > 0
    np.testing.assert_array_equal(result.status == FusionStatus.OUT_OF_ORDER, older)
    idx = np.flatnonzero(older)
    np.testing.assert_array_equal(result.states[idx], result.states[idx - 1])
    assert np.all(np.isfinite(result.states))


# ------------------------------------------------------------------ the ±π wrap
def test_real_yaw_across_pi(test2: Streams) -> None:
    """The Jackal's IMU yaw crosses ±π; the same yaw unwrapped or shifted by 2πk fuses the same."""
    s = test2
    assert np.any(np.abs(np.diff(s.yaw)) > math.pi)  # the data do cross the wrap
    base = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log())
    th = base.states[:, 2]
    assert np.all((th > -math.pi) & (th <= math.pi))
    assert np.any(th > 3.1) and np.any(th < -3.1)
    for shifted in (np.unwrap(s.yaw), s.yaw + 2 * math.pi, s.yaw - 6 * math.pi):
        result = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log(yaw=shifted))
        d = result.states - base.states
        d[:, 2] = np.asarray(wrap_angle(d[:, 2]))
        assert np.max(np.abs(d)) < 1e-10
        np.testing.assert_allclose(result.covariances, base.covariances, rtol=1e-9, atol=1e-15)
        assert np.all((result.states[:, 2] > -math.pi) & (result.states[:, 2] <= math.pi))


# ------------------------------------------------------------------ NaN and unknown covariances
@pytest.mark.parametrize(
    ("field", "named"),
    [
        ("ot", "odometry[0] (times)"),
        ("v", "odometry[1]"),
        ("vv", "odometry_variance[0]"),
        ("it", "yaw[0] (times)"),
        ("yaw", "yaw[1]"),
        ("yv", "yaw_variance"),
        ("w", "yaw_rate[1]"),
        ("wv", "yaw_rate_variance"),
    ],
)
def test_nan_in_a_message_field(test2: Streams, field: str, named: str) -> None:
    s = test2
    arr = s.kwargs()
    source = {
        "ot": arr["odometry"][0],
        "v": arr["odometry"][1],
        "vv": arr["odometry_variance"][0],
        "it": arr["yaw"][0],
        "yaw": arr["yaw"][1],
        "yv": arr["yaw_variance"],
        "w": arr["yaw_rate"][1],
        "wv": arr["yaw_rate_variance"],
    }[field]
    bad = np.array(source, dtype=np.float64, copy=True)
    bad[1234 % len(bad)] = math.nan
    with pytest.raises(ValueError, match=r"^" + re.escape(named) + r" must"):
        s.log(**{field: bad})


def test_nan_online_leaves_the_filter_as_it_was(test2: Streams) -> None:
    s = test2
    fusion = PlanarFusion(s.x0, t0=s.t0)
    fusion.update_batch(s.log())
    x, p, t = fusion.x.copy(), fusion.P.copy(), fusion.t
    assert t is not None
    later = t + 0.02
    calls: list[tuple[str, Callable[[], object]]] = [
        ("yaw", lambda: fusion.update_yaw(later, math.nan, variance=1e-3)),
        ("t", lambda: fusion.update_yaw_rate(math.nan, 0.0, variance=1e-3)),
        ("variance", lambda: fusion.update_speed(later, 1.0, variance=math.nan)),
        ("omega", lambda: fusion.update_odometry(later, 1.0, math.nan, v_variance=1e-3,
                                                 omega_variance=1e-3)),
        ("t", lambda: fusion.predict(math.nan)),
    ]  # fmt: skip
    for name, call in calls:
        with pytest.raises(ValueError, match=rf"^{name} must be finite"):
            call()
        np.testing.assert_array_equal(fusion.x, x)
        np.testing.assert_array_equal(fusion.P, p)
        assert fusion.t == t


def test_unknown_and_zero_imu_covariances(test2: Streams) -> None:
    """REP 145: orientation covariance[0] = -1 marks "no orientation"; all zeros "unknown"."""
    s = test2
    imu = s.imu
    cov = imu.orientation_covariances.copy()
    ori = imu.orientations.copy()
    gone = np.zeros(len(imu), dtype=bool)
    gone[300:400] = True  # 2 s of an IMU that lost its orientation estimate
    cov[gone] = 0.0
    cov[gone, 0, 0] = -1.0
    ori[gone] = 0.0
    lost = BagImu(
        imu.topic, imu.frame_id, imu.times, imu.record_times, ori, imu.angular_velocities,
        imu.linear_accelerations, cov, imu.angular_velocity_covariances,
        imu.linear_acceleration_covariances,
    )  # fmt: skip
    rotated = lost.to_base(rpy_to_quaternion(0.0, 0.0, 0.3))
    np.testing.assert_array_equal(rotated.orientations[gone], 0.0)  # kept, not invented
    np.testing.assert_array_equal(rotated.orientation_covariances[gone], cov[gone])
    with pytest.raises(ValueError, match=r"^yaw_variance must be in .*-1 marks .*REP 145"):
        s.log(yv=cov[:, 0, 0])
    with pytest.raises(ValueError, match=r"^yaw_variance must be in .*all zeros.*unknown"):
        s.log(yv=cov[:, 2, 2])
    # Dropping those rows, as the message says, fuses the rest: the gyro bridges the gap.
    keep = ~gone
    log = MeasurementLog.from_streams(
        odometry=(s.odom.times, s.odom.twists[:, 0]),
        odometry_variance=(s.odom.twist_covariances[:, 0, 0], 1.0),
        yaw=(imu.times[keep], s.yaw[keep]),
        yaw_variance=cov[keep, 2, 2],
        yaw_rate=(imu.times, s.rate),
        yaw_rate_variance=imu.angular_velocity_covariances[:, 2, 2],
    )
    result = PlanarFusion(s.x0, t0=s.t0).update_batch(log)
    assert np.all(result.status == FusionStatus.ACCEPTED)
    assert np.all(np.isfinite(result.states))
    base = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log())
    end = result.final_pose
    assert math.hypot(end.x - base.final_pose.x, end.y - base.final_pose.y) < 0.05
    # Online, one such reading is refused with the same hint.
    fusion = PlanarFusion(s.x0, t0=s.t0)
    with pytest.raises(ValueError, match=r"^variance must be in .*REP 145"):
        fusion.update_yaw(float(imu.times[300]), 0.0, variance=float(cov[300, 0, 0]))
    with pytest.raises(ValueError, match=r"^variance must be in .*unknown"):
        fusion.update_yaw(float(imu.times[300]), 0.0, variance=float(cov[300, 2, 2]))
    assert fusion.t == s.t0


# ------------------------------------------------------------------ an output timer
def test_output_timer_predicts_a_copy(test1: Streams) -> None:
    """A node publishing at 30 Hz (robot_localization's ``frequency``) on test1, in arrival order.

    The figures of ``PlanarFusion.predict``'s notes: predicting the filter itself at
    each tick makes the lagging IMU readings late (refused exactly when older than
    the newest stamp or tick, counted here independently); predicting a copy leaves
    the filter as it was; ``history`` takes every reading.
    """
    s = test1
    o, i = s.odom, s.imu
    start = max(float(o.record_times[0]), float(i.record_times[0]))
    ticks = np.arange(start, float(o.record_times[-1]), 1.0 / 30.0)
    events = sorted(
        [(float(t), 0, -1) for t in ticks]
        + [(float(rt), 1, k) for k, rt in enumerate(o.record_times)]
        + [(float(rt), 2, k) for k, rt in enumerate(i.record_times)]
    )
    ov = o.twist_covariances[:, 0, 0]
    yv = i.orientation_covariances[:, 2, 2]
    wv = i.angular_velocity_covariances[:, 2, 2]
    batch = PlanarFusion(s.x0, t0=s.t0).update_batch(s.log()).final_pose

    def run(mode: str, history: float) -> tuple[int, int, float]:
        fusion = PlanarFusion(s.x0, t0=s.t0, history=history)
        newest = s.t0
        refused = expected = 0
        for now, kind, k in events:
            if kind == 0:
                if mode == "filter":
                    fusion.predict(now)
                    newest = max(newest, now)
                else:
                    x, p, t = fusion.x.copy(), fusion.P.copy(), fusion.t
                    ahead = copy.copy(fusion)
                    ahead.predict(max(now, float(ahead.t or now)))
                    np.testing.assert_array_equal(fusion.x, x)
                    np.testing.assert_array_equal(fusion.P, p)
                    assert fusion.t == t
                continue
            if kind == 1:
                stamps = [float(o.times[k])]
                results = [fusion.update_speed(stamps[0], float(o.twists[k, 0]), variance=ov[k])]
            else:
                stamps = [float(i.times[k])] * 2
                results = [
                    fusion.update_yaw(stamps[0], float(s.yaw[k]), variance=yv[k]),
                    fusion.update_yaw_rate(stamps[0], float(s.rate[k]), variance=wv[k]),
                ]
            for stamp, result in zip(stamps, results, strict=True):
                expected += stamp < newest
                newest = max(newest, stamp)
                refused += not result.accepted
        assert np.all(np.isfinite(fusion.x))
        end = fusion.pose
        return refused, expected, math.hypot(end.x - batch.x, end.y - batch.y)

    readings = len(o) + 2 * len(i)
    assert readings == 27682
    refused, expected, off = run("filter", 0.0)
    assert refused == expected == 19411
    assert off == pytest.approx(55.3, abs=0.1)
    refused, expected, off = run("copy", 0.0)
    assert refused == expected == 6154
    assert off == pytest.approx(0.0022, abs=2e-4)
    refused, _, off = run("filter", 0.2)
    assert refused == 0
    assert off == pytest.approx(0.0034, abs=2e-4)
