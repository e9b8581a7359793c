"""General EKF: equivalence with filterpy, Joseph form, angles, gating and bad input."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter, PlanarFusion
from navkit.geometry import wrap_angle

FloatArray = NDArray[np.float64]

Q_PER_S = np.diag([0.05, 0.05, 0.06, 0.025, 0.02, 0.01])
H_ODOM = np.zeros((2, 6))
H_ODOM[0, 3] = H_ODOM[1, 4] = 1.0
H_YAW = np.zeros((1, 6))
H_YAW[0, 2] = 1.0


def planar_model(
    dt: float,
) -> tuple[Callable[[FloatArray], FloatArray], Callable[[FloatArray], FloatArray]]:
    """Constant-acceleration unicycle with mid-step heading, written independently in numpy."""

    def f(x: FloatArray) -> FloatArray:
        s = x[3] * dt + 0.5 * x[5] * dt * dt
        mid = x[2] + 0.5 * x[4] * dt
        return np.array(
            [
                x[0] + s * math.cos(mid),
                x[1] + s * math.sin(mid),
                x[2] + x[4] * dt,
                x[3] + x[5] * dt,
                x[4],
                x[5],
            ]
        )

    def jac(x: FloatArray) -> FloatArray:
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


def measurement_sequence(n: int, seed: int) -> list[tuple[float, str, FloatArray]]:
    """(dt, kind, z) triples of a robot turning through ±π several times."""
    rng = np.random.default_rng(seed)
    seq = []
    yaw, v, w = 3.0, 0.5, 0.8
    for i in range(n):
        dt = float(rng.uniform(0.01, 0.05))
        w = float(np.clip(w + rng.normal(0, 0.05), -1.5, 1.5))
        v = float(np.clip(v + rng.normal(0, 0.05), -1.0, 1.5))
        yaw = float(wrap_angle(yaw + w * dt))
        if i % 3 == 2:
            seq.append((dt, "yaw", np.array([wrap_angle(yaw + rng.normal(0, 0.05))])))
        else:
            seq.append((dt, "odom", np.array([v + rng.normal(0, 0.02), w + rng.normal(0, 0.02)])))
    return seq


R_ODOM_FULL = np.array([[4e-4, 1e-4], [1e-4, 9e-4]])
R_ODOM_DIAG = np.diag([4e-4, 9e-4])
R_YAW = np.array([[2.5e-3]])
X0 = np.array([0.0, 0.0, 3.0, 0.0, 0.0, 0.0])
P0 = np.diag([1e-6, 1e-6, 1e-4, 1.0, 1.0, 1.0])


def _filterpy_reference(x0: FloatArray, p0: FloatArray) -> Any:
    """filterpy's ExtendedKalmanFilter (Joseph-form update) with a nonlinear predict."""
    from filterpy.kalman import ExtendedKalmanFilter as FilterpyEKF

    class Reference(FilterpyEKF):  # type: ignore[misc]
        model: Callable[[FloatArray], FloatArray]

        def predict_x(self, u: object = 0) -> None:
            self.x = self.model(self.x)

    ref = Reference(dim_x=x0.shape[0], dim_z=1)
    ref.x = x0.copy()
    ref.P = p0.copy()
    return ref


def _relative_gaps(
    ekf: ExtendedKalmanFilter, ref_x: FloatArray, ref_p: FloatArray, angles: tuple[int, ...]
) -> tuple[float, float]:
    """State gap relative to max(|x|, 1); covariance gap relative to sqrt(P_ii P_jj)."""
    dx = ekf.x - ref_x
    for i in angles:
        dx[i] = wrap_angle(float(dx[i]))
    gap_x = float(np.max(np.abs(dx) / np.maximum(np.abs(ref_x), 1.0)))
    scale = np.sqrt(np.diag(ref_p))
    gap_p = float(np.max(np.abs(ekf.P - ref_p) / np.outer(scale, scale)))
    return gap_x, gap_p


