"""PlanarFusion(history=): measurements of one stamp in the batch's order (review 23, FUSION2).

``history`` promises the numbers of :meth:`PlanarFusion.update_batch` of the
log :meth:`MeasurementLog.from_streams` makes of the measurements, bit for
bit. That log orders equal stamps by kind (odometry, yaw, yaw rate,
acceleration); online, a measurement stamped as the newest step kept was
fused at once, after it: odometry and yaw rate at 0.2 s and 0.3 s arriving
yaw-rate-first ended 2.8e-17 m and rad/s away from the batch (late, or
odometry-first, they matched). Now such a measurement goes back before the
steps of its stamp that follow it in that order, as a late one does. These
tests pin every arrival order of small runs with ties against the batch,
the results of the measurements placed so, predicts at a tied stamp, one
kind's ties in arrival order, and the plain filter (no ``history``) fusing
ties as they come. (The random interleavings with frequent ties are in
``test_review22_fusion_history.py``.)
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion

# The review's reproducer: odometry (t, v, omega) and yaw rates (t, omega).
_ODOM = ([0.1, 0.2, 0.3], [0.5, 0.6, 0.7], [0.1, 0.2, 0.0])
_GYRO = ([0.2, 0.3], [0.3, -0.2])
_ODOM_VAR = (1e-3, 1e-3)
_GYRO_VAR = 1e-4


def _feed(fusion: PlanarFusion, m: tuple[str, int], stamp: Any = float) -> Any:
    kind, i = m
    if kind == "o":
        t, v, w = (c[i] for c in _ODOM)
        return fusion.update_odometry(
            stamp(t), v, w, v_variance=_ODOM_VAR[0], omega_variance=_ODOM_VAR[1]
        )
    t, w = (c[i] for c in _GYRO)
    return fusion.update_yaw_rate(stamp(t), w, variance=_GYRO_VAR)


def _same(a: PlanarFusion, b_x: np.ndarray, b_p: np.ndarray, t: float) -> bool:
    return a.t == t and np.array_equal(a.x, b_x) and np.array_equal(a.P, b_p)


def _reproducer_batch() -> Any:
    log = MeasurementLog.from_streams(
        odometry=_ODOM, odometry_variance=_ODOM_VAR, yaw_rate=_GYRO, yaw_rate_variance=_GYRO_VAR
    )
    return log, PlanarFusion(t0=0.0).update_batch(log)


def test_the_review_s_arrival_order_equals_the_batch() -> None:
    _, batch = _reproducer_batch()
    fusion = PlanarFusion(t0=0.0, history=1.0)
    for m in [("o", 0), ("y", 0), ("o", 1), ("y", 1), ("o", 2)]:
        _feed(fusion, m)
    assert _same(fusion, batch.states[-1], batch.covariances[-1], 0.3)


@pytest.mark.parametrize("stamp", [float, np.float64], ids=["fast", "checked"])
def test_every_arrival_order_equals_the_batch(stamp: Any) -> None:
    # 120 orders of the five measurements (all within the window): each ends as the
    # batch, and the last one's result is its row's (the state before it is the
    # batch's state before its row).
    log, batch = _reproducer_batch()
    rows = {("o", i): int(np.flatnonzero((log.times == t) & log.observed[:, 1])[0])
            for i, t in enumerate(_ODOM[0])}  # fmt: skip
    rows |= {("y", i): int(np.flatnonzero((log.times == t) & ~log.observed[:, 1])[0])
             for i, t in enumerate(_GYRO[0])}  # fmt: skip
    measurements = list(rows)
    for order in itertools.permutations(measurements):
        fusion = PlanarFusion(t0=0.0, history=1.0)
        for m in order:
            result = _feed(fusion, m, stamp)
            assert result.accepted
        assert _same(fusion, batch.states[-1], batch.covariances[-1], 0.3), order
        # The last arrival's own update: at its place, after every row before it.
        assert result.nis == batch.nis[rows[order[-1]]], order


# One stamp's readings of every kind, and a step before them.
_ONE_STAMP = {
    "odometry": lambda f, t: f.update_odometry(t, 1.0, 0.3, v_variance=1e-2, omega_variance=1e-2),
    "yaw": lambda f, t: f.update_yaw(t, 0.4, variance=1e-2),
    "yaw_rate": lambda f, t: f.update_yaw_rate(t, -0.2, variance=1e-3),
    "acceleration": lambda f, t: f.update_acceleration(t, 0.5, variance=1e-2),
}


def _one_stamp_batch(*, predict: bool = False) -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0)
    fusion.update_batch(MeasurementLog.from_streams(
        odometry=([0.1, 0.2], [1.0, 1.0], [0.3, 0.3]), odometry_variance=(1e-2, 1e-2),
        yaw=([0.2], [0.4]), yaw_variance=1e-2, yaw_rate=([0.2], [-0.2]),
        yaw_rate_variance=1e-3, acceleration=([0.2], [0.5]), acceleration_variance=1e-2,
    ))  # fmt: skip
    return fusion


@pytest.mark.parametrize("predict", ["none", "before", "after"])
def test_one_stamp_of_every_kind_in_any_order_equals_the_batch(predict: str) -> None:
    # An IMU message (yaw, yaw rate, acceleration) and odometry stamped alike, in all
    # 24 orders; a predict to that stamp (no time passes after it) changes nothing.
    batch = _one_stamp_batch()
    for order in itertools.permutations(_ONE_STAMP):
        fusion = PlanarFusion(t0=0.0, history=0.5)
        _ONE_STAMP["odometry"](fusion, 0.1)
        if predict == "before":
            fusion.predict(0.2)
        for n, kind in enumerate(order):
            assert _ONE_STAMP[kind](fusion, 0.2).accepted
            if predict == "after" and n == 1:
                kept = len(fusion._entries)
                fusion.predict(0.2)
                assert len(fusion._entries) == kept  # no step to keep
        assert fusion.t == batch.t
        np.testing.assert_array_equal(fusion.x, batch.x, err_msg=str(order))
        np.testing.assert_array_equal(fusion.P, batch.P, err_msg=str(order))


def test_a_late_measurement_goes_among_its_stamp_s_in_the_batch_order() -> None:
    # Late (older than the filter time) and tied with kept steps: a yaw rate at 0.2 s
    # goes after the yaw and before the acceleration of 0.2 s.
    batch = _one_stamp_batch()
    fusion = PlanarFusion(t0=0.0, history=0.5)
    _ONE_STAMP["odometry"](fusion, 0.1)
    for kind in ("acceleration", "yaw", "odometry"):
        _ONE_STAMP[kind](fusion, 0.2)
    fusion.predict(0.25)
    assert _ONE_STAMP["yaw_rate"](fusion, 0.2).accepted
    batch.predict(0.25)
    assert fusion.t == batch.t == 0.25
    np.testing.assert_array_equal(fusion.x, batch.x)
    np.testing.assert_array_equal(fusion.P, batch.P)


@pytest.mark.parametrize("values", [(0.3, -0.1), (-0.1, 0.3)])
def test_one_kind_at_one_stamp_stays_in_the_order_it_came(values: tuple[float, float]) -> None:
    # Two yaws of one stamp, and a yaw rate of it arriving between and after them:
    # the yaws in the order they came, as in their stream (from_streams sorts stably).
    fusion = PlanarFusion(t0=0.0, history=1.0)
    fusion.update_yaw_rate(0.1, 0.2, variance=1e-3)
    fusion.update_yaw(0.2, values[0], variance=1e-2)
    fusion.update_yaw_rate(0.2, 0.1, variance=1e-3)
    fusion.update_yaw(0.2, values[1], variance=1e-2)
    batch = PlanarFusion(t0=0.0)
    batch.update_batch(MeasurementLog.from_streams(
        yaw=([0.2, 0.2], list(values)), yaw_variance=1e-2,
        yaw_rate=([0.1, 0.2], [0.2, 0.1]), yaw_rate_variance=1e-3,
    ))  # fmt: skip
    np.testing.assert_array_equal(fusion.x, batch.x)
    np.testing.assert_array_equal(fusion.P, batch.P)


def test_without_history_one_stamp_is_fused_as_it_comes() -> None:
    # The plain filter keeps no steps: a tie is fused at once, in arrival order (the
    # batch of the log in that order), as before.
    fusion = PlanarFusion(t0=0.0)
    for m in [("o", 0), ("y", 0), ("o", 1)]:
        assert _feed(fusion, m).accepted
    arrival = MeasurementLog(
        [0.1, 0.2, 0.2],
        [[0.0, 0.5, 0.1, 0.0], [0.0, 0.0, 0.3, 0.0], [0.0, 0.6, 0.2, 0.0]],
        [[1.0, 1e-3, 1e-3, 1.0], [1.0, 1.0, 1e-4, 1.0], [1.0, 1e-3, 1e-3, 1.0]],
        np.array([[0, 1, 1, 0], [0, 0, 1, 0], [0, 1, 1, 0]], dtype=bool),
    )
    batch = PlanarFusion(t0=0.0)
    batch.update_batch(arrival)
    np.testing.assert_array_equal(fusion.x, batch.x)
    np.testing.assert_array_equal(fusion.P, batch.P)
