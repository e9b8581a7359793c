"""wrap_angle and angle_diff fold arrays in place (review 28)."""

from __future__ import annotations

import math

import numpy as np

from memory_peak import peak_bytes
from navkit.geometry import angle_diff, wrap_angle


def _reference(a: np.ndarray) -> np.ndarray:
    rem = np.fmod(a, 2.0 * math.pi)
    return np.where(
        rem > math.pi, rem - 2.0 * math.pi, np.where(rem <= -math.pi, rem + 2.0 * math.pi, rem)
    )


def test_wrap_angle_and_angle_diff_peaks_are_bounded_by_their_input() -> None:
    # np.where's branches made the peak 4.3 times the input (wrap_angle) and 5.3
    # times (angle_diff); folded in place, 1.1 and 2.1.
    rng = np.random.default_rng(28)
    a = rng.normal(0.0, 100.0, 200_000)
    b = rng.normal(0.0, 100.0, 200_000)
    a[:6] = (math.pi, -math.pi, 3.0 * math.pi, -0.0, np.nextafter(-math.pi, 0.0), 1e300)
    given_a, given_b = a.copy(), b.copy()
    peak, wrapped = peak_bytes(lambda: wrap_angle(a))
    assert peak < 1.5 * a.nbytes, f"wrap_angle: peak {peak / 1e6:.1f} MB for {a.nbytes / 1e6} MB"
    peak, diff = peak_bytes(lambda: angle_diff(a, b))
    assert peak < 2.5 * a.nbytes, f"angle_diff: peak {peak / 1e6:.1f} MB for {a.nbytes / 1e6} MB"
    assert np.array_equal(a, given_a) and np.array_equal(b, given_b)
    ref = _reference(a)
    assert np.array_equal(wrapped, ref) and np.array_equal(np.signbit(wrapped), np.signbit(ref))
    assert np.array_equal(diff, _reference(a - b))
    assert wrapped[1] == math.pi and np.signbit(wrapped[3])
    assert wrap_angle(np.array(-math.pi)) == math.pi  # 0-d: a float, as before
    assert isinstance(wrap_angle(np.array(4.0)), float)