def test_matches_filterpy_1000_steps() -> None:
    """Same model and measurements as filterpy's ExtendedKalmanFilter: equal to 1e-12 relative."""
    ref = _filterpy_reference(X0, P0)
    ekf = ExtendedKalmanFilter(X0, P0, angle_states=(2,))

    def yaw_residual(a: FloatArray, b: FloatArray) -> FloatArray:
        return np.array([wrap_angle(float(a[0] - b[0]))])

    worst_x = worst_p = 0.0
    for dt, kind, z in measurement_sequence(1000, seed=1):
        f, jac = planar_model(dt)
        q = Q_PER_S * dt
        ref.model = f
        ref.F = jac(ref.x)
        ref.Q = q
        ref.predict()
        ref.x[2] = wrap_angle(float(ref.x[2]))
        ekf.predict(f, jac, q)
        if kind == "odom":
            ref.update(z, lambda x: H_ODOM, lambda x: H_ODOM @ x, R=R_ODOM_FULL)
            ekf.update(z, lambda x: H_ODOM @ x, H_ODOM, R_ODOM_FULL)
        else:
            ref.update(z, lambda x: H_YAW, lambda x: H_YAW @ x, R=R_YAW, residual=yaw_residual)
            ekf.update(z, lambda x: H_YAW @ x, lambda x: H_YAW, R_YAW, angle_measurements=(0,))
        ref.x[2] = wrap_angle(float(ref.x[2]))
        gap_x, gap_p = _relative_gaps(ekf, ref.x, ref.P, (2,))
        worst_x = max(worst_x, gap_x)
        worst_p = max(worst_p, gap_p)
    assert worst_x < 1e-12
    assert worst_p < 1e-12
    # The run really exercised the filter: the state moved far from x0.
    assert np.hypot(*ekf.x[:2]) > 1.0


def test_matches_filterpy_dense_model() -> None:
    """A dense nonlinear 5-state model with 3-D measurements: equal to filterpy to 1e-12.

    Measurements come from a simulated true trajectory: with measurements unrelated
    to the model, an EKF's rounding differences grow chaotically (filterpy against
    itself with another operation order then differs by 0.1).
    """
    rng = np.random.default_rng(11)
    n, m = 5, 3
    a = 0.3 * rng.normal(size=(n, n))
    b = rng.normal(size=(m, n))
    root = rng.normal(size=(n, n))
    q = 0.01 * (root @ root.T) + 1e-3 * np.eye(n)
    root = rng.normal(size=(m, m))
    r = 0.05 * (root @ root.T) + 0.01 * np.eye(m)

    def f(x: FloatArray) -> FloatArray:
        return np.asarray(0.9 * x + 0.3 * np.tanh(a @ x), dtype=np.float64)

    def jac(x: FloatArray) -> FloatArray:
        return 0.9 * np.eye(n) + 0.3 * (1.0 - np.tanh(a @ x) ** 2)[:, None] * a

    def h(x: FloatArray) -> FloatArray:
        return np.asarray(b @ x + 0.1 * np.sin(b @ x), dtype=np.float64)

    def hjac(x: FloatArray) -> FloatArray:
        return (1.0 + 0.1 * np.cos(b @ x))[:, None] * b

    x0 = rng.normal(size=n)
    truth = x0 + 0.5 * rng.normal(size=n)
    ref = _filterpy_reference(x0, np.eye(n))
    ref.model = f
    ref.Q = q
    ekf = ExtendedKalmanFilter(x0, np.eye(n))
    worst_x = worst_p = 0.0
    for _ in range(300):
        truth = f(truth) + 0.1 * rng.normal(size=n)
        z = h(truth) + 0.1 * rng.normal(size=m)
        ref.F = jac(ref.x)
        ref.predict()
        ref.update(z, hjac, h, R=r)
        ekf.predict(f, jac, q)
        assert ekf.update(z, h, hjac, r).accepted
        gap_x, gap_p = _relative_gaps(ekf, ref.x, ref.P, ())
        worst_x = max(worst_x, gap_x)
        worst_p = max(worst_p, gap_p)
    assert worst_x < 1e-12
    assert worst_p < 1e-12
    assert np.max(np.abs(ekf.x - truth)) < 1.0  # it tracked the truth


