"""A scalar update whose H P Hᵀ cancels reported and gated on a NIS 4 % off (fixed).

Review 28 bounded the rounding error of the computed S = H P Hᵀ + R by
``cₖ = max(uₖ² + Rₖₖ, Sₖₖ)``, ``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``, and sent updates with
``ε max cₖ / Dₖ > 2⁻³⁰`` to the exact NIS (the kernel's test, ``retry_gated``'s,
``finish_cancelled``'s), but only for 2 to 8 components: "m = 1: untested ... no
κ(S) amplifies S's error ... measured NIS errors 5e-10". The bound is on S's own
error, which a scalar S has as well: where a row of H is nearly orthogonal to the
main direction of a strongly correlated P, H P Hᵀ cancels and the one pivot, S
itself, is as far off as S's terms are large against it. In the cases below
``cₖ / S`` is 1.1e15: the kernel's NIS is 1.8271 for an exact 1.9111 (accepted
at a gate of 1.87), and 1.4266 for an exact 1.4040 (rejected at a gate of 1.415,
with no retry for m = 1). In a random draw of 2-state filters with P's correlation
1 - 1e-9 to 1 - 1e-15 and H nearly orthogonal to it, 2229 of 2621 reported NISs
were more than 1e-8 off the exact one (up to 4.4 %).

Fixed: the test of S applies to m = 1 as well (the kernel's ``ill`` and
``retry_gated``), so that such an update reports and gates on the exact NIS.
"""

from __future__ import annotations

import numpy as np

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

# (P0, H, R, z), x0 = 0: the kernel's NIS below the exact one.
LOW = (
    [[11068.079470922055, 0.6102974117583931], [0.6102974117583931, 3.3651992812079605e-05]],
    [[0.016404341783601253, -297.5017672218659]],
    [[1.6546609238011574e-16]],
    [-1.356247240112222e-07],
)
# The kernel's NIS above the exact one.
HIGH = (
    [[0.36901211730649536, 12.284107947133561], [12.284107947133561, 408.9277857818853]],
    [[1.7657373120027087, -0.053042391593548156]],
    [[1.2634101093081115e-17]],
    [-7.597291528232762e-08],
)


def _arrays(case: tuple[list[list[float]], ...]) -> tuple[np.ndarray, ...]:
    return tuple(np.array(a, dtype=np.float64) for a in case)


def _exact(case: tuple[list[list[float]], ...]) -> tuple[float, np.ndarray]:
    p0, h, r, z = _arrays(case)
    elimination = kernels._eliminated(p0, h, r, z)
    x = kernels._exact_state(np.zeros(2), elimination)
    assert x is not None
    return float(kernels._nis_of(elimination)), x


def test_the_cases_are_as_described() -> None:
    for case, low, high in ((LOW, 1.911, 1.912), (HIGH, 1.404, 1.405)):
        p0, h, r, _ = _arrays(case)
        reach = float((np.abs(h) @ np.sqrt(np.diag(p0)))[0])
        s = float((h @ p0 @ h.T + r)[0, 0])
        assert (reach * reach + r[0, 0]) / s > 1e14
        nis, _ = _exact(case)
        assert low < nis < high


def test_an_ungated_scalar_update_reports_the_exact_nis() -> None:
    for case in (LOW, HIGH):
        p0, h, r, z = _arrays(case)
        nis, x = _exact(case)
        ekf = ExtendedKalmanFilter(np.zeros(2), p0)
        result = ekf.update(z, lambda x, h=h: h @ x, h, r)
        assert result.accepted
        assert result.nis == nis  # 1.8271 and 1.4266 before
        np.testing.assert_array_equal(ekf.x, x)


def test_a_scalar_measurement_the_exact_nis_rejects_is_gated() -> None:
    p0, h, r, z = _arrays(LOW)
    ekf = ExtendedKalmanFilter(np.zeros(2), p0)
    result = ekf.update(z, lambda x: h @ x, h, r, gate=1.87)
    assert not result.accepted  # passed on the kernel's 1.8271 before
    assert result.nis == _exact(LOW)[0]
    np.testing.assert_array_equal(ekf.x, np.zeros(2))
    np.testing.assert_array_equal(ekf.P, p0)


def test_a_scalar_measurement_the_exact_nis_passes_is_not_gated() -> None:
    p0, h, r, z = _arrays(HIGH)
    nis, x = _exact(HIGH)
    ekf = ExtendedKalmanFilter(np.zeros(2), p0)
    result = ekf.update(z, lambda x: h @ x, h, r, gate=1.415)
    assert result.accepted, result.reason  # rejected on the kernel's 1.4266 before
    assert result.nis == nis
    np.testing.assert_array_equal(ekf.x, x)
