"""Review 9: behaviour of the reactive fields that mutation testing showed untested.

Each test checks a formula or a precision promise of a docstring against an
independent computation from the paper's equations (plain ``math``), on inputs
chosen so that a plausible slip in the code (a dropped offset, ``1 - σ``
computed by subtraction) changes the answer.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.planning.reactive import BlendedAttraction, ConicAttraction, PiecewiseRepulsion


@pytest.mark.parametrize(("m", "u_trans", "rad_thr"), [(2.0, 3.0, 0.5), (0.25, 1.0, 4.0)])
def test_conic_potential_is_offset_by_the_threshold_radius(
    m: float, u_trans: float, rad_thr: float
) -> None:
    # U = m·(d - rad_thr)·U_trans: the offset shifts the potential (it may be
    # negative inside rad_thr) while the force keeps the magnitude m·U_trans.
    field = ConicAttraction(np.array([1.0, -2.0]), m=m, u_trans=u_trans, threshold_radius=rad_thr)
    pts = np.array([[4.0, 2.0], [1.0, -1.0], [1.0, -2.0]])
    d = [math.hypot(x - 1.0, y + 2.0) for x, y in pts]
    expected = [m * (di - rad_thr) * u_trans for di in d]
    np.testing.assert_allclose(field.potential(pts), expected, rtol=1e-14, atol=0.0)
    plain = ConicAttraction(np.array([1.0, -2.0]), m=m, u_trans=u_trans)
    np.testing.assert_allclose(
        field.potential(pts) - plain.potential(pts), -m * u_trans * rad_thr, rtol=1e-14
    )
    np.testing.assert_array_equal(field.force(pts), plain.force(pts))


def _blend_reference(
    d: float, k_att: float, c: float, rad_thr: float, width: float, m: float, u_trans: float
) -> tuple[float, float]:
    """(U, -dU/dd) of the circular blend (a = b = 1) along the radius, from the paper's form.

    σ and 1 - σ are written as 1 / (1 + e^∓z), each exact where it is tiny.
    """
    z = 2.0 * (d - rad_thr) / width
    sig = 1.0 / (1.0 + math.exp(-z))
    one_minus = 1.0 / (1.0 + math.exp(z))
    u_par = k_att * c * d * d
    u_cone = m * (d - rad_thr) * u_trans
    dsig = (2.0 / width) * sig * one_minus
    grad = one_minus * 2.0 * k_att * c * d + sig * m * u_trans + dsig * (u_cone - u_par)
    return one_minus * u_par + sig * u_cone, -grad


@pytest.mark.parametrize("d", [1.9e-5, 1.95e-5, 2.0e-5])
def test_blend_keeps_one_minus_sigma_precise_where_it_is_tiny(d: float) -> None:
    # The docstring promises 1 - σ is evaluated as expit(-z), not as 1 - expit(z):
    # with a stiff paraboloid (K_att·c = 1e24) and a narrow blend, 1 - σ ≈ e^-40
    # rounds to 0 as a difference, yet (1 - σ)·U_par dominates the potential.
    k_att, c, rad_thr, width, m, u_trans = 1e12, 1e12, 0.0, 1e-6, 1.0, 1.0
    field = BlendedAttraction(
        np.array([0.0, 0.0]), k_att=k_att, c=c, threshold_radius=rad_thr, width=width, m=m,
        u_trans=u_trans,
    )
    u_ref, f_ref = _blend_reference(d, k_att, c, rad_thr, width, m, u_trans)
    # The paraboloid's share is what a subtraction would lose.
    assert (1.0 / (1.0 + math.exp(2.0 * d / width))) * k_att * c * d * d > 10.0 * m * d
    np.testing.assert_allclose(field.potential([[d, 0.0]]), [u_ref], rtol=1e-9)
    np.testing.assert_allclose(field.force([[d, 0.0]]), [[f_ref, 0.0]], rtol=1e-9, atol=1e-12)
    # Along y the same distance gives the same radial values (a = b).
    np.testing.assert_allclose(field.force([[0.0, -d]]), [[0.0, -f_ref]], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize(("delta", "beta", "r", "s"), [(5.0, 2.0, 0.5, 1.0), (0.5, 3.0, 2.0, 0.25)])
def test_piecewise_repulsion_at_the_obstacle_radius_is_the_linear_piece(
    delta: float, beta: float, r: float, s: float
) -> None:
    # The docstring's pieces: -δ·û for d < r, -β(s + r - d)·û for r <= d <= s + r.
    # At d = r exactly (an exact float distance) the linear piece, β·s, applies.
    field = PiecewiseRepulsion(
        np.array([[0.0, 0.0]]), delta=delta, beta=beta, obstacle_radius=r, spread=s
    )
    assert delta != beta * s  # the force jumps at d = r: the two pieces differ there
    np.testing.assert_allclose(
        field.force([[r, 0.0], [0.0, -r]]), [[beta * s, 0.0], [0.0, -beta * s]]
    )
    np.testing.assert_allclose(field.potential([[r, 0.0]]), [0.5 * beta * s * s])
    # Just inside, the constant push δ.
    inside = math.nextafter(r, 0.0)
    np.testing.assert_allclose(field.force([[inside, 0.0]]), [[delta, 0.0]])