def test_planar_fusion_kernel_matches_general_ekf() -> None:
    """PlanarFusion's compiled step equals the general EKF on the same model to 1e-9."""
    fusion = PlanarFusion(X0, P0, process_noise=Q_PER_S, t0=0.0)
    ekf = ExtendedKalmanFilter(X0, P0, angle_states=(2,))
    t = 0.0
    for dt, kind, z in measurement_sequence(1000, seed=2):
        t += dt
        f, jac = planar_model(dt)
        ekf.predict(f, jac, Q_PER_S * dt)
        if kind == "odom":
            res = fusion.update_odometry(
                t, z[0], z[1], v_variance=R_ODOM_DIAG[0, 0], omega_variance=R_ODOM_DIAG[1, 1]
            )
            ref = ekf.update(z, lambda x: H_ODOM @ x, H_ODOM, R_ODOM_DIAG)
        else:
            res = fusion.update_yaw(t, z[0], variance=R_YAW[0, 0])
            ref = ekf.update(z, lambda x: H_YAW @ x, H_YAW, R_YAW, angle_measurements=(0,))
        assert res.accepted and ref.accepted
        assert res.nis == pytest.approx(ref.nis, rel=1e-7, abs=1e-9)
        np.testing.assert_allclose(res.residual, ref.residual, atol=1e-9)
    dx = fusion.x - ekf.x
    dx[2] = wrap_angle(float(dx[2]))
    assert np.max(np.abs(dx)) < 1e-9
    assert np.max(np.abs(fusion.P - ekf.P)) < 1e-9


def test_joseph_form_equals_textbook_update_and_is_symmetric() -> None:
    rng = np.random.default_rng(3)  # the sizes of test_matches_filterpy_dense_model's filter
    a = rng.normal(size=(5, 5))
    p0 = a @ a.T + 0.1 * np.eye(5)
    h = rng.normal(size=(3, 5))
    r = np.diag([0.2, 0.3, 0.25])
    ekf = ExtendedKalmanFilter(np.zeros(5), p0)
    z = np.array([0.4, -0.1, 0.2])
    result = ekf.update(z, lambda x: h @ x, h, r)
    s = h @ p0 @ h.T + r
    k = p0 @ h.T @ np.linalg.inv(s)
    np.testing.assert_allclose(ekf.x, k @ z, atol=1e-12)
    np.testing.assert_allclose(ekf.P, (np.eye(5) - k @ h) @ p0, atol=1e-12)
    np.testing.assert_array_equal(ekf.P, ekf.P.T)
    assert result.nis == pytest.approx(float(z @ np.linalg.solve(s, z)))


def test_angle_residual_and_state_wrapping() -> None:
    ekf = ExtendedKalmanFilter([math.pi - 0.05], [[0.03]], angle_states=(0,))
    # A yaw of -π + 0.05 is 0.1 rad counter-clockwise of the state, not 2π - 0.1 clockwise.
    result = ekf.update(
        [-math.pi + 0.05], lambda x: x, np.eye(1), [[0.01]], angle_measurements=(0,)
    )
    assert result.residual[0] == pytest.approx(0.1)
    # K = 0.75: the state moves 0.075 rad across ±π and is wrapped to the negative side.
    assert ekf.x[0] == pytest.approx(-math.pi + 0.025)
    assert -math.pi < ekf.x[0] <= math.pi
    ekf.predict(lambda x: x + 7.0, np.eye(1), [[0.0]])
    assert -math.pi < ekf.x[0] <= math.pi


def test_gate_rejects_outlier_and_keeps_state() -> None:
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2) * 0.01)
    before_x, before_p = ekf.x, ekf.P
    h = np.array([[1.0, 0.0]])
    rejected = ekf.update([5.0], lambda x: h @ x, h, [[0.01]], gate=9.0)
    assert not rejected.accepted and not rejected
    assert rejected.nis == pytest.approx(25.0 / 0.02)
    assert rejected.reason is not None and "gate" in rejected.reason
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)
    accepted = ekf.update([0.1], lambda x: h @ x, h, [[0.01]], gate=9.0)
    assert accepted.accepted and accepted.reason is None
    assert accepted.nis == pytest.approx(0.01 / 0.02)


def _fresh() -> ExtendedKalmanFilter:
    return ExtendedKalmanFilter([1.0, 2.0], [[1.0, 0.1], [0.1, 2.0]], angle_states=(1,))


