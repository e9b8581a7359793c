"""The EKF update kernel's cheap test of its Joseph P counts each state's own R term.

Review 35 (mutation testing, MUTANT4). ``_joseph_in_doubt`` first compares a
cheap bound, ``Pᵢᵢ (1 + β)² + ρᵢ²`` with ``ρᵢ = Σₖ |Kᵢₖ| sqrt(Rₖₖ)``, against
2¹³ P⁺ᵢᵢ, and computes the full first-order estimate of the Joseph P's error
only where some state exceeds it. Storing sqrt(Rₖₖ) in the row that then
receives the ρᵢ² (``r_dev = work[3]``) made each state after the first read
the previous state's ρ² as sqrt(Rₖₖ), and passed the suite: it rarely
changes the outcome (1 of 3000 random updates with ill-conditioned R). In
the update below the full estimate is 1.2 times the limit and only state 1's
cheap bound flags it: the kernel must not commit (it returns ``CANCELLED`` and
the public layer finishes the update, within 2⁻⁴⁰ of the exact posterior);
the mutant committed its Joseph P. Oracle: the bound and the estimate
(E Aᵀ + |K| |R| |K|ᵀ over sqrt(P⁺ᵢᵢ P⁺ⱼⱼ), E = |P| + |K| |H| |P|, A = I - K H,
from the kernel's docstring) computed here in NumPy, and the exact posterior
in rational arithmetic (``exact_fractions``).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update, posterior_relative

# Draw 2490 of a search (ill-conditioned R, 2 states, 2 components).
X0 = np.array([0.6388685649418532, -1.0462536071617405])
P0 = np.array([[0.01321950767461927, -0.029646992210189592],
               [-0.029646992210189592, 0.07517945351867093]])  # fmt: skip
H = np.array([[1.0367034339759902, -1.4623641275933739],
              [-0.27691676116944064, 1.3174901491687498]])  # fmt: skip
R = np.array([[63867.445665811116, -2810.9787855342765],
              [-2810.9787855342765, 123.75792140747564]])  # fmt: skip
Z = np.array([1.9613999517472227, 1.209543488154166])
EPS = 2.0**-53


def _posterior() -> tuple[np.ndarray, np.ndarray]:
    s = H @ P0 @ H.T + R
    k = np.linalg.solve(s, H @ P0).T
    a = np.eye(2) - k @ H
    return k, a @ P0 @ a.T + k @ R @ k.T


def test_only_the_second_state_s_cheap_bound_flags_the_update() -> None:
    k, pn = _posterior()
    sigma = np.sqrt(np.diag(P0))
    beta = float(np.max((np.abs(k) @ (np.abs(H) @ sigma)) / sigma))
    rho2 = (np.abs(k) @ np.sqrt(np.diag(R))) ** 2
    cheap = (np.diag(P0) * (1.0 + beta) ** 2 + rho2) / (kernels._P_SURE / EPS * np.diag(pn))
    assert cheap[0] < 0.9 and cheap[1] > 1.1
    # Not the other reasons to cancel: no variance shrank 4096-fold.
    assert np.all(np.diag(P0) / np.diag(pn) < 100.0)


def test_the_full_estimate_exceeds_the_limit() -> None:
    k, pn = _posterior()
    e = np.abs(P0) + np.abs(k) @ np.abs(H) @ np.abs(P0)
    term = e @ np.abs(np.eye(2) - k @ H).T + np.abs(k) @ np.abs(R) @ np.abs(k).T
    deviation = np.sqrt(np.diag(pn))
    ratio = float(np.max(EPS * term / np.outer(deviation, deviation))) / kernels._P_SURE
    assert ratio > 1.1


def test_the_kernel_does_not_commit_its_joseph_p() -> None:
    state = kernels.new_state(X0, P0, ())
    rbuf = kernels.new_rbuf(2, 2)
    kernels.set_r(rbuf, R, 0.5 * R + 0.5 * R.T)
    out = kernels.update_kernel(2, 2)(state, Z, H @ X0, H, R, rbuf, np.empty(2))
    assert out == -float(kernels.CANCELLED)
    np.testing.assert_array_equal(state[kernels.STATE_X], X0)  # nothing committed


def test_the_public_update_is_within_the_bound_of_the_exact_posterior() -> None:
    ekf = ExtendedKalmanFilter(X0, P0)
    result = ekf.update(Z, lambda s: H @ s, H, R)
    assert result.accepted
    _, p_exact, _ = exact_update(X0, P0, H, R, result.residual)
    p_rounded = np.array([[float(v) for v in row] for row in p_exact])
    assert posterior_relative(ekf.P, p_rounded) <= kernels._P_SURE
