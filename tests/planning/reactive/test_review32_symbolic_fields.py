"""Potential fields against their symbolic gradients (review 32, symbolic lens), in mpmath.

Each field's potential was written in sympy from its docstring's definition and
differentiated there (at authoring time; sympy is not a test dependency). The
results, written out below, are evaluated in mpmath at 50 digits at navkit's
float inputs:

* blended sigmoid field, ``σ = (tanh((d - r)/ω) + 1)/2`` (note: sympy's form, with
  ``sech²``, not navkit's ``expit`` one)::

      -∂U/∂q = -(1 - σ) ∇U_par - σ m U_trans ∇d - sech²((d - r)/ω)/(2ω) (U_cone - U_par) ∇d

* paraboloid ``-∇U = -2 K c ((x - xd)/a², (y - yd)/b²)``; cone ``-m U_trans ∇d``;
  piecewise attraction ``-α clip(d - r, 0, s) ∇d``;
* Khatib: ``-∇[½k(1/d - 1/d0)²] = k (1/d - 1/d0) / d² · ∇d`` (``∇d = (q - q_c)/d``),
  per obstacle point and summed over the beams of a scan.

Tolerances: a few ulps of the terms' magnitudes times the condition of the
offset ``q - q_d`` (its rounding, ``(|q| + |q_d|)/d``) and of the blend's
argument (``d/ω``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.mapping import LaserScan
from navkit.planning.reactive import (
    BlendedAttraction,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    repulsive_force_from_scan,
)

mp = pytest.importorskip("mpmath")

EPS = 2.0**-52


pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")


def _blended_exact(q: np.ndarray, g: np.ndarray, p: dict[str, float]) -> tuple[Any, Any, Any]:
    """The sympy gradient's force, its terms' magnitude, and the distance."""
    ox, oy = mp.mpf(float(q[0])) - float(g[0]), mp.mpf(float(q[1])) - float(g[1])
    d = mp.sqrt(ox**2 + oy**2)
    kc = mp.mpf(p["k_att"]) * p["c"]
    arg = (d - p["threshold_radius"]) / p["width"]
    sig = (mp.tanh(arg) + 1) / 2
    dsig = mp.sech(arg) ** 2 / (2 * p["width"])
    u_par = kc * (ox**2 / mp.mpf(p["a"]) ** 2 + oy**2 / mp.mpf(p["b"]) ** 2)
    u_cone = mp.mpf(p["m"]) * p["u_trans"] * (d - p["threshold_radius"])
    grad_par = (2 * kc * ox / mp.mpf(p["a"]) ** 2, 2 * kc * oy / mp.mpf(p["b"]) ** 2)
    radial = sig * p["m"] * p["u_trans"] + dsig * (u_cone - u_par)
    force = mp.matrix(
        [-(1 - sig) * grad_par[0] - radial * ox / d, -(1 - sig) * grad_par[1] - radial * oy / d]
    )
    size = (
        (1 - sig) * mp.sqrt(grad_par[0] ** 2 + grad_par[1] ** 2)
        + dsig * (abs(u_cone) + abs(u_par))
        + sig * p["m"] * p["u_trans"]
    )
    return force, size, d


def test_blended_force_is_the_symbolic_gradient() -> None:
    rng = np.random.default_rng(3208)
    mp.mp.dps = 50
    for i in range(400):
        p = {
            k: float(10 ** rng.uniform(lo, hi))
            for k, lo, hi in (
                ("k_att", -2, 2),
                ("c", -1, 1),
                ("a", -1, 1),
                ("b", -1, 1),
                ("threshold_radius", -2, 1),
                ("width", -2, 0.5),
                ("m", -1, 1),
                ("u_trans", -1, 1),
            )
        }
        g = rng.normal(0.0, 3.0, 2)
        # Across the blend (|d - r| of a few widths) and from 1 µm to 30 m.
        if i % 2:
            dist = abs(p["threshold_radius"] + p["width"] * rng.normal(0.0, 3.0))
        else:
            dist = 10 ** rng.uniform(-6, 1.5)
        ang = rng.uniform(-math.pi, math.pi)
        q = g + dist * np.array([math.cos(ang), math.sin(ang)])
        force, size, d = _blended_exact(q, g, p)
        got = BlendedAttraction(g, **p).force(q)[0]
        cond = (
            4
            + 2 * d / p["width"]
            + abs(d - p["threshold_radius"]) * 2 / p["width"]
            + (abs(q).sum() + abs(g).sum()) / d
        )
        for k in range(2):
            assert abs(force[k] - got[k]) <= 8 * EPS * size * cond, (i, p, q, g)


def _radial_roots(width: float) -> list[float]:
    """Where navkit's radial force (defaults, but ``width``) changes sign on (0, 3] m."""
    field = BlendedAttraction((0.0, 0.0), width=width)
    d = np.linspace(1e-5, 3.0, 300_001)
    pull = field.force(np.column_stack((d, np.zeros_like(d))))[:, 0]
    cross = np.nonzero(np.sign(pull[:-1]) != np.sign(pull[1:]))[0]
    return [float(d[k]) for k in cross]