H2 = np.array([[1.0, 0.0]])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda e: e.predict(lambda x: x, np.eye(3), np.eye(2)), ValueError, "F"),
        (
            lambda e: e.predict(lambda x: x, np.eye(2), -np.eye(2)),
            ValueError,
            "Q must be positive semi",
        ),
        (
            lambda e: e.predict(lambda x: x, np.eye(2), [[1.0, 0.5], [0.0, 1.0]]),
            ValueError,
            "Q must be symmetric",
        ),
        (lambda e: e.predict(lambda x: x[:1], np.eye(2), np.eye(2)), ValueError, "f\\(x\\)"),
        (lambda e: e.predict(lambda x: x * np.nan, np.eye(2), np.eye(2)), ValueError, "f\\(x\\)"),
        (lambda e: e.predict(lambda x: x, np.full((2, 2), np.nan), np.eye(2)), ValueError, "F"),
        (lambda e: e.predict("f", np.eye(2), np.eye(2)), TypeError, "f must be callable"),
        (
            lambda e: e.predict(lambda x: x, np.zeros((2, 2)), np.zeros((2, 2))),
            FilterError,
            "positive definite",
        ),
        (lambda e: e.update([np.nan], lambda x: x[:1], H2, [[1.0]]), ValueError, "z"),
        (lambda e: e.update([1.0], lambda x: x[:1], np.eye(2), [[1.0]]), ValueError, "H"),
        (
            lambda e: e.update([1.0], lambda x: x[:1], H2, [[0.0]]),
            ValueError,
            "R must be positive definite",
        ),
        (
            lambda e: e.update([1.0], lambda x: x[:1], H2, [[-1.0]]),
            ValueError,
            "R must be positive definite",
        ),
        (lambda e: e.update([1.0], lambda x: x, H2, [[1.0]]), ValueError, "h\\(x\\)"),
        (
            lambda e: e.update([1.0], lambda x: x[:1], H2, [[1.0]], angle_measurements=(1,)),
            ValueError,
            "angle_measurements",
        ),
        (lambda e: e.update([1.0], lambda x: x[:1], H2, [[1.0]], gate=-1.0), ValueError, "gate"),
        (lambda e: e.update([[1.0]], lambda x: x[:1], H2, [[1.0]]), ValueError, "z must be 1-D"),
    ],
)
def test_bad_input_raises_and_leaves_state(
    call: Callable[[ExtendedKalmanFilter], object], error: type[Exception], match: str
) -> None:
    ekf = _fresh()
    before_x, before_p = ekf.x, ekf.P
    with pytest.raises(error, match=match):
        call(ekf)
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)


@pytest.mark.parametrize(
    ("x0", "p0", "angles", "match"),
    [
        ([0.0, 0.0], np.eye(3), (), "P0"),
        ([0.0, np.nan], np.eye(2), (), "x0"),
        ([0.0, 0.0], [[1.0, 2.0], [2.0, 1.0]], (), "P0 must be positive definite"),
        ([0.0, 0.0], np.eye(2), (2,), "angle_states"),
        ([0.0, 0.0], np.eye(2), (0, 0), "duplicate"),
        ([], np.zeros((0, 0)), (), "x0"),
    ],
)
def test_bad_construction(x0: object, p0: object, angles: tuple[int, ...], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        ExtendedKalmanFilter(x0, p0, angle_states=angles)  # type: ignore[arg-type]


def test_options_are_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        ExtendedKalmanFilter([0.0, 0.0], np.eye(2), (1,))  # type: ignore[call-arg]
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2), angle_states=(1,))
    assert ekf.angle_states == (1,)
    with pytest.raises(TypeError, match="positional"):
        ekf.update([1.0], lambda x: x[:1], H2, [[1.0]], (0,))  # type: ignore[call-arg]
    np.testing.assert_array_equal(ekf.x, [0.0, 0.0])


