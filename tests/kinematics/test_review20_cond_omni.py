"""Conditioning review: omni layouts close to singular (two wheels almost parallel).

With wheels at 0, ε and 90°, the layout's condition number grows as 5.3/ε. Against an
exact solve of the (square) Jacobian in 60-digit arithmetic (mpmath; skipped when
absent) :meth:`OmniDrive.forward` is backward stable: its error relative to the
largest twist component stays below about 0.5 κ ε_mach (measured 2.8e-7 at κ = 5.3e9,
4.7e-12 at 5.3e4), for every base radius (the layout, not the Jacobian, is inverted).
Beyond κ = 1e10 the layout is refused with a ValueError naming ``wheel_angles``.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.kinematics import OmniDrive

mp = pytest.importorskip("mpmath")

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

_EPS = 2.0**-52


@pytest.mark.parametrize("spread", [1e-2, 1e-4, 1e-6, 1e-8, 1e-9])
@pytest.mark.parametrize("base_radius", [1e-6, 0.2, 1e6])
def test_nearly_parallel_wheels_lose_only_what_the_layout_costs(
    spread: float, base_radius: float
) -> None:
    angles = np.array([0.0, spread, np.pi / 2])
    drive = OmniDrive(angles, wheel_radius=0.05, base_radius=base_radius)
    layout = np.column_stack((-np.sin(angles), np.cos(angles), np.ones(3)))
    kappa = float(np.linalg.cond(layout))
    speeds = [1.0, -2.0, 0.5]
    twist = drive.forward(speeds)
    with mp.workdps(60):
        jac = mp.matrix(
            [[-mp.sin(mp.mpf(a)), mp.cos(mp.mpf(a)), mp.mpf(base_radius)] for a in angles]
        ) / mp.mpf(0.05)
        exact = [float(v) for v in mp.lu_solve(jac, mp.matrix(speeds))]
    got = [twist.vx, twist.vy, twist.omega]
    scale = max(abs(v) for v in exact)
    error = max(abs(g - e) for g, e in zip(got, exact, strict=True)) / scale
    assert error <= 4.0 * kappa * _EPS, (error, kappa)


@pytest.mark.parametrize("spread", [1e-10, 1e-12, 0.0])
def test_a_layout_beyond_the_condition_limit_is_refused(spread: float) -> None:
    with pytest.raises(ValueError, match="wheel_angles"):
        OmniDrive(np.array([0.0, spread, np.pi / 2]), wheel_radius=0.05, base_radius=0.2)
