"""EKF step speed against filterpy, and the batch fusion kernel on 100,000 measurements.

Run with ``python -m pytest benchmarks/test_bench_ekf.py --benchmark-only``.

The model is PlanarFusion's: state [x, y, θ, v, ω, a], constant-acceleration
unicycle with mid-step heading, process noise per second, and a wheel-odometry
(v, ω) measurement. One "step" is predict-to-the-measurement-time plus update.
Each round runs ``STEPS`` = 1000 steps (so milliseconds per round read as
microseconds per step); the table's ratio column within the ``ekf-step-x1000``
group is the speed-up the issue's ≥ 10× target refers to, and
``extra_info["us_per_step"]`` (``--benchmark-json``) records the mean per step.

* ``filterpy``: ``filterpy.kalman.ExtendedKalmanFilter`` with ``predict_x``
  overridden by the nonlinear motion model and ``F``/``Q`` set every step (its
  ``update`` is also Joseph form).
* ``navkit_planar``: :meth:`PlanarFusion.update_odometry` (validation, one
  compiled predict+update kernel call, an ``UpdateResult``).
* ``navkit_general``: the general :class:`ExtendedKalmanFilter` (type and shape
  checks in Python, one compiled kernel per predict and per update) with the
  same Python model functions as filterpy; issue 17's goal is ≥ 3× filterpy.
* group ``ekf-step-ratio``: filterpy ÷ the general filter, alternately in one
  loop (``extra_info["filterpy_over_navkit"]``), the issue's ≥ 3× row; in the
  same loop the model functions alone (``filterpy_over_callbacks``: the most
  any filter driven by them can reach, the Jacobian and f costing about three
  quarters of navkit's step) and the filters without them
  (``machinery_filterpy_over_navkit``).
* ``model_callbacks``: only the Python model functions both filters call every
  step (the Jacobian, f, h, each on a copy of the state): the floor of any
  filter driven by them. ``general − callbacks`` against ``filterpy − callbacks``
  is the speed-up of the filter machinery itself.
* group ``ekf-predict-x1000``: the same three without the update (filterpy's
  and the general filter's predict, the Jacobian and f), so that the update's
  share is the step minus the predict.
* ``batch_100k``: :meth:`PlanarFusion.update_batch` over a 100,000-row log (odometry at
  50 Hz, IMU yaw at 50 Hz, gyro at 100 Hz).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, MeasurementLog, PlanarFusion
from test_bench_astar import peer

# filterpy is a peer (``test`` extra): without it its tests skip (peer()), and the
# navkit filters are checked against each other instead.
try:
    from filterpy.kalman import ExtendedKalmanFilter as FilterpyEKF
except ImportError:
    FilterpyEKF = None

STEPS = 1000
DT = 0.02
Q_PER_S = np.diag([0.05, 0.05, 0.06, 0.025, 0.02, 0.01])
R_ODOM = np.diag([1e-3, 1e-3])
H_ODOM = np.zeros((2, 6))
H_ODOM[0, 3] = H_ODOM[1, 4] = 1.0
X0 = np.zeros(6)
P0 = np.diag([1e-9, 1e-9, 1e-9, 1.0, 1.0, 1.0])


def motion(
    dt: float,
) -> tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]:
    def f(x: np.ndarray) -> np.ndarray:
        s = x[3] * dt + 0.5 * x[5] * dt * dt
        mid = x[2] + 0.5 * x[4] * dt
        return np.array(
            [x[0] + s * math.cos(mid), x[1] + s * math.sin(mid), x[2] + x[4] * dt,
             x[3] + x[5] * dt, x[4], x[5]]
        )  # fmt: skip

    def jac(x: np.ndarray) -> np.ndarray:
        s = x[3] * dt + 0.5 * x[5] * dt * dt
        mid = x[2] + 0.5 * x[4] * dt
        c, sn = math.cos(mid), math.sin(mid)
        out = np.eye(6)
        out[0, 2:6] = [-s * sn, dt * c, -0.5 * dt * s * sn, 0.5 * dt * dt * c]
        out[1, 2:6] = [s * c, dt * sn, 0.5 * dt * s * c, 0.5 * dt * dt * sn]
        out[2, 4] = dt
        out[3, 5] = dt
        return out

    return f, jac


MEASUREMENTS = np.column_stack(
    (0.8 + 0.05 * np.sin(np.arange(STEPS) * 0.01), 0.3 + 0.02 * np.cos(np.arange(STEPS) * 0.03))
)


def per_step(benchmark: Any) -> None:
    """The mean per step in ``extra_info`` (nothing under ``--benchmark-disable``)."""
    if benchmark.stats is not None:
        benchmark.extra_info["us_per_step"] = round(benchmark.stats.stats.mean / STEPS * 1e6, 3)


State = tuple[np.ndarray, np.ndarray]


#: Issue 17's bound on the EKF against filterpy: the filters reach the same state to
#: 1e-12. After the 1000 steps they differ by about 1e-13 (rounding, and navkit's wrapped
#: heading), so a check at 1e-9 would pass a filter a thousand times further off.
SAME_STATE_RTOL = 1e-12


def assert_same_state(ours: State, theirs: State) -> None:
    """Final state and covariance of two filters equal to :data:`SAME_STATE_RTOL`.

    The heading is compared modulo 2π; entries near zero to the same bound
    relative to the largest entry of x or P.
    """
    (x, p), (x2, p2) = ours, theirs
    x, p = np.ravel(x), np.asarray(p, dtype=np.float64)
    x2 = np.array(x2, dtype=np.float64).ravel()
    x2[2] = math.remainder(x2[2], 2.0 * math.pi)  # filterpy does not wrap the heading
    rtol = SAME_STATE_RTOL
    np.testing.assert_allclose(x2, x, rtol=rtol, atol=rtol * float(np.max(np.abs(x))))
    np.testing.assert_allclose(p2, p, rtol=rtol, atol=rtol * float(np.max(np.abs(p))))


def filterpy_steps() -> Callable[[], State]:
    """``STEPS`` filterpy steps from X0, P0 (a new filter per call); the final x, P."""
    peer("filterpy")
    f, jac = motion(DT)
    q = Q_PER_S * DT

    class Model(FilterpyEKF):  # type: ignore[misc]
        def predict_x(self, u: object = 0) -> None:
            self.x = f(self.x)

    def hjac(x: np.ndarray) -> np.ndarray:
        return H_ODOM

    def hx(x: np.ndarray) -> np.ndarray:
        return H_ODOM @ x

    def run() -> State:
        ekf = Model(dim_x=6, dim_z=2)
        ekf.x = X0.copy()
        ekf.P = P0.copy()
        ekf.Q = q
        for z in MEASUREMENTS:
            ekf.F = jac(ekf.x)
            ekf.predict()
            ekf.update(z, hjac, hx, R=R_ODOM)
        return ekf.x, ekf.P

    return run


def navkit_steps() -> Callable[[], State]:
    """``STEPS`` steps of navkit's general EKF from X0, P0 (a new filter per call); x, P."""
    f, jac = motion(DT)
    q = Q_PER_S * DT

    def h(x: np.ndarray) -> np.ndarray:
        return H_ODOM @ x

    def run() -> State:
        ekf = ExtendedKalmanFilter(X0, P0, angle_states=(2,))
        for z in MEASUREMENTS:
            ekf.predict(f, jac, q)
            ekf.update(z, h, H_ODOM, R_ODOM)
        return ekf.x, ekf.P

    return run