def test_update_result_is_an_immutable_container() -> None:
    from navkit.estimation import UpdateResult

    residual = np.array([0.5, -0.25])
    result = UpdateResult(True, 1.5, residual)
    residual[0] = 9.0  # the result holds its own copy
    np.testing.assert_array_equal(result.residual, [0.5, -0.25])
    with pytest.raises(ValueError, match="read-only"):
        result.residual[0] = 1.0
    with pytest.raises(AttributeError):
        result.nis = 2.0  # type: ignore[misc]
    assert result.reason is None and bool(result)
    assert result != UpdateResult(True, 1.5, np.array([0.5, -0.25]))  # compared by identity
    with pytest.raises(ValueError, match="residual"):
        UpdateResult(True, 1.0, np.zeros((2, 2)))
    with pytest.raises(TypeError, match="accepted"):
        UpdateResult(1, 1.0, np.zeros(1))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="nis"):
        UpdateResult(True, -1.0, np.zeros(1))
    with pytest.raises(TypeError, match="reason"):
        UpdateResult(False, 1.0, np.zeros(1), 3)  # type: ignore[arg-type]
    # The filters' results have the same fields and types.
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    out = ekf.update([1.0], lambda x: x[:1], H2, [[1.0]])
    assert type(out) is UpdateResult
    assert isinstance(out.accepted, bool) and isinstance(out.nis, float)
    assert out.residual.shape == (1,) and out.reason is None


def test_inputs_not_modified_and_state_is_a_copy() -> None:
    x0 = np.array([1.0, 2.0])
    p0 = np.eye(2)
    ekf = ExtendedKalmanFilter(x0, p0)
    ekf.update([3.0], lambda x: x[:1], H2, [[1.0]])
    np.testing.assert_array_equal(x0, [1.0, 2.0])
    np.testing.assert_array_equal(p0, np.eye(2))
    ekf.x[0] = 100.0
    assert ekf.x[0] != 100.0


def test_noise_matrix_changed_in_place_is_revalidated() -> None:
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    q = np.eye(2) * 0.1
    ekf.predict(lambda x: x, np.eye(2), q)
    ekf.predict(lambda x: x, np.eye(2), q)  # same values: the cached check is reused
    q[0, 0] = -1.0  # the caller's matrix changes between steps
    before = ekf.P
    with pytest.raises(ValueError, match="Q must be positive semi"):
        ekf.predict(lambda x: x, np.eye(2), q)
    np.testing.assert_array_equal(ekf.P, before)
    r = np.array([[0.5]])
    assert ekf.update([1.0], lambda x: x[:1], H2, r).accepted
    r[0, 0] = 0.0
    with pytest.raises(ValueError, match="R must be positive definite"):
        ekf.update([1.0], lambda x: x[:1], H2, r)
    with pytest.raises(TypeError, match="R"):
        ekf.update([1.0], lambda x: x[:1], H2, [["a"]])


def _run_steps(
    spell: Callable[[FloatArray], object], steps: int = 20
) -> tuple[FloatArray, FloatArray, list[float]]:
    """A few steps of the planar model with every array argument passed through ``spell``."""
    ekf = ExtendedKalmanFilter(spell(X0), spell(P0), angle_states=(2,))  # type: ignore[arg-type]
    nis = []
    for dt, kind, z in measurement_sequence(steps, seed=4):
        f, jac = planar_model(dt)
        ekf.predict(
            lambda x, f=f: spell(f(x)),  # type: ignore[misc]
            spell(jac(ekf.x)),  # type: ignore[arg-type]
            spell(Q_PER_S * dt),  # type: ignore[arg-type]
        )
        if kind == "odom":
            h_mat, r, angles = H_ODOM, R_ODOM_FULL, ()
        else:
            h_mat, r, angles = H_YAW, R_YAW, (0,)
        result = ekf.update(
            spell(z),  # type: ignore[arg-type]
            lambda x, h_mat=h_mat: spell(h_mat @ x),  # type: ignore[misc]
            lambda x, h_mat=h_mat: spell(h_mat),  # type: ignore[misc]
            spell(r),  # type: ignore[arg-type]
            angle_measurements=list(angles),
        )
        nis.append(result.nis)
    return ekf.x, ekf.P, nis


def _read_only(a: FloatArray) -> FloatArray:
    out = np.array(a, copy=True)
    out.flags.writeable = False
    return out


def _strided(a: FloatArray) -> FloatArray:
    wide = np.zeros((*a.shape[:-1], 2 * a.shape[-1]))
    wide[..., ::2] = a
    return wide[..., ::2]


