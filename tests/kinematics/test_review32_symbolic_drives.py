"""Drive kinematics against their symbolic derivation (review 32, symbolic lens).

OmniDrive: the wheel Jacobian ``J`` (rows ``[-sin θi, cos θi, L] / r``) and its
Moore–Penrose pseudo-inverse ``(JᵀJ)⁻¹Jᵀ`` are computed in mpmath at 50 digits for
arbitrary layouts; navkit's ``forward_matrix`` must agree to rounding times the
layout's condition number. For the Y layout sympy gives (at authoring time)

    J⁻¹ = [[-r/3, -r/3, 2r/3], [√3 r/3, -√3 r/3, 0], [r/(3L), r/(3L), r/(3L)]]

i.e. ``(2r/3)[cos(θi + π/2), sin(θi + π/2)]`` in the velocity rows, and the paper's
forward matrix ``r [cos(θi + π/2), sin(θi + π/2), 1/(3L)]`` times ``J`` is
``diag(3/2, 3/2, 1)``: the correction the class docstring states.

DiffDrive with unequal radii: ``v = (ωr Rr + ωl Rl)/2``, ``ω = (ωr Rr - ωl Rl)/D``
and its inverse, evaluated exactly at the float inputs.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.kinematics import DiffDrive, OmniDrive

mp = pytest.importorskip("mpmath")

EPS = 2.0**-52


pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")


def _exact_pinv(angles: np.ndarray, r: float, big_l: float) -> Any:
    jac = mp.matrix([[-mp.sin(a), mp.cos(a), mp.mpf(big_l)] for a in angles.tolist()]) / r
    return mp.inverse(jac.T * jac) * jac.T


def test_omni_forward_matrix_is_the_exact_pseudo_inverse() -> None:
    rng = np.random.default_rng(3203)
    mp.mp.dps = 50
    checked = 0
    while checked < 150:
        n = int(rng.integers(3, 8))
        angles = rng.uniform(-7.0, 7.0, n)
        r = float(10 ** rng.uniform(-3, 0))
        big_l = float(10 ** rng.uniform(-2, 2))
        layout = np.column_stack((-np.sin(angles), np.cos(angles), np.ones(n)))
        cond = float(np.linalg.cond(layout))
        if cond > 1e3:
            continue  # far from the 1e10 refusal: ordinary layouts, tight bound
        drive = OmniDrive(angles, wheel_radius=r, base_radius=big_l)
        exact = _exact_pinv(angles, r, big_l)
        got = drive.forward_matrix
        for i in range(3):
            row = max(abs(exact[i, j]) for j in range(n))
            for j in range(n):
                # SVD-based pinv: backward stable, rounding times cond and a factor of n.
                assert abs(float(exact[i, j]) - got[i, j]) <= 16 * n * EPS * cond * float(row)
        checked += 1


def test_omni_three_wheel_inverse_is_the_closed_form_and_the_paper_matrix_is_not() -> None:
    r, big_l = 0.05, 0.2
    drive = OmniDrive.three_wheel(wheel_radius=r, base_radius=big_l)
    s3 = math.sqrt(3.0)
    closed = np.array(
        [[-r / 3, -r / 3, 2 * r / 3], [s3 * r / 3, -s3 * r / 3, 0.0], [r / (3 * big_l)] * 3]
    )
    assert np.allclose(drive.forward_matrix, closed, rtol=0.0, atol=8 * EPS)
    theta = np.radians([30.0, 150.0, 270.0])
    paper = np.array(
        [r * np.cos(theta + np.pi / 2), r * np.sin(theta + np.pi / 2), [r / (3 * big_l)] * 3]
    )
    assert np.allclose(paper @ drive.jacobian, np.diag([1.5, 1.5, 1.0]), atol=1e-14)
    assert np.allclose(drive.forward_matrix @ drive.jacobian, np.eye(3), atol=1e-14)


def test_diff_drive_with_unequal_radii_is_the_symbolic_model() -> None:
    rng = np.random.default_rng(3204)
    mp.mp.dps = 50
    for i in range(600):
        track = float(10 ** rng.uniform(-2, 1))
        left = float(10 ** rng.uniform(-2, 0))
        # Radii 1e-9 apart (the close-radii branch) to a factor 2 apart.
        spread = float(rng.choice([1e-9, 1e-3, 0.01, 0.5]))
        right = left * (1.0 + spread * float(rng.uniform(-1, 1)))
        drive = DiffDrive(track=track, left_radius=left, right_radius=right)
        wl, wr = (float(v) for v in rng.normal(0.0, 10.0, 2))
        if i % 3 == 0:  # driving straight: ω cancels
            wr = wl * left / right * (1.0 + 1e-9 * float(rng.normal()))
        elif i % 3 == 1:  # turning on the spot: v cancels
            wr = -wl * left / right * (1.0 + 1e-9 * float(rng.normal()))
        got = drive.forward([wl, wr])
        ml, mr = mp.mpf(wl) * left, mp.mpf(wr) * right
        size = abs(ml) + abs(mr)
        assert float(abs((mr + ml) / 2 - got.vx)) <= 4 * EPS * float(size), (i, wl, wr)
        assert float(abs((mr - ml) / track - got.omega)) <= 4 * EPS * float(size) / track
        assert got.vy == 0.0
        v, w = (float(u) for u in rng.normal(0.0, 1.0, 2))
        speeds = drive.inverse([v, 0.0, w])
        half = mp.mpf(w) * track / 2
        size = abs(v) + abs(half)
        assert float(abs((v - half) / left - speeds[0])) * left <= 3 * EPS * float(size)
        assert float(abs((v + half) / right - speeds[1])) * right <= 3 * EPS * float(size)