def _exact_root(width: float, near: float) -> float:
    """The exact zero of dU/dd (defaults, but ``width``) nearest ``near``."""

    def du_dd(d: Any) -> Any:
        arg = (d - mp.mpf(0.5)) / width
        sig = (mp.tanh(arg) + 1) / 2
        dsig = mp.sech(arg) ** 2 / (2 * width)
        return (1 - sig) * 2 * d + dsig * ((d - mp.mpf(0.5)) - d**2) + sig

    return float(mp.findroot(du_dd, mp.mpf(near), tol=1e-30))


def test_blended_notes_minima_are_where_the_symbolic_gradient_vanishes() -> None:
    """The Notes' numbers: defaults' minimum 3.75 mm from the goal, a ring at 0.55 m for
    a width of 0.1, minima 4.6 cm away for widths 0.3 and 0.5 and 5.5 cm near 0.38."""
    mp.mp.dps = 30
    # width: (sign changes on (1e-5, 3] m, the claimed one, half a unit of its last digit)
    expected = {
        0.15: (1, 0.00375, 5e-6),
        0.3: (1, 0.046, 5e-4),
        0.5: (1, 0.046, 5e-4),
        0.38: (1, 0.055, 5e-4),
        0.1: (3, 0.55, 5e-3),
    }
    for width, (count, claim, half_unit) in expected.items():
        found = _radial_roots(width)
        # Width 0.1: the minimum 0.2 mm from the goal, the ridge at 0.44 m and the ring.
        assert len(found) == count, (width, found)
        for root in found:
            exact = _exact_root(width, root)
            assert abs(exact - root) <= 2e-5  # the grid's spacing: navkit's sign change
        assert abs(_exact_root(width, found[-1]) - claim) <= half_unit, width