@pytest.mark.parametrize(
    "spell",
    [
        lambda a: np.asarray(a).tolist(),
        _read_only,
        _strided,
        lambda a: np.asfortranarray(a),
        lambda a: np.asarray(a, dtype=np.dtype(">f8")),  # big-endian
        lambda a: np.asarray(a, dtype=object),
    ],
    ids=["list", "read-only", "strided", "fortran", "big-endian", "object"],
)
def test_other_spellings_give_identical_results(spell: Callable[[FloatArray], object]) -> None:
    """Lists and non-standard arrays take the converting path: bit-for-bit the same results."""
    x_ref, p_ref, nis_ref = _run_steps(lambda a: a)
    x, p, nis = _run_steps(spell)
    np.testing.assert_array_equal(x, x_ref)
    np.testing.assert_array_equal(p, p_ref)
    assert nis == nis_ref


def test_overflow_is_not_applied() -> None:
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    before_x, before_p = ekf.x, ekf.P
    # z - h(x) overflows: no residual, NIS inf.
    out = ekf.update([1e308], lambda x: x[:1] - 1e308, H2, [[1.0]])
    assert not out.accepted and out.nis == math.inf and out.residual.shape == (0,)
    assert out.reason is not None and "overflow" in out.reason and "residual" in out.reason
    # A finite residual whose NIS overflows: the residual is reported.
    out = ekf.update([1e300], lambda x: x[:1], H2, [[1e-100]])
    assert not out.accepted and out.nis == math.inf
    assert out.reason is not None and "NIS" in out.reason
    np.testing.assert_array_equal(out.residual, [1e300])
    # H so large that S overflows: FilterError.
    with pytest.raises(FilterError, match="innovation covariance S is not finite"):
        ekf.update([1.0], lambda x: x[:1], np.array([[1e200, 0.0]]), [[1.0]])
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)
    assert ekf.update([0.5], lambda x: x[:1], H2, [[1.0]]).accepted


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda e: e.update([1.0], lambda x: x[:1], np.array([[np.inf, 0.0]]), [[1.0]]), "H"),
        (lambda e: e.update([1.0], lambda x: x[:1] * np.nan, H2, [[1.0]]), "h\\(x\\)"),
        (lambda e: e.update([1.0], lambda x: x[:1], H2, [[np.nan]]), "R"),
        (lambda e: e.predict(lambda x: x, np.eye(2), np.full((2, 2), np.nan)), "Q"),
        (lambda e: e.predict(lambda x: x, lambda x: np.full((2, 2), np.inf), np.eye(2)), "F"),
    ],
)
def test_non_finite_values_are_named(
    call: Callable[[ExtendedKalmanFilter], object], match: str
) -> None:
    """Values checked inside the kernels are reported as ValueErrors naming them."""
    ekf = _fresh()
    ekf.predict(lambda x: x, np.eye(2), np.eye(2))  # the validated Q is cached from now on
    before_x, before_p = ekf.x, ekf.P
    with pytest.raises(ValueError, match=f"^{match} must contain only finite values"):
        call(ekf)
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)


def test_angle_indices_are_checked_against_each_measurement_size() -> None:
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    angles = (1,)
    h2 = np.eye(2)
    assert ekf.update([0.1, 0.2], lambda x: x, h2, np.eye(2), angle_measurements=angles)
    # The same tuple, now out of range for a 1-D measurement: checked again.
    with pytest.raises(ValueError, match="angle_measurements"):
        ekf.update([0.1], lambda x: x[:1], H2, [[1.0]], angle_measurements=angles)
    raw = np.array([3.0, 3.0]) - (ekf.x - 0.5)
    assert raw[1] > math.pi  # the angle component needs wrapping
    out = ekf.update([3.0, 3.0], lambda x: x - 0.5, h2, np.eye(2), angle_measurements=angles)
    assert out.residual[0] == raw[0]  # not an angle: not wrapped
    assert out.residual[1] == pytest.approx(raw[1] - 2 * math.pi)


def test_slightly_asymmetric_noise_is_symmetrised() -> None:
    """Q within the symmetry tolerance is accepted and used symmetrised, P stays symmetric."""
    q = np.array([[0.1, 0.02], [0.02 * (1 + 1e-12), 0.2]])
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    for _ in range(3):
        ekf.predict(lambda x: x, np.array([[1.0, 0.1], [0.0, 1.0]]), q)
    np.testing.assert_array_equal(ekf.P, ekf.P.T)
    ref = np.eye(2)
    f = np.array([[1.0, 0.1], [0.0, 1.0]])
    for _ in range(3):
        ref = f @ ref @ f.T + 0.5 * (q + q.T)
    np.testing.assert_allclose(ekf.P, ref, rtol=1e-14)


