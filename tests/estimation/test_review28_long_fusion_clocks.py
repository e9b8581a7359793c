"""PlanarFusion in a node that runs for days (review 28, the long-run lens).

Long runs are simulated by starting at large stamps, not by waiting:

* stamps after 2038 (2.2e9 s), beyond 2**32 s (2106) and at 1e10 s give the run
  from 0 s to well within its documented rounding (the filter time is the stamp,
  each ``dt`` a difference of stamps, so nothing accumulates);
* 10**5 predict/update cycles keep ``P`` exactly symmetric and positive definite,
  its variances at their steady state;
* the class notes on clock jumps: a clock that goes back (a bag replayed with
  ``--loop``) or one stamp far ahead leaves every later measurement refused, the
  filter unchanged, until ``reset(fusion.x, fusion.P)`` restarts the clock with
  the estimate kept;
* the notes on the history window: every step of one stamp is kept (the window
  is one of time), so stamps that do not advance grow it step by step.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import FusionStatus, PlanarFusion

EPOCH = 1.76e9
RATE = 200.0


def _drive(fusion: PlanarFusion, base: float, steps: int) -> None:
    """Odometry at ``RATE`` Hz from ``base``, a yaw every fourth step, turning at 0.2 rad/s."""
    for k in range(1, steps + 1):
        t = base + k / RATE
        fusion.update_odometry(t, 0.5, 0.2, v_variance=1e-4, omega_variance=1e-4)
        if k % 4 == 0:
            yaw = math.remainder(0.2 * k / RATE, 2.0 * math.pi)
            fusion.update_yaw(t, yaw, variance=1e-3)


@pytest.mark.parametrize("base", [EPOCH, 2.2e9, 2.0**32 + 0.5, 1e10])
def test_runs_at_far_stamps_are_the_run_from_zero(base: float) -> None:
    # 100 s of 200 Hz odometry. The stamps base + k / RATE are rounded at their
    # size (up to 1e-6 s at 1e10 s, 0.02 % of a step) but never summed: the
    # state ends within 3.3e-8 of the run from 0 (measured; 1e-6 leaves 30x), the
    # covariance, whose Q dt takes each rounded dt, within 3.3e-5 of itself at
    # 1e10 s (4.6e-6 at epoch stamps).
    steps = 20_000
    ref = PlanarFusion(t0=0.0)
    _drive(ref, 0.0, steps)
    far = PlanarFusion(t0=base)
    _drive(far, base, steps)
    assert far.t == base + steps / RATE
    np.testing.assert_allclose(far.x, ref.x, rtol=0.0, atol=1e-6)
    np.testing.assert_allclose(far.P, ref.P, rtol=3e-4, atol=1e-9)


def test_covariance_stays_symmetric_and_positive_over_a_long_run() -> None:
    fusion = PlanarFusion(t0=EPOCH)
    variances = []
    for chunk in range(10):  # 10**5 odometry updates, 25,000 yaw updates
        _drive(fusion, EPOCH + chunk * 50.0, 10_000)
        p = fusion.P
        assert np.array_equal(p, p.T)
        assert np.linalg.eigvalsh(p).min() > 0.0
        variances.append(np.diag(p)[2:])
    # Heading, speed, yaw rate and acceleration are measured (directly or through
    # the model): their variances settle, the last chunks alike to 1 %.
    np.testing.assert_allclose(variances[-1], variances[-2], rtol=1e-2)


def _odometry(fusion: PlanarFusion, t: float):  # type: ignore[no-untyped-def]
    return fusion.update_odometry(t, 0.5, 0.0, v_variance=1e-4, omega_variance=1e-4)


def test_a_clock_gone_back_refuses_until_reset() -> None:
    fusion = PlanarFusion(t0=EPOCH)
    for k in range(1, 501):
        _odometry(fusion, EPOCH + k * 0.02)
    x, p, t = fusion.x, fusion.P, fusion.t
    # The bag starts again (ros2 bag play --loop): 10 s back, then forward again.
    replayed = [_odometry(fusion, EPOCH + k * 0.02) for k in range(1, 500)]
    assert all(r.status is FusionStatus.OUT_OF_ORDER for r in replayed)
    assert np.array_equal(fusion.x, x) and np.array_equal(fusion.P, p) and fusion.t == t
    fusion.reset(fusion.x, fusion.P)  # as the class notes say: the estimate kept
    assert np.array_equal(fusion.x, x)
    taken = [_odometry(fusion, EPOCH + k * 0.02) for k in range(1, 50)]
    assert all(r.accepted for r in taken)
    assert fusion.t == EPOCH + 49 * 0.02


def test_one_stamp_far_ahead_moves_the_clock_there() -> None:
    fusion = PlanarFusion(t0=EPOCH)
    for k in range(1, 501):
        _odometry(fusion, EPOCH + k * 0.02)
    before = fusion.pose
    ahead = EPOCH + 10.0 + 1000.0
    assert fusion.update_yaw(ahead, 0.0, variance=1e-2).accepted  # a corrupt stamp
    assert fusion.t == ahead
    # Predicted over the whole gap at the speed it had (0.5 m/s): the notes' 500 m.
    moved = math.hypot(fusion.pose.x - before.x, fusion.pose.y - before.y)
    assert 499.0 < moved < 502.0
    later = [_odometry(fusion, EPOCH + 10.0 + k * 0.02) for k in range(1, 1001)]
    assert all(r.status is FusionStatus.OUT_OF_ORDER for r in later)
    fusion.reset(fusion.x, fusion.P)
    assert _odometry(fusion, EPOCH + 30.02).accepted


def test_steps_of_one_stamp_are_all_kept() -> None:
    # The class notes: the window is one of time, not of steps.
    fusion = PlanarFusion(t0=EPOCH, history=0.5)
    for n in range(1, 201):
        assert fusion.update_yaw(EPOCH, 0.0, variance=1e-3).accepted
        assert _odometry(fusion, EPOCH).accepted  # goes back before the yaws of EPOCH
        assert len(fusion._entries) == 2 * n
    # A stamp that advances past the window lets them all go.
    assert _odometry(fusion, EPOCH + 1.0).accepted
    assert len(fusion._entries) == 1
