"""The drives' batch calls without full-size temporaries, the same bits (review 28).

At the peak, as multiples of the result: DiffDrive.forward_batch 2.0 -> 1.7,
DiffDrive.inverse_batch 2.0 -> 1.5 (np.column_stack of separate columns),
OmniDrive.saturate 3.4 -> 1.4 (unit, unit * limit and np.where).
"""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.kinematics import DiffDrive, OmniDrive

N = 200_000


def _rows(columns: int) -> np.ndarray:
    return np.random.default_rng(28).normal(0.0, 10.0, (N, columns))


def test_diff_forward_batch_peaks_under_1_85_times_its_result() -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    speeds = _rows(2)
    peak, out = peak_bytes(lambda: drive.forward_batch(speeds))
    assert peak < 1.85 * out.nbytes, f"peak {peak / out.nbytes:.2f} times the result"


def test_diff_inverse_batch_peaks_under_1_8_times_its_result() -> None:
    drive = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.051)
    twists = _rows(3)
    twists[:, 1] = 0.0
    peak, out = peak_bytes(lambda: drive.inverse_batch(twists))
    assert peak < 1.8 * out.nbytes, f"peak {peak / out.nbytes:.2f} times the result"
    # The formula of DiffDrive.inverse, bit for bit (tobytes: signs of zeros too).
    half = 0.5 * twists[:, 2] * drive.track
    expected = np.column_stack(
        ((twists[:, 0] - half) / drive.left_radius, (twists[:, 0] + half) / drive.right_radius)
    )
    assert out.tobytes() == expected.tobytes()


def test_omni_saturate_peaks_under_twice_its_result_and_leaves_its_input() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    speeds = _rows(3)
    speeds[::3] *= 0.01  # rows within the limit, returned as they are
    kept = speeds.copy()
    peak, out = peak_bytes(lambda: drive.saturate(speeds, max_wheel_speed=5.0))
    assert peak < 2.0 * out.nbytes, f"peak {peak / out.nbytes:.2f} times the result"
    np.testing.assert_array_equal(speeds, kept)
    fastest = np.max(np.abs(kept), axis=1, keepdims=True)
    over = fastest > 5.0
    expected = np.where(over, kept / np.where(over, fastest, 1.0) * 5.0, kept)
    assert out.tobytes() == expected.tobytes()
    assert not np.shares_memory(out, speeds)
