"""An EKF whose state holds UTM coordinates rounds it at their size, as the guide says (review 54).

``ExtendedKalmanFilter`` is general: ``f`` and ``h`` are the caller's, and so is
the frame of the state. A state holding a UTM position (a northing of 5.1e6 m,
floats 9.3e-10 m apart) is rounded at that size by every ``f(x)`` and every
``x + K y``: steady steps drift it by up to half a spacing each, with one sign
(docs/guides/estimation.md, "The EKF": 5000 predictions of 1 mm moved it
1.9e-6 m from the same run at the origin). The guide's way out, a state in a
local frame with the offset added to the estimate, is the run at the origin
moved, to a spacing; and a measurement update at UTM, whose innovation
``z - h(x)`` is a difference of close floats (exact), is the update at the
origin to within a few spacings.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from navkit.estimation import ExtendedKalmanFilter

OFFSET = np.array([512345.25, 5123456.5, 0.0])
STEP = 0.001
YAW = 0.3
STEPS = 5000
SPACING = math.ulp(OFFSET[1])  # 9.3e-10 m


def _f(x: np.ndarray) -> np.ndarray:
    return np.array([x[0] + STEP * math.cos(x[2]), x[1] + STEP * math.sin(x[2]), x[2]])


def _jacobian(x: np.ndarray) -> np.ndarray:
    return np.array(
        [[1.0, 0.0, -STEP * math.sin(x[2])], [0.0, 1.0, STEP * math.cos(x[2])], [0.0, 0.0, 1.0]]
    )


Q = np.diag([1e-8, 1e-8, 1e-9])


def _dead_reckoning(start: np.ndarray) -> np.ndarray:
    ekf = ExtendedKalmanFilter(start, np.diag([1e-6, 1e-6, 1e-6]), angle_states=[2])
    for _ in range(STEPS):
        ekf.predict(_f, _jacobian, Q)
    return ekf.x


def test_steady_steps_at_utm_drift_by_up_to_half_a_spacing_each() -> None:
    origin = _dead_reckoning(np.array([0.0, 0.0, YAW]))
    far = _dead_reckoning(OFFSET + np.array([0.0, 0.0, YAW])) - OFFSET
    drift = float(np.abs(far[:2] - origin[:2]).max())
    # The guide's figure: 1.9e-6 m; never more than half a spacing a step.
    assert 1e-6 < drift <= STEPS * SPACING / 2
    assert far[2] == origin[2]


def _exact_end() -> list[Fraction]:
    """The dead-reckoned UTM position in exact arithmetic on the float steps ``_f`` adds."""
    dx = Fraction(STEP * math.cos(YAW))
    dy = Fraction(STEP * math.sin(YAW))
    return [Fraction(OFFSET[0]) + STEPS * dx, Fraction(OFFSET[1]) + STEPS * dy]


def test_the_local_frame_with_the_offset_added_last_is_exact_to_a_spacing() -> None:
    exact = _exact_end()
    local = _dead_reckoning(np.array([0.0, 0.0, YAW]))
    moved = local[:2] + OFFSET[:2]  # the guide's way out: the offset added last
    direct = _dead_reckoning(OFFSET + np.array([0.0, 0.0, YAW]))[:2]
    moved_error = max(abs(Fraction(float(v)) - e) for v, e in zip(moved, exact, strict=True))
    direct_error = max(abs(Fraction(float(v)) - e) for v, e in zip(direct, exact, strict=True))
    assert moved_error <= SPACING  # the local sums' rounding, then one rounding at UTM
    assert direct_error > 1000 * SPACING  # 1.9e-6 m: the steps rounded at UTM


def test_a_position_update_at_utm_is_the_update_at_the_origin() -> None:
    rng = np.random.default_rng(54)
    readings = rng.normal(0.0, 1.0, (200, 2))

    def run(offset: np.ndarray) -> np.ndarray:
        ekf = ExtendedKalmanFilter(offset + np.array([0.0, 0.0, YAW]), np.diag([100.0, 100.0, 1.0]))
        for z in readings:
            ekf.predict(_f, _jacobian, Q)
            ekf.update(z + offset[:2], lambda x: x[:2], np.eye(2, 3), np.eye(2))
        out: np.ndarray = ekf.x - offset
        return out

    origin = run(np.zeros(3))
    far = run(OFFSET)
    # Each step rounds the estimate once or twice at its size; the measurements pull
    # it back, so the difference stays within some spacings (measured: 1.15 of one).
    assert np.all(np.abs(far[:2] - origin[:2]) <= 20 * SPACING)
