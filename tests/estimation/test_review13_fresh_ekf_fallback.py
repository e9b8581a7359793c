"""Fresh-eyes review 13: ExtendedKalmanFilter's information-form fallback made updates worse.

``finish_cancelled`` keeps the information form (P⁻¹ + Hᵀ R⁻¹ H)⁻¹ where its error
estimate (κ, from inverses of scaled matrices) is below the Joseph form's, whose
estimate is scaled by the smaller of the two forms' variances. When the information
matrix is singular to working precision (a dense row of H measured ~1e40 times more
precisely than the prior) its inverse is garbage with tiny variances, κ comes out
about 1/ε (not the true 1e40), and the garbage's tiny variances inflate the Joseph
form's estimate: the garbage is kept. At 6f6c674 (Joseph form only) these updates
were accurate to 1e-13; now the covariance is off by its own size (posterior
variances 1e23 times too small: an overconfident filter). Found by 3000 random
updates compared with exact ``Fraction`` posteriors, old code against new: 9 were
more than 10 times worse and above 1e-12, 6 above 1e-6.

Both cases lie outside ``update``'s documented guarantee (a dense H; a P of scaled
condition 1.5e12), but ``finish_cancelled`` says that there "the Joseph form stays,
its result and status as before". The values are float hex, the draws exactly.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from exact_fractions import exact_gain, fractions
from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter


def _hex(rows: list[list[str]]) -> np.ndarray:
    return np.array([[float.fromhex(v) for v in row] for row in rows])


def _exact_posterior(p: np.ndarray, h: np.ndarray, r: np.ndarray) -> np.ndarray:
    """P - P Hᵀ (H P Hᵀ + R)⁻¹ H P in exact arithmetic, rounded once."""
    n, m = p.shape[0], h.shape[0]
    pf = fractions(p)
    hp, s_inv, _ = exact_gain(p, h, r)
    out = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            gain_term = sum(hp[a][i] * s_inv[a][b] * hp[b][j] for a in range(m) for b in range(m))
            out[i, j] = float(pf[i][j] - gain_term)
    return out


def _relative_error(got: np.ndarray, exact: np.ndarray) -> float:
    scale = np.sqrt(np.diag(exact))
    return float(np.max(np.abs(got - exact) / np.outer(scale, scale)))


# A 2-state prior of scaled condition 357, one dense row of H, R 1e42 below H P Hᵀ.
DENSE_P = _hex(
    [
        ["0x1.6edf89d55baecp+66", "-0x1.1d3ab56a912e5p+67"],
        ["-0x1.1d3ab56a912e5p+67", "0x1.c080256cef1f9p+67"],
    ]
)
DENSE_H = _hex([["0x1.a57b336de428ap-2", "-0x1.17e2281a7a0b2p+1"]])
DENSE_R = _hex([["0x1.6dde62d8e4cd8p-72"]])

# A 5-state prior of scaled condition 1.5e12, state 0 measured 1e42 more precisely.
ILL_P = _hex(
    [
        ["0x1.161d739c7285ep+90", "-0x1.15674c54f96a5p+90", "0x1.f97ab3b0c5349p+89",
         "-0x1.c1fe33d6f7627p+91", "0x1.043940323ab24p+90"],
        ["-0x1.15674c54f96a5p+90", "0x1.2476b94eedfd4p+91", "-0x1.42edcd5601296p+91",
         "0x1.687f157691b5bp+92", "-0x1.b5f80865a1a79p+90"],
        ["0x1.f97ab3b0c5349p+89", "-0x1.42edcd5601296p+91", "0x1.6e5ac87ca1b7bp+91",
         "-0x1.7a4d7249d4498p+92", "0x1.d0660904c2772p+90"],
        ["-0x1.c1fe33d6f7627p+91", "0x1.687f157691b5bp+92", "-0x1.7a4d7249d4498p+92",
         "0x1.e4315e08ec959p+93", "-0x1.2148fe970ce53p+92"],
        ["0x1.043940323ab24p+90", "-0x1.b5f80865a1a79p+90", "0x1.d0660904c2772p+90",
         "-0x1.2148fe970ce53p+92", "0x1.5ac028405d2d7p+90"],
    ]
)  # fmt: skip
ILL_H = np.array([[1.0, 0.0, 0.0, 0.0, 0.0]])
ILL_R = _hex([["0x1.9efd7bfc9ad0cp-49"]])


def test_a_dense_precise_measurement_keeps_the_posterior() -> None:
    ekf = ExtendedKalmanFilter(np.zeros(2), DENSE_P)
    assert ekf.update([0.0], lambda x: DENSE_H @ x, DENSE_H, DENSE_R).accepted
    exact = _exact_posterior(DENSE_P, DENSE_H, DENSE_R)
    # Exact: variances 9.4e17 and 3.3e16; now 8.0e-6 and 2.9e-7.
    assert _relative_error(ekf.P, exact) < 1e-9


def test_an_ill_conditioned_prior_is_no_worse_than_the_joseph_form() -> None:
    ekf = ExtendedKalmanFilter(np.zeros(5), ILL_P)
    assert ekf.update([0.0], lambda x: ILL_H @ x, ILL_H, ILL_R).accepted
    assert _relative_error(ekf.P, _exact_posterior(ILL_P, ILL_H, ILL_R)) < 1e-9


def test_the_exact_reference_is_what_the_joseph_form_gave() -> None:
    # The reference itself: the posterior variances are 9.4e17 and 3.3e16 (the Joseph
    # form of 6f6c674 met every entry to 3.5e-14), far above the kept garbage's 1e-5.
    exact = _exact_posterior(DENSE_P, DENSE_H, DENSE_R)
    assert np.all(np.diag(exact) > 1e16)
    assert np.all(np.diag(exact) < np.diag(DENSE_P))


# Four rows of H on three states measured 1e150 times more precisely than known (R
# itself of condition 1e10): S = H P Hᵀ + R has condition 4.5e18, so the kernel's
# gain, and the state x + K y, lose every digit; at 6f6c674 the Joseph P raised
# FilterError, now the information form's P (accurate) is committed with that state.
# 170 of 504 updates that raised before are accepted with x more than 3 posterior
# standard deviations (and more than 1e-12 of |x| + |K y|) from the exact state.
SINGULAR_S_P = _hex(
    [
        ["0x1.46491448e3d43p+111", "-0x1.33450883ab0f2p+108", "0x1.a5d717d1e6c3fp+109",
         "0x1.feba4159b7e2ap+109"],
        ["-0x1.33450883ab0f2p+108", "0x1.3595fd2880e90p+105", "-0x1.908ca62a01a07p+106",
         "-0x1.e6d1e0b6f2234p+106"],
        ["0x1.a5d717d1e6c3fp+109", "-0x1.908ca62a01a07p+106", "0x1.1ac189a57551cp+108",
         "0x1.5068e231cdb5cp+108"],
        ["0x1.feba4159b7e2ap+109", "-0x1.e6d1e0b6f2234p+106", "0x1.5068e231cdb5cp+108",
         "0x1.acdeb97767af9p+108"],
    ]
)  # fmt: skip
SINGULAR_S_H = _hex(
    [
        ["0x1.0000000000000p+0", "0x1.cd744cbe3f757p-2", "0x0.0p+0", "0x0.0p+0"],
        ["0x1.19a1009ebcc04p-1", "-0x1.0af846065fa83p+0", "-0x1.9075529da0843p-1", "0x0.0p+0"],
        ["0x1.3404458c7719ap+1", "0x0.0p+0", "0x0.0p+0", "0x0.0p+0"],
        ["0x1.0000000000000p+0", "0x1.3999761c8de43p+0", "0x0.0p+0", "0x0.0p+0"],
    ]
)  # fmt: skip
SINGULAR_S_R = _hex(
    [
        ["0x1.7f0ac77822d66p-497", "-0x1.40a120cf5d493p-497", "-0x1.b440f1295cf20p-497",
         "-0x1.b3ef83ec0b0dap-497"],
        ["-0x1.40a120cf5d493p-497", "0x1.0c6472c1c44ebp-497", "0x1.6d300a9ee500fp-497",
         "0x1.6ce8614cb9622p-497"],
        ["-0x1.b440f1295cf20p-497", "0x1.6d300a9ee500fp-497", "0x1.f0e76e1470a7dp-497",
         "0x1.f0810bdf41e8ep-497"],
        ["-0x1.b3ef83ec0b0dap-497", "0x1.6ce8614cb9622p-497", "0x1.f0810bdf41e8ep-497",
         "0x1.f02283a8873a6p-497"],
    ]
)  # fmt: skip
SINGULAR_S_X0 = _hex(
    [["0x1.26471b16bd076p+52", "-0x1.f9510abec6120p+50", "0x1.f3be05f485d63p+53",
      "0x1.831c8f6cfa73bp+53"]]
)[0]  # fmt: skip
SINGULAR_S_Z = _hex(
    [["0x1.d0fa5b6c1e7fdp+54", "-0x1.34f3fdf68cb61p+55", "-0x1.5d274d2cfa87ap+56",
      "-0x1.807a600405788p+55"]]
)[0]  # fmt: skip


def _exact_state(
    x0: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The exact x + P Hᵀ S⁻¹ y and the rounding scale |x| + |K| |y| of each state."""
    n, m = p.shape[0], h.shape[0]
    yf = [Fraction(v) for v in y.tolist()]
    _, _, gain = exact_gain(p, h, r)
    state = [Fraction(x0[i]) + sum(gain[i][a] * yf[a] for a in range(m)) for i in range(n)]
    scale = [
        abs(Fraction(x0[i])) + sum(abs(gain[i][a] * yf[a]) for a in range(m)) for i in range(n)
    ]
    return np.array([float(v) for v in state]), np.array([float(v) for v in scale])


def test_an_accepted_update_has_a_state_consistent_with_its_covariance() -> None:
    ekf = ExtendedKalmanFilter(SINGULAR_S_X0, SINGULAR_S_P)
    h = SINGULAR_S_H
    try:
        accepted = ekf.update(SINGULAR_S_Z, lambda x: h @ x, h, SINGULAR_S_R).accepted
    except FilterError:
        return  # as at 6f6c674: refused, the state unchanged
    assert accepted
    exact, scale = _exact_state(
        SINGULAR_S_X0, SINGULAR_S_P, h, SINGULAR_S_R, SINGULAR_S_Z - h @ SINGULAR_S_X0
    )
    posterior = _exact_posterior(SINGULAR_S_P, h, SINGULAR_S_R)
    # Within 3 standard deviations of the exact posterior, or of x's own rounding.
    allowed = 3.0 * np.sqrt(np.diag(posterior)) + 1e-12 * scale
    assert np.all(np.abs(ekf.x - exact) <= allowed)
