"""Metamorphic relations of the estimators: odometry, PlanarFusion, the EKF and the compass.

Relations between runs that the models guarantee: a log in chunks equals the whole
log, a mirrored or rotated world gives the mirrored or rotated estimate, a shifted
origin shifts the estimate and leaves the covariance alone, lengths scaled by k
scale the estimate. Where the arithmetic is the same operation for operation the
results are compared bit for bit; elsewhere with 1e-9 (inputs O(10), a few hundred
float64 operations: rounding stays below 1e-12) or 1e-7 where a rotation of the
world changes the rounding of every step of a filter (errors then grow through
the covariance updates but stay far below 1e-7 over 25 steps).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.errors import FilterError
from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    FusionStatus,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
    UpdateResult,
    compass_to_yaw,
)
from navkit.geometry import Pose2D, angle_diff
from navkit.kinematics import DiffDrive, OmniDrive

FAST = settings(max_examples=40, deadline=None)
# A fusion run per example (tens of ms): fewer by default, FAST's count under -m slow.
FUSION = settings(FAST, max_examples=15)
METHODS = ("arc", "midpoint", "first_order")


def assert_same_angles(a: Any, b: Any, tol: float = 1e-9) -> None:
    assert np.all(np.abs(angle_diff(a, b)) <= tol), (a, b)


# ----------------------------------------------------------------------------- odometry


@st.composite
def encoder_logs(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    ticks = st.integers(-300, 300)
    steps = draw(st.lists(st.tuples(ticks, ticks), min_size=1, max_size=20))
    left = np.cumsum([0] + [s[0] for s in steps])
    right = np.cumsum([0] + [s[1] for s in steps])
    return left, right


lengths = st.floats(0.05, 2.0)
start = st.tuples(st.floats(-10, 10), st.floats(-10, 10), st.floats(-4, 4))


@FAST
@given(lengths, lengths, lengths, st.sampled_from(METHODS), encoder_logs(), start, st.data())
def test_diff_odometry_chunks_online_mirror_and_rigid_motion(
    track: float, rl: float, rr: float, method: Any, log: Any, pose: Any, data: st.DataObject
) -> None:
    left, right = log
    drive = DiffDrive(track=track, left_radius=rl, right_radius=rr)

    def odometry(d: DiffDrive = drive, p: Any = pose, **kw: Any) -> DiffOdometry:
        return DiffOdometry(d, ticks_per_rev=1000, method=method, pose=p, **kw)

    whole = odometry().update_batch(left, right)
    # One reading at a time, and the log in two chunks (a cumulative sum restarted:
    # rounding only).
    online_odo = odometry()
    online = np.array(
        [online_odo.update(int(a), int(b)).as_array() for a, b in zip(left, right, strict=True)]
    )
    cut = data.draw(st.integers(1, len(left)))
    chunked_odo = odometry()
    chunks = [chunked_odo.update_batch(left[:cut], right[:cut])]
    if cut < len(left):
        chunks.append(chunked_odo.update_batch(left[cut:], right[cut:]))
    for other in (online, np.vstack(chunks)):
        np.testing.assert_allclose(other[:, :2], whole[:, :2], rtol=1e-9, atol=1e-9)
        assert_same_angles(other[:, 2], whole[:, 2])
    # The mirror image: wheels (with their radii and readings) swap sides.
    mirror = DiffDrive(track=track, left_radius=rr, right_radius=rl)
    flipped = odometry(mirror, (pose[0], -pose[1], -pose[2])).update_batch(right, left)
    np.testing.assert_allclose(flipped[:, :2] * [1, -1], whole[:, :2], rtol=1e-9, atol=1e-9)
    assert_same_angles(-flipped[:, 2], whole[:, 2])
    # Starting elsewhere is composing with the start pose.
    from_origin = odometry(p=None).update_batch(left, right)
    moved = np.array([Pose2D(*pose).compose(row).as_array() for row in from_origin])
    np.testing.assert_allclose(moved[:, :2], whole[:, :2], rtol=1e-9, atol=1e-9)
    assert_same_angles(moved[:, 2], whole[:, 2])
    # A counter that starts anywhere (and wraps) gives the same tick differences: bit for bit.
    offset = data.draw(st.integers(0, 65535))
    wrapped = odometry(bits=16).update_batch(
        (left + offset) % 65536, (right + offset) % 65536
    )
    np.testing.assert_array_equal(wrapped, whole)


@FAST
@given(
    st.lists(st.tuples(*[st.floats(-5, 5)] * 3, st.floats(-4, 4)), min_size=1, max_size=15),
    start,
    st.floats(-3.2, 3.2),
    st.data(),
)
def test_omni_odometry_chunks_rotation_and_mirror(
    rows: list[tuple[float, ...]], pose: Any, phi: float, data: st.DataObject
) -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    inc = np.array([r[:3] for r in rows])
    yaws = np.array([r[3] for r in rows])
    whole = OmniOdometry(drive, pose=pose).update_batch(inc, yaws)
    cut = data.draw(st.integers(0, len(rows)))
    odo = OmniOdometry(drive, pose=pose)
    first = odo.update_batch(inc[:cut], yaws[:cut])
    chunks = np.vstack([first, odo.update_batch(inc[cut:], yaws[cut:])[1:]])
    np.testing.assert_allclose(chunks, whole, rtol=1e-9, atol=1e-9)
    # The world turned by phi about the origin: compass yaws and the start turn with it.
    c, s = math.cos(phi), math.sin(phi)
    turned_start = (c * pose[0] - s * pose[1], s * pose[0] + c * pose[1], pose[2] + phi)
    turned = OmniOdometry(drive, pose=turned_start).update_batch(inc, yaws + phi)
    np.testing.assert_allclose(turned[:, :2], whole[:, :2] @ np.array([[c, s], [-s, c]]), atol=1e-9)
    assert_same_angles(turned[:, 2], whole[:, 2] + phi)
    # Mirror: wheel angles negated, wheels turning backwards, yaws negated.
    mirror = OmniDrive(-drive.wheel_angles, wheel_radius=0.05, base_radius=0.2)
    flipped = OmniOdometry(mirror, pose=(pose[0], -pose[1], -pose[2])).update_batch(-inc, -yaws)
    np.testing.assert_allclose(flipped[:, :2] * [1, -1], whole[:, :2], atol=1e-9)


# ------------------------------------------------------------------------- PlanarFusion

OBSERVED: list[tuple[int, ...]] = [
    (1, 0, 0, 0), (0, 1, 1, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1), (1, 0, 1, 1)
]


@st.composite
def measurement_logs(
    draw: st.DrawFn, *, kinds: Sequence[tuple[int, ...]] = OBSERVED
) -> MeasurementLog:
    n = draw(st.integers(1, 25))
    # Time steps that are multiples of 1/16 s: sums and shifts by integers stay exact.
    dts = draw(st.lists(st.sampled_from([0.0, 0.0625, 0.25, 0.5, 1.0]), min_size=n, max_size=n))
    rows = st.tuples(st.floats(-4, 4), st.floats(-3, 3), st.floats(-2, 2), st.floats(-2, 2))
    values = draw(st.lists(rows, min_size=n, max_size=n))
    variances = draw(st.lists(st.tuples(*[st.floats(1e-4, 1.0)] * 4), min_size=n, max_size=n))
    observed = draw(st.lists(st.sampled_from(kinds), min_size=n, max_size=n))
    return MeasurementLog(
        np.cumsum(dts), np.array(values), np.array(variances), np.array(observed, dtype=bool)
    )


states = st.tuples(
    st.floats(-5, 5),
    st.floats(-5, 5),
    st.floats(-3, 3),
    st.floats(-2, 2),
    st.floats(-1, 1),
    st.floats(-1, 1),
)


def with_values(log: MeasurementLog, values: Any, variances: Any = None) -> MeasurementLog:
    var = log.variances if variances is None else variances
    return MeasurementLog(log.times, values, var, log.observed)


@FUSION
@given(measurement_logs(), states, st.floats(-100, 100), st.floats(-100, 100))
def test_fusion_shifted_origin_shifts_the_estimate_only(
    log: MeasurementLog, x0: Any, cx: float, cy: float
) -> None:
    base = PlanarFusion(x0, t0=0.0).update_batch(log)
    shifted_start = (x0[0] + cx, x0[1] + cy, *x0[2:])
    shifted = PlanarFusion(shifted_start, t0=0.0).update_batch(log)
    # Nothing but the position depends on the position: the rest is bit for bit equal.
    np.testing.assert_array_equal(shifted.covariances, base.covariances)
    np.testing.assert_array_equal(shifted.states[:, 2:], base.states[:, 2:])
    np.testing.assert_array_equal(shifted.nis, base.nis)
    np.testing.assert_allclose(shifted.states[:, :2] - [cx, cy], base.states[:, :2], atol=1e-9)


test_fusion_shifted_origin_shifts_the_estimate_only_thoroughly = slow_twin(
    test_fusion_shifted_origin_shifts_the_estimate_only, max_examples=40
)


@FUSION
@given(measurement_logs(), states, st.floats(-math.pi, math.pi))
def test_fusion_rotated_world_rotates_estimate_and_covariance(
    log: MeasurementLog, x0: Any, phi: float
) -> None:
    # The default P0 and process noise are isotropic in x, y: rotation invariant.
    base = PlanarFusion(x0, t0=0.0).update_batch(log)
    c, s = math.cos(phi), math.sin(phi)
    rot = np.array([[c, -s], [s, c]])
    turned_start = (*(rot @ x0[:2]), x0[2] + phi, *x0[3:])
    values = log.values.copy()
    values[:, 0] += phi  # absolute yaw readings turn with the world
    turned = PlanarFusion(turned_start, t0=0.0).update_batch(with_values(log, values))
    np.testing.assert_array_equal(turned.status, base.status)
    np.testing.assert_allclose(turned.states[:, :2], base.states[:, :2] @ rot.T, atol=1e-7)
    assert_same_angles(turned.states[:, 2], base.states[:, 2] + phi, 1e-7)
    np.testing.assert_allclose(turned.states[:, 3:], base.states[:, 3:], atol=1e-7)
    jac = np.eye(6)
    jac[:2, :2] = rot
    np.testing.assert_allclose(turned.covariances, jac @ base.covariances @ jac.T, atol=1e-7)


test_fusion_rotated_world_rotates_estimate_and_covariance_thoroughly = slow_twin(
    test_fusion_rotated_world_rotates_estimate_and_covariance, max_examples=40
)


@FUSION
@given(measurement_logs(), states)
def test_fusion_mirrored_world(log: MeasurementLog, x0: Any) -> None:
    base = PlanarFusion(x0, t0=0.0).update_batch(log)
    flip = np.array([1.0, -1.0, -1.0, 1.0, -1.0, 1.0])  # y, θ and ω change sign
    values = log.values * np.array([-1.0, 1.0, -1.0, 1.0])
    mirrored = PlanarFusion(np.array(x0) * flip, t0=0.0).update_batch(with_values(log, values))
    np.testing.assert_array_equal(mirrored.status, base.status)
    back = mirrored.states * flip
    np.testing.assert_allclose(back[:, [0, 1, 3, 4, 5]], base.states[:, [0, 1, 3, 4, 5]], atol=1e-9)
    assert_same_angles(back[:, 2], base.states[:, 2])
    expected = flip[:, None] * base.covariances * flip
    np.testing.assert_allclose(mirrored.covariances, expected, atol=1e-9)


test_fusion_mirrored_world_thoroughly = slow_twin(test_fusion_mirrored_world, max_examples=40)


@FUSION
@given(measurement_logs(), states, st.sampled_from([0.25, 4.0, 16.0]))
def test_fusion_is_scale_free_in_lengths(log: MeasurementLog, x0: Any, k: float) -> None:
    base = PlanarFusion(x0, t0=0.0).update_batch(log)
    lengths = np.array([k, k, 1.0, k, 1.0, k])  # x, y, v, a are lengths (per time)
    comps = np.array([1.0, k, 1.0, k])  # measured yaw, v, ω, a
    p0 = np.array([1e-9, 1e-9, 1e-9, 1.0, 1.0, 1.0]) * lengths**2
    q = np.array([0.05, 0.05, 0.06, 0.025, 0.02, 0.01]) * lengths**2
    scaled = PlanarFusion(np.array(x0) * lengths, p0, process_noise=q, t0=0.0).update_batch(
        with_values(log, log.values * comps, log.variances * comps**2)
    )
    np.testing.assert_array_equal(scaled.status, base.status)
    np.testing.assert_allclose(scaled.states / lengths, base.states, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(
        scaled.covariances / np.outer(lengths, lengths), base.covariances, rtol=1e-9, atol=1e-9
    )
    np.testing.assert_allclose(scaled.nis, base.nis, rtol=1e-9, atol=1e-12)


test_fusion_is_scale_free_in_lengths_thoroughly = slow_twin(
    test_fusion_is_scale_free_in_lengths, max_examples=40
)


@FUSION
@given(measurement_logs(), states, st.integers(-1000, 1000), st.data())
def test_fusion_time_shift_chunks_and_copies_are_exact(
    log: MeasurementLog, x0: Any, shift: int, data: st.DataObject
) -> None:
    base = PlanarFusion(x0, t0=0.0).update_batch(log)
    # Only time differences enter the model (and these shifts keep them exact).
    later = PlanarFusion(x0, t0=float(shift)).update_batch(
        MeasurementLog(log.times + shift, log.values, log.variances, log.observed)
    )
    np.testing.assert_array_equal(later.states, base.states)
    np.testing.assert_array_equal(later.covariances, base.covariances)
    # The log in two batches, with a copy of the filter taken in between.
    cut = data.draw(st.integers(0, len(log)))
    fusion = PlanarFusion(x0, t0=0.0)

    def part(sl: slice) -> MeasurementLog:
        return MeasurementLog(log.times[sl], log.values[sl], log.variances[sl], log.observed[sl])

    first = fusion.update_batch(part(slice(0, cut)))
    second = copy.deepcopy(fusion).update_batch(part(slice(cut, None)))
    np.testing.assert_array_equal(np.vstack([first.states, second.states]), base.states)
    covariances = np.concatenate([first.covariances, second.covariances])
    np.testing.assert_array_equal(covariances, base.covariances)


test_fusion_time_shift_chunks_and_copies_are_exact_thoroughly = slow_twin(
    test_fusion_time_shift_chunks_and_copies_are_exact, max_examples=40
)


@FUSION
@given(
    measurement_logs(kinds=[(1, 0, 0, 0), (0, 1, 1, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)]),
    states,
    st.sampled_from([None, 0.9, 0.999]),
)
def test_fusion_batch_equals_online_updates(log: MeasurementLog, x0: Any, gate: Any) -> None:
    # Rows of one online kind each: update_batch promises the same numbers.
    batch = PlanarFusion(x0, t0=0.0, gate_probability=gate).update_batch(log)
    fusion = PlanarFusion(x0, t0=0.0, gate_probability=gate)
    methods = [
        fusion.update_yaw, fusion.update_speed, fusion.update_yaw_rate, fusion.update_acceleration
    ]
    rows = zip(log.times, log.values, log.variances, log.observed, strict=True)
    for i, (t, z, var, seen) in enumerate(rows):
        if seen[1] and seen[2]:
            result = fusion.update_odometry(
                float(t),
                float(z[1]),
                float(z[2]),
                v_variance=float(var[1]),
                omega_variance=float(var[2]),
            )
        else:
            k = int(np.argmax(seen))
            result = methods[k](float(t), float(z[k]), variance=float(var[k]))
        assert result.accepted == bool(batch.accepted[i])
        np.testing.assert_array_equal(fusion.x, batch.states[i])
        np.testing.assert_array_equal(fusion.P, batch.covariances[i])


test_fusion_batch_equals_online_updates_thoroughly = slow_twin(
    test_fusion_batch_equals_online_updates, max_examples=40
)


@FAST
@given(
    states,
    st.floats(-1.5, 1.5),
    st.floats(-2, 2),
    st.floats(-2, 2),
    st.tuples(*[st.floats(1e-4, 1.0)] * 3),
    st.floats(0.0, 1.0),
    st.permutations([0, 1, 2]),
)
def test_fusion_readings_at_one_time_in_any_order_equal_one_joint_update(
    x0: Any, offset: float, omega: float, acc: float, var: Any, t: float, order: list[int]
) -> None:
    # A yaw within ±1.5 rad of the initial heading keeps the residual well within ±π,
    # where the docstring promises the equality (a reading nearly opposite to the
    # estimate is ambiguous and the order of the calls can matter).
    yaw = x0[2] + offset
    fusion = PlanarFusion(x0, t0=0.0)
    calls: list[Callable[[], UpdateResult]] = [
        lambda: fusion.update_yaw(t, yaw, variance=var[0]),
        lambda: fusion.update_yaw_rate(t, omega, variance=var[1]),
        lambda: fusion.update_acceleration(t, acc, variance=var[2]),
    ]
    for i in order:
        assert calls[i]().accepted
    joint = PlanarFusion(x0, t0=0.0).update_batch(
        MeasurementLog(
            np.array([t]),
            np.array([[yaw, 0.0, omega, acc]]),
            np.array([[var[0], 1.0, var[1], var[2]]]),
            np.array([[True, False, True, True]]),
        )
    )
    rest = [0, 1, 3, 4, 5]
    np.testing.assert_allclose(fusion.x[rest], joint.states[0][rest], atol=1e-9)
    assert_same_angles(fusion.x[2], joint.states[0][2])
    np.testing.assert_allclose(fusion.P, joint.covariances[0], atol=1e-9)


# --------------------------------------------------------------------------------- EKF


@st.composite
def linear_problems(draw: st.DrawFn) -> tuple[Any, ...]:
    n = draw(st.integers(2, 4))
    m = draw(st.integers(1, n))

    def matrix(rows: int, cols: int, bound: float) -> np.ndarray:
        flat = draw(st.lists(st.floats(-bound, bound), min_size=rows * cols, max_size=rows * cols))
        return np.array(flat).reshape(rows, cols)

    a = matrix(n, n, 1.0)
    p0 = a @ a.T + draw(st.floats(0.05, 2.0)) * np.eye(n)
    b = matrix(n, n, 1.0)
    q = 0.1 * (b @ b.T) + 0.01 * np.eye(n)
    x0 = matrix(1, n, 5.0)[0]
    h = matrix(m, n, 2.0)
    z = matrix(1, m, 5.0)[0]
    r = np.array(draw(st.lists(st.floats(0.01, 2.0), min_size=m, max_size=m)))
    f = np.eye(n) + matrix(n, n, 0.5)
    return x0, p0, f, q, h, z, r


def _linear(matrix: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    return lambda x: matrix @ x


@FAST
@given(linear_problems(), st.randoms(use_true_random=False))
def test_ekf_sequential_scalar_updates_equal_one_joint_update(problem: Any, rnd: Any) -> None:
    x0, p0, f, q, h, z, r = problem
    joint = ExtendedKalmanFilter(x0, p0)
    joint.predict(lambda x: f @ x, f, q)
    joint.update(z, lambda x: h @ x, h, np.diag(r))
    seq = ExtendedKalmanFilter(x0, p0)
    seq.predict(lambda x: f @ x, f, q)
    for i in rnd.sample(range(len(z)), len(z)):
        row = h[i : i + 1]
        seq.update(z[i : i + 1], _linear(row), row, [[r[i]]])
    np.testing.assert_allclose(seq.x, joint.x, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(seq.P, joint.P, rtol=1e-7, atol=1e-7)


@FAST
@given(linear_problems(), st.floats(-100, 100), st.floats(0.1, 20), st.floats(0.1, 20))
def test_ekf_translation_and_gate_monotonicity(
    problem: Any, c: float, g1: float, g2: float
) -> None:
    x0, p0, f, q, h, z, r = problem
    d = np.full(x0.shape, c)
    base = ExtendedKalmanFilter(x0, p0)
    base.predict(lambda x: f @ x, f, q)
    result = base.update(z, lambda x: h @ x, h, np.diag(r))
    # The same linear model about a shifted origin: the covariance never sees the state.
    moved = ExtendedKalmanFilter(x0 + d, p0)
    moved.predict(lambda x: f @ (x - d) + d, f, q)
    moved_result = moved.update(z + h @ d, lambda x: h @ x, h, np.diag(r))
    np.testing.assert_allclose(moved.x - d, base.x, rtol=1e-7, atol=1e-7)
    np.testing.assert_array_equal(moved.P, base.P)
    assert math.isclose(moved_result.nis, result.nis, rel_tol=1e-6, abs_tol=1e-9)
    # A measurement accepted by a gate is accepted by every wider one; the NIS is the same.
    low, high = sorted((g1, g2))
    verdicts = []
    for gate in (low, high):
        ekf = ExtendedKalmanFilter(x0, p0)
        verdicts.append(ekf.update(z, lambda x: h @ x, h, np.diag(r), gate=gate))
    first = ExtendedKalmanFilter(x0, p0).update(z, lambda x: h @ x, h, np.diag(r))
    assert verdicts[0].nis == verdicts[1].nis == first.nis
    assert verdicts[1].accepted or not verdicts[0].accepted


# ------------------------------------------------------------------------------ compass

readings = st.one_of(st.floats(-1000, 1000), st.sampled_from([0.0, 180.0, -180.0, 360.0, 540.0]))


@FAST
@given(st.lists(readings, min_size=1, max_size=30), st.data())
def test_compass_log_in_pieces_equals_the_whole_log(log: list[float], data: st.DataObject) -> None:
    whole = compass_to_yaw(log, initial_deg=log[0], unwrap=True)
    wrapped = compass_to_yaw(log, initial_deg=log[0])
    # numpy.unwrap's rule, whole turns counted as integers (review 53): its running sum
    # of rounded corrections is an ulp or two off from the first turn on.
    turns = np.rint((whole - wrapped) / (2 * np.pi))
    np.testing.assert_array_equal(whole, wrapped + turns * (2 * np.pi))
    np.testing.assert_allclose(whole, np.unwrap(wrapped), rtol=0, atol=1e-12)
    cuts = sorted(data.draw(st.lists(st.integers(0, len(log)), max_size=5)))
    cal = CompassCalibration(unwrap=True)
    pieces = []
    for lo, hi in zip([0, *cuts], [*cuts, len(log)], strict=True):
        pieces.append(np.atleast_1d(cal(log[lo:hi])))
    np.testing.assert_array_equal(np.concatenate(pieces), whole)


@FAST
@given(
    st.lists(readings, min_size=1, max_size=30), readings, st.integers(-3, 3), st.floats(-360, 360)
)
def test_compass_yaw_is_relative_and_mirrors(
    log: list[float], initial: float, turns: int, c: float
) -> None:
    raw = np.array(log)
    yaw = compass_to_yaw(raw, initial_deg=initial)
    # Whole turns and a common rotation of readings and reference change nothing;
    # a mirrored compass (readings negated) gives the negated yaw. Rounding of
    # degrees ~1e3 converted to radians: ~1e-13.
    assert_same_angles(compass_to_yaw(raw + 360.0 * turns, initial_deg=initial), yaw)
    assert_same_angles(compass_to_yaw(raw + c, initial_deg=initial + c), yaw)
    assert_same_angles(-compass_to_yaw(-raw, initial_deg=-initial), yaw)


@FUSION
@given(measurement_logs(), st.sampled_from([1e300, 1e160, 1.7e308]), st.data())
def test_fusion_corrupt_timestamp_changes_nothing_else(
    log: MeasurementLog, bad_time: float, data: st.DataObject
) -> None:
    # A row whose prediction overflows is skipped (TIME_GAP): the other rows are those
    # of the log without it, bit for bit; online it raises and changes nothing.
    k = data.draw(st.integers(0, len(log)))

    def insert(arr: np.ndarray, row: Any) -> np.ndarray:
        return np.insert(arr, k, row, axis=0)

    corrupt = MeasurementLog(
        insert(log.times, bad_time),
        insert(log.values, [1.0, 1.0, 1.0, 1.0]),
        insert(log.variances, [1.0, 1.0, 1.0, 1.0]),
        insert(log.observed, [True, True, True, True]),
    )
    clean = PlanarFusion(t0=0.0).update_batch(log)
    skipped = PlanarFusion(t0=0.0).update_batch(corrupt)
    assert skipped.status[k] == FusionStatus.TIME_GAP
    others = np.arange(len(corrupt)) != k
    np.testing.assert_array_equal(skipped.states[others], clean.states)
    np.testing.assert_array_equal(skipped.covariances[others], clean.covariances)
    fusion = PlanarFusion(t0=0.0)
    head = slice(0, k)
    fusion.update_batch(
        MeasurementLog(log.times[head], log.values[head], log.variances[head], log.observed[head])
    )
    before = (fusion.x, fusion.P, fusion.t)
    with pytest.raises(FilterError):
        fusion.update_yaw(bad_time, 1.0, variance=1.0)
    with pytest.raises(FilterError):
        fusion.predict(bad_time)
    np.testing.assert_array_equal(fusion.x, before[0])
    np.testing.assert_array_equal(fusion.P, before[1])
    assert fusion.t == before[2]


test_fusion_corrupt_timestamp_changes_nothing_else_thoroughly = slow_twin(
    test_fusion_corrupt_timestamp_changes_nothing_else, max_examples=40
)


@FAST
@given(
    st.integers(2, 5), st.integers(1, 4), st.randoms(use_true_random=False), st.integers(0, 2**32)
)
def test_ekf_relabelling_state_and_measurement_components(
    n: int, m: int, rnd: Any, seed: int
) -> None:
    # The order of the components is a labelling: permuting the state (with P, F, Q, H
    # and angle_states) and the measurement (with R and angle_measurements) permutes
    # the result. Only the summation order of the products changes: rounding.
    m = min(m, n)
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    p0 = a @ a.T + np.eye(n)
    x0 = 3.0 * rng.normal(size=n)
    f = np.eye(n) + 0.3 * rng.normal(size=(n, n))
    b = rng.normal(size=(n, n))
    q = 0.1 * b @ b.T
    h = rng.normal(size=(m, n))
    z = 3.0 * rng.normal(size=m)
    r = np.diag(rng.uniform(0.1, 1.0, m))
    angle_state, angle_meas = rnd.randrange(n), rnd.randrange(m)
    h[angle_meas] = 0.0
    h[angle_meas, angle_state] = 1.0  # a heading measured directly
    z[angle_meas] = rng.uniform(-10.0, 10.0)
    perm = np.array(rnd.sample(range(n), n))
    mperm = np.array(rnd.sample(range(m), m))
    inv, minv = np.argsort(perm), np.argsort(mperm)

    base = ExtendedKalmanFilter(x0, p0, angle_states=[angle_state])
    base.predict(_linear(f), f, q)
    result = base.update(z, _linear(h), h, r, angle_measurements=(angle_meas,))

    fp, hp = f[np.ix_(perm, perm)], h[np.ix_(mperm, perm)]
    relabelled = ExtendedKalmanFilter(
        x0[perm], p0[np.ix_(perm, perm)], angle_states=[int(inv[angle_state])]
    )
    relabelled.predict(_linear(fp), fp, q[np.ix_(perm, perm)])
    other = relabelled.update(
        z[mperm], _linear(hp), hp, r[np.ix_(mperm, mperm)],
        angle_measurements=(int(minv[angle_meas]),),
    )
    assert other.accepted == result.accepted
    assert math.isclose(other.nis, result.nis, rel_tol=1e-8, abs_tol=1e-9)
    x = relabelled.x[inv]
    linear = np.arange(n) != angle_state
    np.testing.assert_allclose(x[linear], base.x[linear], rtol=1e-7, atol=1e-7)
    assert_same_angles(x[angle_state], base.x[angle_state], 1e-7)
    np.testing.assert_allclose(relabelled.P[np.ix_(inv, inv)], base.P, rtol=1e-7, atol=1e-7)
