"""Time: the online PlanarFusion at epoch stamps, late measurements included; EKF agreement.

Review 31 (METAMORPH). Only stamp differences enter the model, and PlanarFusion
documents that the filter time is the last stamp, never a sum, so a run shifted
by a constant whose differences stay exact is the same run. Stamps here are
multiples of 1/64 s below 2**24 s in the unshifted run: shifted by 1.7e9 s
(``2**30 < 1.7e9 < 2**31``, where floats lie ``2**-22`` s apart) or by any of
the other shifts, every stamp and every difference is exact, so the shifted run
must give the same statuses, states and covariances bit for bit, also along the
online path with ``history`` (late measurements rewind and replay; the age test
``t - stamp <= history`` has a slack of ``2**-51 (|t| + |stamp| + history)``,
1.5 µs at epoch stamps, far below the 1/64 s grid, so no decision changes).
review 8 checked :meth:`PlanarFusion.update_batch` under integer shifts up to
1000 s; this is the online path and the epoch range.

The general :class:`ExtendedKalmanFilter` given PlanarFusion's model (the
benchmark's ``motion``) and the same odometry reaches PlanarFusion's state at
epoch stamps: same steps, the same arithmetic up to rounding, so to the
benchmark's bound ``SAME_STATE_RTOL = 1e-12`` (after 200 steps the two differ
by about 1e-15 relative).
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from test_ekf import planar_model  # the fusion model as EKF callbacks

from hypothesis_twins import slow_twin
from navkit.estimation import ExtendedKalmanFilter, PlanarFusion

TICK = 1.0 / 64.0
SHIFTS = (1.7e9, 2.0**31, 123456.0, -(2.0**30))
Q_PER_S = np.diag([0.05, 0.05, 0.06, 0.025, 0.02, 0.01])

# (tick, kind, a, b): a measurement stamped tick / 64 s; kinds 0..3 are odometry (v=a,
# omega=b), yaw (3a), yaw rate (b), speed (a).
events = st.lists(
    st.tuples(
        st.integers(1, 400),
        st.integers(0, 3),
        st.floats(-1.0, 1.0),
        st.floats(-1.0, 1.0),
    ),
    min_size=1,
    max_size=60,
)


def _online(
    order: list[tuple[int, int, float, float]], shift: float, history: float
) -> tuple[list[tuple[str, bool]], np.ndarray, np.ndarray, float | None]:
    fusion = PlanarFusion(
        np.zeros(6), process_noise=Q_PER_S, t0=shift, history=history, gate_probability=0.999
    )
    statuses = []
    for tick, kind, a, b in order:
        t = shift + tick * TICK
        if kind == 0:
            r = fusion.update_odometry(t, a, b, v_variance=1e-3, omega_variance=1e-3)
        elif kind == 1:
            r = fusion.update_yaw(t, 3.0 * a, variance=1e-2)
        elif kind == 2:
            r = fusion.update_yaw_rate(t, b, variance=1e-4)
        else:
            r = fusion.update_speed(t, a, variance=1e-3)
        statuses.append((r.status.name, r.accepted))
    return statuses, fusion.x, fusion.P, fusion.t


@settings(max_examples=30, deadline=None)
@given(
    log=events,
    swaps=st.lists(st.booleans(), max_size=60),
    history_ticks=st.sampled_from([0, 4, 20]),
    shift=st.sampled_from(SHIFTS),
)
def test_online_fusion_shifted_to_epoch_stamps_is_the_same_run(
    log: list[tuple[int, int, float, float]],
    swaps: list[bool],
    history_ticks: int,
    shift: float,
) -> None:
    order = sorted(log, key=lambda e: e[0])
    # Neighbours swapped: late measurements, fused (history) or refused (OUT_OF_ORDER).
    for i, swap in enumerate(swaps[: len(order) - 1]):
        if swap:
            order[i], order[i + 1] = order[i + 1], order[i]
    history = history_ticks * TICK
    statuses, x, p, t = _online(order, 0.0, history)
    s_statuses, s_x, s_p, s_t = _online(order, shift, history)
    assert s_statuses == statuses
    np.testing.assert_array_equal(s_x, x)
    np.testing.assert_array_equal(s_p, p)
    assert t is not None and s_t == shift + t


test_online_fusion_shifted_to_epoch_stamps_is_the_same_run_thoroughly = slow_twin(
    test_online_fusion_shifted_to_epoch_stamps_is_the_same_run, max_examples=150
)


@settings(max_examples=10, deadline=None)
@given(
    shift=st.sampled_from((0.0, *SHIFTS)),
    seed=st.integers(0, 2**32 - 1),
    ticks=st.sampled_from([1, 2, 3]),
)
def test_ekf_with_the_fusion_model_agrees_at_epoch_stamps(
    shift: float, seed: int, ticks: int
) -> None:
    rng = np.random.default_rng(seed)
    steps = 200
    dt = ticks * TICK
    z = np.column_stack((rng.uniform(-1.0, 1.0, steps), rng.uniform(-1.0, 1.0, steps)))
    x0 = np.zeros(6)
    p0 = np.diag([1e-9, 1e-9, 1e-9, 1.0, 1.0, 1.0])
    h_odom = np.zeros((2, 6))
    h_odom[0, 3] = h_odom[1, 4] = 1.0
    r_odom = np.diag([1e-3, 1e-3])
    f, jac = planar_model(dt)
    ekf = ExtendedKalmanFilter(x0, p0, angle_states=(2,))
    fusion = PlanarFusion(x0, p0, process_noise=Q_PER_S, t0=shift)
    for i in range(steps):
        ekf.predict(f, jac, Q_PER_S * dt)
        ekf.update(z[i], lambda x: h_odom @ x, h_odom, r_odom)
        fusion.update_odometry(
            shift + (i + 1) * dt, z[i, 0], z[i, 1], v_variance=1e-3, omega_variance=1e-3
        )
    x, p = fusion.x, fusion.P
    rtol = 1e-12  # benchmarks/test_bench_ekf.py SAME_STATE_RTOL
    e_x = np.array(ekf.x, dtype=np.float64)
    e_x[2] = x[2] + math.remainder(e_x[2] - x[2], 2.0 * math.pi)
    np.testing.assert_allclose(e_x, x, rtol=rtol, atol=rtol * float(np.max(np.abs(x))))
    np.testing.assert_allclose(ekf.P, p, rtol=rtol, atol=rtol * float(np.max(np.abs(p))))
