"""Filters and odometries used for many jobs, against fresh ones (review 53, REUSE).

A robot process keeps its filter and odometry for hours. The EKF keeps, per
measurement size, a compiled kernel and a buffer holding the last validated R
and the options, and the last validated Q (``_rbufs``, ``_state``): a filter
that has run any job must continue exactly as a new filter built from its
``x`` and ``P``. The odometries' ``reset(pose)`` promises the odometry the
constructor builds at that pose; ``reset()`` without a pose forgets the
counters only, and its sums go on (documented in review 53: a new odometry at
the current pose may differ in the last bits, which the last test pins both
ways). ``CompassCalibration.reset`` promises a fresh calibration.
PlanarFusion.reset is pinned by review 23.
"""

from __future__ import annotations

from functools import partial
from typing import Any

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from navkit.estimation import CompassCalibration, DiffOdometry, ExtendedKalmanFilter, OmniOdometry
from navkit.kinematics import DiffDrive, OmniDrive

_EKF_OPS = st.lists(
    st.tuples(
        st.sampled_from(["predict", "update"]),
        st.integers(1, 4),  # measurement size
        st.integers(0, 2**32 - 1),  # the step's matrices
        st.integers(0, 5),  # diagonal or scaled-identity noise; gate; angle measurement
    ),
    max_size=8,
)


FloatArray = NDArray[np.float64]


def _constant(value: FloatArray, x: FloatArray) -> FloatArray:
    """A linear model's Jacobian: ``value`` whatever the state ``x``."""
    return value


def _ekf_job(ekf: ExtendedKalmanFilter, ops: list[tuple[str, int, int, int]]) -> list[Any]:
    """Run ``ops``: what each step left (its result, x and P, bytes), or its error."""
    seen: list[Any] = []
    n = ekf.dim
    for kind, m, seed, option in ops:
        rng = np.random.default_rng(seed)
        try:
            if kind == "predict":
                a = np.eye(n) + 0.1 * rng.standard_normal((n, n))
                q = np.diag(rng.uniform(0.01, 1.0, n)) if option % 2 else 0.05 * np.eye(n)
                ekf.predict(partial(np.matmul, a), partial(_constant, a), q)
                seen.append(None)
            else:
                h = rng.standard_normal((m, n))
                r = np.diag(rng.uniform(0.1, 1.0, m)) if option % 2 else 0.5 * np.eye(m)
                options: dict[str, Any] = {}
                if option >= 2:
                    options["gate"] = 3.0
                if option >= 4:
                    options["angle_measurements"] = (0,)
                z = rng.standard_normal(m)
                result = ekf.update(z, partial(np.matmul, h), partial(_constant, h), r, **options)
                seen.append(repr(result))
        except (TypeError, ValueError) as exc:
            seen.append(f"{type(exc).__name__}: {exc}")
        seen.append((ekf.x.tobytes(), ekf.P.tobytes()))
    return seen


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(1, 5), angles=st.booleans(), first=_EKF_OPS, second=_EKF_OPS)
def test_an_ekf_after_any_job_continues_as_a_new_filter_from_its_estimate(
    n: int, angles: bool, first: list[tuple[str, int, int, int]],
    second: list[tuple[str, int, int, int]],
) -> None:  # fmt: skip
    angle_states = (0,) if angles else ()
    reused = ExtendedKalmanFilter(np.zeros(n), np.eye(n), angle_states=angle_states)
    _ekf_job(reused, first)
    fresh = ExtendedKalmanFilter(reused.x.copy(), reused.P.copy(), angle_states=angle_states)
    assert (reused.x.tobytes(), reused.P.tobytes()) == (fresh.x.tobytes(), fresh.P.tobytes())
    assert _ekf_job(reused, second) == _ekf_job(fresh, second)


_DIFF = DiffDrive(track=0.5, wheel_radius=0.1)
_TICKS = st.lists(st.tuples(st.integers(-3000, 3000), st.integers(-3000, 3000)), max_size=15)
_POSES = st.tuples(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6), st.floats(-3.2, 3.2))


def _diff_job(odo: DiffOdometry, ticks: list[tuple[int, int]], bits: int | None) -> list[Any]:
    seen: list[Any] = []
    for left, right in ticks:
        if bits is not None:
            left, right = left % 2**bits, right % 2**bits
        seen.append(odo.update(left, right))
    return seen


@settings(max_examples=80, deadline=None)
@given(
    first=_TICKS, second=_TICKS, pose=_POSES, bits=st.sampled_from([None, 12, 16]),
    method=st.sampled_from(["arc", "midpoint", "first_order"]),
)  # fmt: skip
def test_a_diff_odometry_reset_at_a_pose_is_a_new_one(
    first: list[tuple[int, int]], second: list[tuple[int, int]],
    pose: tuple[float, float, float], bits: int | None, method: Any,
) -> None:  # fmt: skip
    options: dict[str, Any] = {"ticks_per_rev": 1000, "bits": bits, "method": method}
    reused = DiffOdometry(_DIFF, **options)
    _diff_job(reused, first, bits)
    reused.reset(pose)
    assert _diff_job(reused, second, bits) == _diff_job(
        DiffOdometry(_DIFF, pose=pose, **options), second, bits
    )


_OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
_STEPS = st.lists(
    st.tuples(st.lists(st.floats(-2.0, 2.0), min_size=3, max_size=3), st.floats(-3.2, 3.2)),
    max_size=15,
)


@settings(max_examples=80, deadline=None)
@given(first=_STEPS, second=_STEPS, pose=_POSES)
def test_an_omni_odometry_reset_at_a_pose_is_a_new_one(
    first: list[tuple[list[float], float]], second: list[tuple[list[float], float]],
    pose: tuple[float, float, float],
) -> None:  # fmt: skip
    reused = OmniOdometry(_OMNI)
    for wheels, yaw in first:
        reused.update(wheels, yaw)
    reused.reset(pose)
    fresh = OmniOdometry(_OMNI, pose=pose)
    for wheels, yaw in second:
        assert reused.update(wheels, yaw) == fresh.update(wheels, yaw)


def test_a_reset_without_a_pose_goes_on_summing_as_documented() -> None:
    # One tick of the right wheel, then a leg of one tick on and back: after a
    # reset() without a pose the leg gives the poses of the odometry never reset
    # (the counters latched again) and, in the last bit, not those of a new
    # odometry at its pose (the sums restart there); reset(pose=odo.pose) gives
    # the latter.
    first, leg = [(0, 0), (0, 1)], [(0, 0), (0, 1), (0, 0)]
    reset = DiffOdometry(_DIFF, ticks_per_rev=1000)
    _diff_job(reset, first, None)
    at = reset.pose
    kept = DiffOdometry(_DIFF, ticks_per_rev=1000)
    _diff_job(kept, [*first, (0, 1), (0, 2), (0, 1)], None)  # the leg's ticks, shifted
    reset.reset()
    on = _diff_job(reset, leg, None)
    assert on[-1] == kept.pose
    new = _diff_job(DiffOdometry(_DIFF, ticks_per_rev=1000, pose=at), leg, None)
    assert on[-1].x != new[-1].x  # the documented last-bit difference
    assert abs(on[-1].x - new[-1].x) <= np.spacing(new[-1].x)
    again = DiffOdometry(_DIFF, ticks_per_rev=1000)
    _diff_job(again, first, None)
    again.reset(pose=again.pose)
    assert _diff_job(again, leg, None) == new
    # The omnidirectional odometry alike: reset() changes nothing.
    omni = OmniOdometry(_OMNI)
    step = _OMNI.inverse([1.0, 0.0, 0.0]) * 3e-4
    for yaw in (0.0, 0.1):
        omni.update(step, yaw)
    twin = OmniOdometry(_OMNI)
    for yaw in (0.0, 0.1):
        twin.update(step, yaw)
    omni.reset()
    assert [omni.update(step, 0.2) for _ in range(3)] == [twin.update(step, 0.2) for _ in range(3)]


@settings(max_examples=60, deadline=None)
@given(
    first=st.lists(st.floats(0.0, 360.0), max_size=8),
    second=st.lists(st.floats(0.0, 360.0), max_size=8),
    unwrap=st.booleans(),
)
def test_a_reset_compass_calibration_is_a_new_one(
    first: list[float], second: list[float], unwrap: bool
) -> None:
    reused = CompassCalibration(unwrap=unwrap)
    for reading in first:
        reused(reading)
    reused.reset()
    fresh = CompassCalibration(unwrap=unwrap)
    assert [reused(r) for r in second] == [fresh(r) for r in second]
    assert reused.initial_deg == fresh.initial_deg


def test_a_filter_can_be_rebuilt_from_the_covariance_it_committed() -> None:
    # A reading 1e20 times more precise than the estimate: the kernels' LDLᵀ takes
    # the posterior P as positive definite (second pivot about 1e-17 of its scale)
    # and commits it, while LAPACK's Cholesky of the same P finds a pivot <= 0.
    h = np.array([[-1.206849486366775, 0.13135791792025192]])
    ekf = ExtendedKalmanFilter(np.zeros(2), np.array([[1.0, 0.9], [0.9, 1.0]]))
    ekf.update(np.array([0.5]), partial(np.matmul, h), partial(_constant, h), np.array([[1e-20]]))
    rebuilt = ExtendedKalmanFilter(ekf.x.copy(), ekf.P.copy())  # refused before 54bec22
    ops = [("predict", 1, 5, 0), ("update", 1, 6, 1), ("update", 2, 7, 0)]
    assert _ekf_job(ekf, ops) == _ekf_job(rebuilt, ops)