def test_compile_kernels_ahead() -> None:
    from navkit.estimation._ekf_kernels import compile_kernels

    compile_kernels()  # compiled (or loaded from the cache) for the filter's types only
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    assert ekf.update([1.0], lambda x: x, np.eye(1), [[1.0]]).nis == pytest.approx(0.5)


def test_copies_and_pickles_are_independent() -> None:
    import copy
    import pickle

    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2), angle_states=(1,))
    ekf.predict(lambda x: x, np.eye(2), 0.1 * np.eye(2))
    for twin in (copy.copy(ekf), copy.deepcopy(ekf), pickle.loads(pickle.dumps(ekf))):
        assert type(twin) is ExtendedKalmanFilter and twin.angle_states == (1,)
        np.testing.assert_array_equal(twin.x, ekf.x)
        np.testing.assert_array_equal(twin.P, ekf.P)
        twin.update([3.0], lambda x: x[:1], H2, [[0.1]])  # moves the twin only
        assert twin.x[0] > 2.0 and ekf.x[0] == 0.0
        twin.predict(lambda x: x + 4.0, np.eye(2), 0.1 * np.eye(2))
        assert -math.pi < twin.x[1] <= math.pi  # still wraps its angle state


def test_kernels_compile_nothing_for_other_argument_types() -> None:
    """Lists, float32, read-only and strided arrays are converted: no new specialisations."""
    from navkit.estimation import _ekf_kernels

    _run_steps(lambda a: a, steps=4)
    for spell in (
        lambda a: np.asarray(a).tolist(),
        lambda a: np.asarray(a, dtype=np.float32),
        _read_only,
        _strided,
    ):
        _run_steps(spell, steps=4)
    # The filter calls the kernels' compiled entries; their dispatchers hold one signature.
    dispatchers = _ekf_kernels.kernel_dispatchers()
    assert len(dispatchers) >= 3  # predict for 6 states, update for 1 and 2 components
    for kernel in dispatchers:
        assert len(kernel.signatures) == 1


def test_model_functions_share_one_copy_of_the_state() -> None:
    """F sees the prior state before f, which may update its argument in place."""
    seen = []
    ekf = ExtendedKalmanFilter([1.0, 2.0], np.eye(2))
    jac = np.array([[1.0, 0.5], [0.0, 1.0]])

    def f_in_place(x: FloatArray) -> FloatArray:
        x[0] += 0.5 * x[1]
        return x

    def jac_at(x: FloatArray) -> FloatArray:
        seen.append(x.copy())
        return jac

    ekf.predict(f_in_place, jac_at, 0.1 * np.eye(2))
    np.testing.assert_array_equal(seen[0], [1.0, 2.0])  # the prior state
    np.testing.assert_array_equal(ekf.x, [2.0, 2.0])
    np.testing.assert_allclose(ekf.P, jac @ jac.T + 0.1 * np.eye(2), rtol=1e-15)
    out = ekf.update([2.5], lambda x: x[:1], lambda x: H2, [[1.0]])
    assert out.accepted and out.residual[0] == pytest.approx(0.5)


def test_measurement_sizes_alternate() -> None:
    """Alternating measurement sizes switch kernels and validated R matrices correctly."""
    a = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    b = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    h2 = np.array([[1.0, 0.2], [0.0, 1.0]])
    h1 = np.array([[0.5, 1.0]])
    r2 = np.diag([0.1, 0.2])
    r1 = np.array([[0.3]])
    for i in range(6):
        z2 = np.array([0.1 * i, -0.1 * i])
        z1 = np.array([0.05 * i])
        a.update(z2, lambda x: h2 @ x, h2, r2)
        a.update(z1, lambda x: h1 @ x, h1, r1)
        # the same measurements through the converting path (lists)
        b.update(z2.tolist(), lambda x: (h2 @ x).tolist(), h2.tolist(), r2.tolist())
        b.update(z1.tolist(), lambda x: (h1 @ x).tolist(), h1.tolist(), r1.tolist())
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.P, b.P)
    r2[0, 0] = -1.0  # a changed R is validated again, for its own size
    with pytest.raises(ValueError, match="R must be positive definite"):
        a.update(np.zeros(2), lambda x: h2 @ x, h2, r2)