def test_simple_attractions_are_their_symbolic_gradients() -> None:
    rng = np.random.default_rng(3209)
    mp.mp.dps = 50
    for _ in range(300):
        g = rng.normal(0.0, 2.0, 2)
        q = g + rng.normal(0.0, 1.5, 2) * 10 ** rng.uniform(-3, 0.5)
        k_att, c, a, b, m, u, alpha = (float(v) for v in 10 ** rng.uniform(-1, 1, 7))
        r, s = float(rng.uniform(0, 1)), float(rng.uniform(0.1, 2))
        ox, oy = mp.mpf(float(q[0])) - float(g[0]), mp.mpf(float(q[1])) - float(g[1])
        d = mp.sqrt(ox**2 + oy**2)
        cond = 4 + (abs(q).sum() + abs(g).sum()) / float(d)
        cases = [
            (
                ParaboloidAttraction(g, k_att=k_att, c=c, a=a, b=b),
                (-2 * k_att * c * ox / mp.mpf(a) ** 2, -2 * k_att * c * oy / mp.mpf(b) ** 2),
            ),
            (
                ConicAttraction(g, m=m, u_trans=u, threshold_radius=r),
                (-m * u * ox / d, -m * u * oy / d),
            ),
            (
                PiecewiseAttraction(g, alpha=alpha, goal_radius=r, spread=s),
                (-alpha * min(max(d - r, 0), s) * ox / d, -alpha * min(max(d - r, 0), s) * oy / d),
            ),
        ]
        for field, exact in cases:
            got = field.force(q)[0]
            size = mp.sqrt(exact[0] ** 2 + exact[1] ** 2)
            # The piecewise magnitude d - r cancels near the goal radius: its condition too.
            extra = (
                float(d / max(abs(d - r), mp.mpf(1e-300)))
                if isinstance(field, PiecewiseAttraction)
                else 1.0
            )
            for k in range(2):
                assert abs(exact[k] - got[k]) <= 4 * EPS * size * cond * extra, field


def test_khatib_force_is_the_gradient_of_its_potential_per_point_and_per_beam() -> None:
    rng = np.random.default_rng(3210)
    mp.mp.dps = 50
    for _ in range(200):
        obstacles = rng.normal(0.0, 1.0, (int(rng.integers(1, 6)), 2))
        q = rng.normal(0.0, 1.0, 2)
        k, d0 = float(10 ** rng.uniform(-2, 2)), float(rng.uniform(0.2, 3.0))
        got = KhatibRepulsion(obstacles, k_rep=k, influence_radius=d0).force(q)[0]
        fx = fy = total = mp.mpf(0)
        cond = 4.0
        for ob in obstacles:
            ox, oy = mp.mpf(float(q[0])) - float(ob[0]), mp.mpf(float(q[1])) - float(ob[1])
            d = mp.sqrt(ox**2 + oy**2)
            if d > d0:
                continue
            push = k * (1 / d - 1 / mp.mpf(d0)) / d**2
            fx, fy, total = fx + push * ox / d, fy + push * oy / d, total + abs(push)
            # 1/d - 1/d0 cancels near d0; the offset's rounding as above.
            offset = (abs(q).sum() + abs(ob).sum()) / float(d)
            cond = max(cond, 4 + float(d0 / abs(d0 - d)) + offset)
        assert abs(fx - got[0]) <= 8 * EPS * total * cond
        assert abs(fy - got[1]) <= 8 * EPS * total * cond
    for _ in range(40):
        n = int(rng.integers(1, 400))
        d0 = float(10 ** rng.uniform(-1, 1))
        k = float(10 ** rng.uniform(-2, 2))
        ranges = rng.uniform(0.0, 2 * d0, n)
        ranges[rng.random(n) < 0.1] = math.nan
        scan = LaserScan(
            ranges,
            angle_min=float(rng.uniform(-math.pi, 0.0)),
            angle_increment=2 * math.pi / n,
            range_min=0.05,
            range_max=1.9 * d0,
        )
        got = repulsive_force_from_scan(scan, k_rep=k, influence_radius=d0)
        fx = fy = total = mp.mpf(0)
        for rho, theta in zip(ranges.tolist(), LaserScan.angles(scan).tolist(), strict=True):
            if not (0.05 <= rho < 1.9 * d0) or rho > d0:
                continue
            push = k * (1 / mp.mpf(rho) - 1 / mp.mpf(d0)) / mp.mpf(rho) ** 2
            fx, fy, total = fx - push * mp.cos(theta), fy - push * mp.sin(theta), total + push
        # A sum reordered over SIMD lanes (documented): rounding grows with log2(n).
        bound = 4 * EPS * (2 + math.log2(n + 1)) * total
        assert abs(fx - got[0]) <= bound and abs(fy - got[1]) <= bound