def planar_steps() -> Callable[[], State]:
    """``STEPS`` :meth:`PlanarFusion.update_odometry` calls from X0, P0 (compiled); x, P."""
    times = DT * np.arange(1, STEPS + 1)
    rows = [(float(t), float(z[0]), float(z[1])) for t, z in zip(times, MEASUREMENTS, strict=True)]
    PlanarFusion(X0, P0, process_noise=Q_PER_S, t0=0.0).update_odometry(
        DT, 0.0, 0.0, v_variance=1.0, omega_variance=1.0
    )

    def run() -> State:
        fusion = PlanarFusion(X0, P0, process_noise=Q_PER_S, t0=0.0)
        for t, v, w in rows:
            fusion.update_odometry(t, v, w, v_variance=1e-3, omega_variance=1e-3)
        return fusion.x, fusion.P

    return run


def reference_state(other: Callable[[], Callable[[], State]]) -> State:
    """What a navkit filter must reach: filterpy's state, else the ``other`` navkit filter's."""
    return filterpy_steps()() if FilterpyEKF is not None else other()()


@pytest.mark.benchmark(group="ekf-step-x1000")
def test_step_filterpy(benchmark: Any) -> None:
    run = filterpy_steps()
    assert_same_state(navkit_steps()(), run())
    benchmark(run)
    per_step(benchmark)


