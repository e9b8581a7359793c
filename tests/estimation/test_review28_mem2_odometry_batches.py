"""The odometries' update_batch without full-size temporaries, the same poses (review 28).

DiffOdometry.update_batch peaked at 5.3 times its result (128 MB at 10⁶
readings), OmniOdometry.update_batch at 5.0: a second (T, 3) array besides the
steps and the temporaries of the heading sums and of the chained positions.
Now 2.7 and 3.3, bit for bit the same poses (the one-step equality with
``update`` is tested elsewhere).
"""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive, OmniDrive

N = 200_000


def test_diff_update_batch_peaks_under_three_and_a_half_times_its_result() -> None:
    rng = np.random.default_rng(28)
    left = np.cumsum(rng.integers(-5, 20, N))
    right = np.cumsum(rng.integers(-5, 20, N))
    drive = DiffDrive(track=0.5, wheel_radius=0.1)

    def run() -> np.ndarray:
        odo = DiffOdometry(drive, ticks_per_rev=1000, pose=Pose2D(5e6, 4e5, 3.0))
        return odo.update_batch(left, right)

    peak, out = peak_bytes(run)
    assert peak < 3.5 * out.nbytes, f"peak {peak / out.nbytes:.2f} times the result"


def test_omni_update_batch_peaks_under_four_and_a_quarter_times_its_result() -> None:
    rng = np.random.default_rng(28)
    increments = rng.normal(0.0, 0.1, (N, 3))
    yaws = np.cumsum(rng.normal(0.0, 0.05, N))
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)

    def run() -> np.ndarray:
        return OmniOdometry(drive, pose=Pose2D(5e6, 4e5, 3.0)).update_batch(increments, yaws)

    peak, out = peak_bytes(run)
    assert peak < 4.25 * out.nbytes, f"peak {peak / out.nbytes:.2f} times the result"


def test_batches_are_plain_running_sums_bit_for_bit_and_leave_inputs_alone() -> None:
    # From the origin the positions are the running sums of the rotated steps
    # (_chain's docstring): rebuilt here with plain NumPy, bit for bit.
    rng = np.random.default_rng(5)
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    increments = rng.normal(0.0, 0.1, (1_000, 3))
    yaws = rng.uniform(-10.0, 10.0, 1_000)
    kept = (increments.copy(), yaws.copy())
    out = OmniOdometry(drive).update_batch(increments, yaws)
    forward = drive.forward_matrix
    bx = increments[:, 0] * forward[0, 0]
    by = increments[:, 0] * forward[1, 0]
    for k in (1, 2):
        bx = bx + increments[:, k] * forward[0, k]
        by = by + increments[:, k] * forward[1, k]
    heading = np.fmod(yaws, 2 * np.pi)
    heading = np.where(heading > np.pi, heading - 2 * np.pi, heading)
    heading = np.where(heading <= -np.pi, heading + 2 * np.pi, heading)
    previous = np.concatenate(([0.0], heading[:-1]))
    turn = np.fmod(heading - previous, 2 * np.pi)
    turn = np.where(turn > np.pi, turn - 2 * np.pi, turn)
    turn = np.where(turn <= -np.pi, turn + 2 * np.pi, turn)
    mid = previous + 0.5 * turn
    c, s = np.cos(mid), np.sin(mid)
    x = np.cumsum(np.concatenate(([0.0], c * bx - s * by)))
    y = np.cumsum(np.concatenate(([0.0], s * bx + c * by)))
    assert out[:, 0].tobytes() == x.tobytes()
    assert out[:, 1].tobytes() == y.tobytes()
    assert out[1:, 2].tobytes() == heading.tobytes()
    np.testing.assert_array_equal(increments, kept[0])
    np.testing.assert_array_equal(yaws, kept[1])
