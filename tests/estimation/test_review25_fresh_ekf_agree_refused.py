"""EKF fallback: an update whose two states "agree" but neither is trusted (review 25).

``finish_cancelled`` compares the kernel's state (solved with S) and the
information form's x⁺. "Agreeing" means within ``max(2⁻³³ (|x| + |x⁺ - x|),
sqrt(P⁺ᵢᵢ))``: where the posterior's deviation is far below 2⁻³³ of the
state's size, that says nothing. With S ill-conditioned (ε κ(S) 5.5 below),
x⁺'s error bound above the tolerance and the Joseph form failed, the kernel's x
was committed with the information form's P⁺, status OK: 8.7e5 posterior
deviations off the exact state (a filter that then gates every consistent
measurement). Where the states disagree, the same situation was already
refused ("no state to trust"); now it is refused here too, the filter unchanged.
Review 26: such an update now commits the exact state (x + P Hᵀ S⁻¹ y in rational
arithmetic, rounded once) with P⁺ instead of being refused.
The reference is exact rational arithmetic on the float inputs.
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update

# A position and a second state, the first measured twice alone and once in a
# combination with the second, each 1e-35 of the prior variance (found at random).
_X0 = np.array([-1.4026188864123863e01, 1.5255811655764508e04])
_P0 = np.array(
    [
        [1.2049910094707189e-01, 1.9259160683157251e01],
        [1.9259160683157251e01, 9.2791037993883856e03],
    ]
)
_H = np.array([[0.0, 3.0], [0.0, 1.0], [-0.10181809942646872, 1.4079534619791716]])
_R = np.diag([1.2203729906288603e-31, 2.3841632631325325e-31, 4.3288876575651042e-32])
_Z = np.array([45534.244603888, 15178.081534629333, 21371.431247573622])


def test_an_update_with_no_trusted_state_is_refused_not_committed_wrong() -> None:
    x_exact, p_exact, _ = exact_update(_X0, _P0, _H, _R, _Z - _H @ _X0)
    ekf = ExtendedKalmanFilter(_X0, _P0)
    try:
        result = ekf.update(_Z, lambda s: _H @ s, _H, _R)
    except FilterError:
        # Refused: the filter is as before.
        np.testing.assert_array_equal(ekf.x, _X0)
        np.testing.assert_array_equal(ekf.P, _P0)
        return
    # Accepted: then the state must be the exact one to within a fraction of the
    # committed posterior's deviation (it was 8.7e5 of them off).
    assert result.accepted
    for i in range(2):
        sigma = float(p_exact[i][i]) ** 0.5
        error = abs(float(x_exact[i] - Fraction(ekf.x[i])))
        size = abs(float(x_exact[i])) + abs(float(_X0[i]))
        assert error <= 0.25 * sigma + 4 * 2.0**-52 * size, (i, error / sigma)


@pytest.mark.parametrize("gate", [1e-300, None])
def test_the_gate_still_decides_first(gate: float | None) -> None:
    # The exact NIS's gate comes first, as where the states disagree: a measurement
    # the gate rejects is GATED (not an error), the filter unchanged. Without the
    # gate the update is applied with the exact state (review 26; it was refused).
    ekf = ExtendedKalmanFilter(_X0, _P0)
    if gate is None:
        assert ekf.update(_Z, lambda s: _H @ s, _H, _R).accepted
        x_exact, _, _ = exact_update(_X0, _P0, _H, _R, _Z - _H @ _X0)
        np.testing.assert_array_equal(ekf.x, [float(v) for v in x_exact])
        return
    result = ekf.update(_Z, lambda s: _H @ s, _H, _R, gate=gate)
    assert result.status.name == "GATED"
    np.testing.assert_array_equal(ekf.x, _X0)
    np.testing.assert_array_equal(ekf.P, _P0)