@pytest.mark.benchmark(group="ekf-step-x1000")
def test_step_navkit_planar(benchmark: Any) -> None:
    run = planar_steps()
    assert_same_state(run(), reference_state(navkit_steps))
    benchmark(run)
    per_step(benchmark)


@pytest.mark.benchmark(group="ekf-step-x1000")
def test_step_navkit_general_ekf(benchmark: Any) -> None:
    run = navkit_steps()
    assert_same_state(run(), reference_state(planar_steps))
    benchmark(run)
    per_step(benchmark)


@pytest.mark.benchmark(group="ekf-step-ratio")
def test_step_ratio_to_filterpy(benchmark: Any) -> None:
    """filterpy's ``STEPS`` steps ÷ the general EKF's, alternately in one loop.

    The issue's row (≥ 3): ``filterpy_over_navkit`` in ``extra_info``, the
    median per-round ratio of this thread's CPU time, so machine load and
    memory state affect both alike. The order is reversed every other round,
    and every round's two final states are checked equal to
    :data:`SAME_STATE_RTOL` outside the timers: a filter that went wrong under
    the timing fails the test instead of reporting a speed-up.
    """
    ours, theirs = navkit_steps(), filterpy_steps()
    assert_same_state(ours(), theirs())  # checked (and warm) before the timed rounds

    floor = callback_steps()
    sides: dict[str, Callable[[], Any]] = {"filterpy": theirs, "navkit": ours, "floor": floor}

    def rounds() -> dict[str, float]:
        ratios, ceilings, machinery = [], [], []
        for i in range(41):
            spent, states = {}, {}
            for side in sides if i % 2 == 0 else list(sides)[::-1]:
                c0 = time.thread_time()
                states[side] = sides[side]()
                spent[side] = time.thread_time() - c0
            assert_same_state(states["navkit"], states["filterpy"])
            theirs_s, ours_s, floor_s = spent["filterpy"], spent["navkit"], spent["floor"]
            ratios.append(theirs_s / ours_s)
            ceilings.append(theirs_s / floor_s)
            machinery.append((theirs_s - floor_s) / max(ours_s - floor_s, 1e-9))
        return {
            "filterpy_over_navkit": float(np.median(ratios)),
            "filterpy_over_callbacks": float(np.median(ceilings)),
            "machinery_filterpy_over_navkit": float(np.median(machinery)),
        }

    benchmark.extra_info.update(benchmark.pedantic(rounds, rounds=1, iterations=1))


def callback_steps() -> Callable[[], None]:
    """``STEPS`` calls of the model functions both filters call every step (F, f, h).

    Each on a copy of the state, as navkit calls them (filterpy passes its own).
    """
    f, jac = motion(DT)

    def h(x: np.ndarray) -> np.ndarray:
        return H_ODOM @ x

    def run() -> None:
        x = X0.copy()
        for _ in MEASUREMENTS:
            jac(x.copy())
            f(x.copy())
            h(x.copy())

    return run


