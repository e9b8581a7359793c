"""Old ExtendedKalmanFilter states: angle states kept, one without P refused (review 52, MUTANT32).

The lead's migration of filters pickled before their estimate lived in one
array (e8c9f20) was tested on pickles without angle states and on states
holding neither ``_x`` nor ``_p``: mutants dropping the old ``_angles`` and
refusing only a state lacking both passed (the second raised ``KeyError``
for a state holding ``_x`` alone).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter


def _loaded(slots: dict[str, Any]) -> ExtendedKalmanFilter:
    ekf = ExtendedKalmanFilter.__new__(ExtendedKalmanFilter)
    ekf.__setstate__((None, slots))
    return ekf


def test_an_old_state_with_angle_states_wraps_as_a_filter_built_today() -> None:
    x = np.array([1.0, 2.0, 3.1])
    old = _loaded({"_x": x.copy(), "_p": np.eye(3), "_angles": (2,), "_n": 3, "_validated": {}})
    fresh = ExtendedKalmanFilter(x.copy(), np.eye(3), angle_states=(2,))
    assert old.angle_states == fresh.angle_states == (2,)
    for ekf in (old, fresh):
        ekf.predict(lambda s: s + np.array([0.0, 0.0, 0.2]), np.eye(3), 1e-3 * np.eye(3))
    assert -math.pi < old.x[2] <= math.pi
    np.testing.assert_array_equal(old.x, fresh.x)
    np.testing.assert_array_equal(old.P, fresh.P)


@pytest.mark.parametrize("held", ["_x", "_p"])
def test_a_state_missing_its_x_or_p_is_refused(held: str) -> None:
    with pytest.raises(ValueError, match="holds no estimate"):
        _loaded({held: np.eye(3) if held == "_p" else np.zeros(3)})