def linear(h: FloatArray) -> Callable[[FloatArray], FloatArray]:
    """The measurement model x -> h x."""
    return lambda x: h @ x


def test_update_options_switch_with_each_call() -> None:
    """Each update uses its own angle_measurements and gate, whatever the previous ones were.

    ``a`` passes the same objects again and again (the buffers keep their options by
    identity), ``b`` new lists and new float objects every time (checked in full).
    """
    a = ExtendedKalmanFilter([0.0, 3.0], np.eye(2), angle_states=(1,))
    b = ExtendedKalmanFilter([0.0, 3.0], np.eye(2), angle_states=(1,))
    h2 = np.eye(2)
    h1 = np.array([[0.0, 1.0]])
    angles2 = (1,)
    angles1 = (0,)
    gate = 4.0
    calls: list[tuple[FloatArray, FloatArray, tuple[int, ...] | None, float | None]] = [
        (np.array([0.1, -3.1]), h2, angles2, None),
        (np.array([0.1, -3.1]), h2, None, None),  # the same z, now not an angle: far off
        (np.array([30.0, 3.0]), h2, angles2, gate),  # gated
        (np.array([30.0, 3.0]), h2, angles2, None),  # the same, no gate: accepted
        (np.array([-3.0]), h1, angles1, gate),
        (np.array([-3.0]), h1, None, gate),  # gated without the wrap
        (np.array([0.2, 3.1]), h2, None, 1e9),
        (np.array([3.1]), h1, angles1, None),
    ]
    for z, h, angles, g in calls * 3:
        options_a: dict[str, Any] = {}
        options_b: dict[str, Any] = {}
        if angles is not None:
            options_a["angle_measurements"] = angles
            options_b["angle_measurements"] = list(angles)
        if g is not None:
            options_a["gate"] = g
            options_b["gate"] = float(str(g))  # an equal float, another object
        out_a = a.update(z, linear(h), h, np.eye(len(z)), **options_a)
        out_b = b.update(z.tolist(), linear(h), h, np.eye(len(z)), **options_b)
        assert (out_a.accepted, out_a.reason) == (out_b.accepted, out_b.reason)
        np.testing.assert_array_equal(out_a.residual, out_b.residual)
        np.testing.assert_array_equal(a.x, b.x)
        np.testing.assert_array_equal(a.P, b.P)
        if angles is not None:  # the residual of an angle component is wrapped
            assert all(-math.pi < out_a.residual[i] <= math.pi for i in angles)
    results = [a.update(z, linear(h), h, np.eye(len(z)), gate=gate) for z, h, *_ in calls]
    assert not all(r.accepted for r in results)  # the gate of this call, not of the last one


@pytest.mark.parametrize("p0", [[[1e-320]], np.diag([1.0, 1e-310])])
def test_covariance_the_kernels_cannot_take_is_refused_at_construction(p0: object) -> None:
    """A subnormal pivot passed P0's check, then failed the first (even identity) predict."""
    with pytest.raises(ValueError, match="P0 must be positive definite with LDLᵀ pivots"):
        ExtendedKalmanFilter(np.zeros(len(p0)), p0)  # type: ignore[arg-type]
    tiny = ExtendedKalmanFilter([0.0], [[1e-300]])  # normal pivots: accepted, and it steps
    tiny.predict(lambda x: x, [[1.0]], [[0.0]])
    assert tiny.P[0, 0] == 1e-300


def test_measurement_noise_the_kernels_cannot_take_is_refused() -> None:
    """The same for R: a subnormal pivot failed as a FilterError on S with a zero row of H."""
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    H = np.array([[1.0, 0.0], [0.0, 0.0]])
    with pytest.raises(ValueError, match="R must be positive definite with LDLᵀ pivots"):
        ekf.update([0.1, 0.0], lambda x: H @ x, H, np.diag([1.0, 1e-320]))
    np.testing.assert_array_equal(ekf.x, [0.0, 0.0])
    assert ekf.update([0.1, 0.0], lambda x: H @ x, H, np.diag([1.0, 1e-300])).accepted