@pytest.mark.benchmark(group="ekf-step-x1000")
def test_step_model_callbacks(benchmark: Any) -> None:
    benchmark(callback_steps())
    per_step(benchmark)


def _filterpy_model(f: Callable[[np.ndarray], np.ndarray]) -> Any:
    """A filterpy EKF at X0, P0 whose predict runs ``f``."""
    peer("filterpy")

    class Model(FilterpyEKF):  # type: ignore[misc]
        def predict_x(self, u: object = 0) -> None:
            self.x = f(self.x)

    ekf = Model(dim_x=6, dim_z=2)
    ekf.x = X0.copy()
    ekf.P = P0.copy()
    return ekf


@pytest.mark.benchmark(group="ekf-predict-x1000")
def test_predict_filterpy(benchmark: Any) -> None:
    f, jac = motion(DT)
    q = Q_PER_S * DT

    def run() -> State:
        ekf = _filterpy_model(f)
        ekf.Q = q
        for _ in MEASUREMENTS:
            ekf.F = jac(ekf.x)
            ekf.predict()
        return ekf.x, ekf.P

    assert_same_state(navkit_predicts()(), run())
    benchmark(run)
    per_step(benchmark)


def navkit_predicts() -> Callable[[], State]:
    """``STEPS`` predicts of navkit's general EKF from X0, P0; the final x, P."""
    f, jac = motion(DT)
    q = Q_PER_S * DT

    def run() -> State:
        ekf = ExtendedKalmanFilter(X0, P0, angle_states=(2,))
        for _ in MEASUREMENTS:
            ekf.predict(f, jac, q)
        return ekf.x, ekf.P

    return run


@pytest.mark.benchmark(group="ekf-predict-x1000")
def test_predict_navkit_general_ekf(benchmark: Any) -> None:
    benchmark(navkit_predicts())
    per_step(benchmark)


@pytest.mark.benchmark(group="ekf-predict-x1000")
def test_predict_model_callbacks(benchmark: Any) -> None:
    f, jac = motion(DT)

    def run() -> None:
        x = X0.copy()
        for _ in MEASUREMENTS:
            jac(x.copy())
            f(x.copy())

    benchmark(run)
    per_step(benchmark)


@pytest.fixture(scope="module")
def log_100k() -> MeasurementLog:
    rng = np.random.default_rng(0)
    n_odom = 25_000  # 50 Hz odometry + 50 Hz yaw + 100 Hz gyro = 100,000 rows over 500 s
    t_odom = np.arange(n_odom) / 50.0
    t_gyro = np.arange(2 * n_odom) / 100.0
    log = MeasurementLog.from_streams(
        odometry=(
            t_odom,
            0.8 + 0.05 * rng.normal(size=n_odom),
            0.3 + 0.02 * rng.normal(size=n_odom),
        ),
        odometry_variance=(0.05**2, 0.02**2),
        yaw=(t_odom + 0.005, np.mod(0.3 * t_odom + math.pi, 2 * math.pi) - math.pi),
        yaw_variance=0.03**2,
        yaw_rate=(t_gyro, 0.3 + 0.01 * rng.normal(size=2 * n_odom)),
        yaw_rate_variance=0.01**2,
    )
    assert len(log) == 100_000
    return log


@pytest.mark.benchmark(group="batch-100k")
def test_batch_100k(benchmark: Any, log_100k: MeasurementLog) -> None:
    PlanarFusion(t0=0.0).update_batch(log_100k)  # compile outside the timing
    result = benchmark(lambda: PlanarFusion(t0=0.0).update_batch(log_100k))
    assert result.states.shape == (100_000, 6)
    if benchmark.stats is not None:
        mean = benchmark.stats.stats.mean
        benchmark.extra_info["us_per_measurement"] = round(mean / 1e5 * 1e6, 3)
