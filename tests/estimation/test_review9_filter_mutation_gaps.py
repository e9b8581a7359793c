"""Review 9 (mutation testing): filter promises that no earlier test pinned down.

References are computed independently (exact rational arithmetic with
``fractions.Fraction``), not taken from navkit.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion


def _exact_posterior(p: list[list[float]], row: int, r: float) -> list[list[Fraction]]:
    """P - P hᵀ (h P hᵀ + r)⁻¹ h P for h the unit row ``row``, in exact arithmetic."""
    pf = [[Fraction(v) for v in line] for line in p]
    s = pf[row][row] + Fraction(r)
    n = len(p)
    return [[pf[i][j] - pf[i][row] * pf[row][j] / s for j in range(n)] for i in range(n)]


@pytest.mark.parametrize(
    ("p", "r"),
    [
        ([[1e8]], 1e-8),
        ([[1e6]], 1e-12),
        ([[1e8, 5e7], [5e7, 1e8]], 1e-8),
        ([[4.0, 1.0, -1.0], [1.0, 2.0, 0.5], [-1.0, 0.5, 3.0]], 1e-17),
    ],
)
def test_ekf_precise_measurement_of_a_vague_state_keeps_the_true_posterior(
    p: list[list[float]], r: float
) -> None:
    # The Joseph form's reason to exist: S = P00 + R rounds to P00, the gain to
    # exactly 1, and the short form (I - KH)P leaves a posterior variance of 0 (not
    # positive definite). The true posterior variance of the measured state is
    # about R, and every entry matches exact arithmetic.
    n = len(p)
    ekf = ExtendedKalmanFilter(np.zeros(n), p)
    h = np.zeros((1, n))
    h[0, 0] = 1.0
    result = ekf.update([1.0], lambda x: x[:1], h, [[r]])
    assert result.accepted
    exact = _exact_posterior(p, 0, r)
    got = ekf.P
    scale = max(abs(float(v)) for line in exact for v in line)
    for i in range(n):
        for j in range(n):
            assert math.isclose(got[i, j], float(exact[i][j]), rel_tol=1e-6, abs_tol=1e-9 * scale)
    assert math.isclose(got[0, 0], float(exact[0][0]), rel_tol=1e-6)
    assert got[0, 0] > 0.0
    assert np.all(np.linalg.eigvalsh(got) > 0.0)


@pytest.mark.parametrize(("component", "method"), [(2, "update_yaw"), (3, "update_speed")])
@pytest.mark.parametrize(("prior", "r"), [(1e-9, 1e-100), (1.0, 1e-20), (1e4, 1e-14)])
def test_fusion_precise_measurement_keeps_the_true_posterior(
    component: int, method: str, prior: float, r: float
) -> None:
    # As above, for PlanarFusion's own Joseph-form update.
    diag = [1.0] * 6
    diag[component] = prior
    fusion = PlanarFusion(P0=diag, t0=0.0)
    result = getattr(fusion, method)(0.0, 0.3, variance=r)
    assert result.accepted
    exact = float(Fraction(prior) * Fraction(r) / (Fraction(prior) + Fraction(r)))
    assert math.isclose(fusion.P[component, component], exact, rel_tol=1e-9)
    assert fusion.x[component] == pytest.approx(0.3, rel=1e-12)


def test_ekf_nis_exactly_at_the_gate_is_accepted() -> None:
    # Documented: "a measurement with NIS above it is rejected". Here S = 1 + 1 and
    # y = 2, so the NIS is exactly 2.
    for gate, accepted in ((2.0, True), (math.nextafter(2.0, 0.0), False), (3.0, True)):
        ekf = ExtendedKalmanFilter([0.0], [[1.0]])
        result = ekf.update([2.0], lambda x: x.copy(), [[1.0]], [[1.0]], gate=gate)
        assert result.nis == 2.0
        assert result.accepted is accepted
        assert bool(ekf.x[0] != 0.0) is accepted


@pytest.mark.parametrize("gate", [0.0, -1.0, math.inf, 1e-320])
def test_ekf_invalid_gate_is_refused_after_earlier_updates_too(gate: float) -> None:
    # The first update of a measurement size validates the options in full; later
    # ones of that size take a fast path, which must refuse the same gates.
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    h = np.array([[1.0, 0.0]])
    for _ in range(2):
        assert ekf.update(np.array([0.1]), lambda x: x[:1], h, np.array([[1.0]]), gate=5.0).accepted
    before = ekf.x.copy()
    with pytest.raises(ValueError, match="gate"):
        ekf.update(np.array([0.1]), lambda x: x[:1], h, np.array([[1.0]]), gate=gate)
    np.testing.assert_array_equal(ekf.x, before)


@pytest.mark.parametrize("bits", [4, 16])
def test_diff_odometry_half_range_step_is_negative_as_tick_delta(bits: int) -> None:
    # tick_delta maps a change to [-2**(bits-1), 2**(bits-1)): a change of exactly
    # half the counter range is taken as that many ticks backwards, by update (its
    # plain-int fast path) as by update_batch.
    from navkit.estimation import DiffOdometry
    from navkit.kinematics import DiffDrive

    half = 2 ** (bits - 1)
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    expected_x = -2.0 * math.pi * 0.1 * half / 1000.0
    online = DiffOdometry(drive, ticks_per_rev=1000, bits=bits)
    online.update(0, 0)
    pose = online.update(half, half)
    assert math.isclose(pose.x, expected_x, rel_tol=1e-12)
    batch = DiffOdometry(drive, ticks_per_rev=1000, bits=bits)
    rows = batch.update_batch([0, half], [0, half])
    assert math.isclose(float(rows[-1, 0]), expected_x, rel_tol=1e-12)
