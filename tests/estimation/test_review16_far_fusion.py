"""PlanarFusion far from the origin: a UTM start must not drift by rounding.

PlanarFusion observes no position: x and y are dead reckoning, each prediction
adding ``v dt`` along the heading. Added to the coordinates themselves, every
step was rounded at their size, with one sign for steady motion: 1 kHz odometry
at 1 m/s from a UTM northing (5e6 m, floats 9.3e-10 m apart) drifted by
0.16 mm per km (1.6 cm per 100 km), 10^5 times what the start's own
representation forces. The filter now keeps the start apart and sums the motion
from it.

Checks, against the same log from the origin shifted by the start (exact: both
starts are representable and the motion does not depend on the start):

* states, :attr:`x`, :attr:`pose` and every row of :meth:`update_batch`'s result
  match within a few float spacings of the coordinates (hypothesis over starts,
  headings, speeds), online and batch alike;
* a straight 100 m run at 1 kHz from a UTM northing ends within 1e-8 m of the
  exact sum (it ended 1.6e-5 m off);
* online updates and ``update_batch`` agree bit for bit far from the origin;
* copies and pickles carry on bit for bit; pickles made before the change (the
  buffer holding absolute positions) restore the same pose;
* a start at the origin keeps the states bit for bit (the buffer holds them).
"""

from __future__ import annotations

import copy
import math
import pickle
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.estimation import _fusion as fusion_module
from navkit.geometry import Pose2D


def _tolerance(*coordinates: float) -> float:
    return 4.0 * max(float(np.spacing(abs(c))) for c in coordinates)


def _log(n: int, speed: float, omega: float) -> MeasurementLog:
    t = np.arange(1, n + 1) * 0.001
    return MeasurementLog.from_streams(
        odometry=(t, np.full(n, speed), np.full(n, omega)), odometry_variance=(1e-6, 1e-6)
    )


@settings(max_examples=25, deadline=None)
@given(
    x0=st.floats(4e5, 8e5),
    y0=st.floats(1e6, 1e7),
    theta=st.floats(-math.pi, math.pi),
    speed=st.floats(0.1, 3.0),
    omega=st.sampled_from([0.0, 1e-3, -0.05]),
)
def test_far_start_is_the_origin_run_shifted(
    x0: float, y0: float, theta: float, speed: float, omega: float
) -> None:
    log = _log(3000, speed, omega)
    near = PlanarFusion(x0=[0.0, 0.0, theta, speed, omega, 0.0], t0=0.0)
    far = PlanarFusion(x0=[x0, y0, theta, speed, omega, 0.0], t0=0.0)
    a = near.update_batch(log).states
    b = far.update_batch(log).states
    tol = _tolerance(x0 + 1e3, y0 + 1e3)
    assert np.abs(b[:, 0] - (x0 + a[:, 0])).max() <= tol
    assert np.abs(b[:, 1] - (y0 + a[:, 1])).max() <= tol
    np.testing.assert_array_equal(b[:, 2:], a[:, 2:])
    assert abs(far.pose.x - (x0 + near.pose.x)) <= tol
    assert abs(far.x[1] - (y0 + near.x[1])) <= tol
    # Online, step by step, the same.
    online = PlanarFusion(x0=[x0, y0, theta, speed, omega, 0.0], t0=0.0)
    for i in range(300):
        online.update_odometry(log.times[i], speed, omega, v_variance=1e-6, omega_variance=1e-6)
    np.testing.assert_array_equal(online.x, b[299])


def test_straight_run_at_a_utm_northing_matches_the_exact_sum() -> None:
    y0 = 5123456.5
    n = 100_000
    fusion = PlanarFusion(x0=[512345.25, y0, math.pi / 2, 1.0, 0.0, 0.0], t0=0.0)
    fusion.update_batch(_log(n, 1.0, 0.0))
    # Each step moves sin(pi/2) * (1.0 * dt) along y, dt the difference of the stamps.
    t = np.arange(0, n + 1) * 0.001
    exact = Fraction(y0) + sum((Fraction(float(d)) for d in np.diff(t)), Fraction(0))
    assert math.sin(math.pi / 2) == 1.0
    assert abs(Fraction(fusion.pose.y) - exact) <= Fraction(1, 10**8)
    assert abs(fusion.pose.x - 512345.25) <= 1e-9  # cos(pi/2) = 6e-17: 6e-12 m over 100 m


def test_online_and_batch_agree_bit_for_bit_far_from_origin() -> None:
    rng = np.random.default_rng(4)
    n = 500
    t = np.cumsum(rng.uniform(5e-4, 2e-3, n))
    v = 1.0 + rng.normal(0.0, 0.1, n)
    w = rng.normal(0.0, 0.2, n)
    x0 = [612345.75, 6123456.25, 0.7, 1.0, 0.0, 0.0]
    batch = PlanarFusion(x0=x0, t0=0.0)
    states = batch.update_batch(MeasurementLog.from_streams(odometry=(t, v, w))).states
    online = PlanarFusion(x0=x0, t0=0.0)
    for i in range(n):
        online.update_odometry(float(t[i]), float(v[i]), float(w[i]),
                               v_variance=1e-3, omega_variance=1e-3)
        np.testing.assert_array_equal(online.x, states[i])
    assert online.pose == batch.pose
    # The repr writes the far position in full (review 36: it was 6.1235e+06).
    assert repr(online) == repr(batch) and repr(float(online.x[1])) in repr(online)


@pytest.mark.parametrize("copier", [copy.copy, copy.deepcopy,
                                     lambda o: pickle.loads(pickle.dumps(o))])
def test_copies_carry_on_alike(copier: object) -> None:
    fusion = PlanarFusion(x0=[512345.25, 5123456.5, 0.3, 1.0, 0.0, 0.0], t0=0.0)
    fusion.update_batch(_log(200, 1.0, 0.1))
    twin = copier(fusion)  # type: ignore[operator]
    assert twin.pose == fusion.pose
    log = MeasurementLog.from_streams(
        odometry=(0.2 + np.arange(1, 101) * 0.001, np.ones(100), np.zeros(100)))
    np.testing.assert_array_equal(twin.update_batch(log).states, fusion.update_batch(log).states)


def test_pickle_from_before_the_change_restores_the_absolute_pose() -> None:
    fusion = PlanarFusion(x0=[512345.25, 5123456.5, 0.3, 1.0, 0.0, 0.0], t0=0.0)
    fusion.update_batch(_log(50, 1.0, 0.1))
    expected = fusion.x
    # A former pickle: the buffer with the absolute state, two or three arguments.
    buf = fusion._buf.copy()
    buf[:2] = expected[:2]
    for args in ((buf.copy(), fusion._gates.copy()),
                 (buf.copy(), fusion._gates.copy(), PlanarFusion)):
        old = fusion_module._restore_fusion(*args)  # type: ignore[arg-type]
        np.testing.assert_array_equal(old.x, expected)
        assert old.pose == fusion.pose


def test_origin_start_states_are_the_buffer_bit_for_bit() -> None:
    fusion = PlanarFusion(x0=[0.0, 0.0, 0.3, 1.0, 0.0, 0.0], t0=0.0)
    result = fusion.update_batch(_log(100, 1.0, 0.1))
    np.testing.assert_array_equal(result.states[-1], fusion._buf[:6])
    assert fusion.pose == Pose2D(*fusion._buf[:3].tolist())
    signed = PlanarFusion(x0=[-0.0, -0.0, 0.0, 0.0, 0.0, 0.0])
    assert math.copysign(1.0, signed.pose.x) == -1.0  # kept as given
