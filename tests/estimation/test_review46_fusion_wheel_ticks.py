"""DiffOdometry on the Husky's real motion, against dead reckoning written here (review 46).

robot_localization's test1 bag records the Husky's wheel odometry as twists
(v, ω) at 10 Hz, not encoder counts. Its 395 s drive (359 m at up to
1.02 m/s, turns of up to 0.54 rad/s) is turned into the counts of 16-bit
wheel encoders (10,000 a turn on 0.1651 m wheels 0.555 m apart, about a
Husky's: each counter wraps every 6.8 m of its wheel, 52 times over the run), and
``DiffOdometry`` integrates them. The reference is written here from the
textbook equations on the same integer counts (distances ``Δn · 2πr / N``;
heading change ``(d_r - d_l) / b``; the exact arc ``d sin(Δθ)/Δθ``,
``d (1 - cos Δθ)/Δθ``, the midpoint ``d cos(Δθ/2)``, ``d sin(Δθ/2)``, or the
first-order ``d, 0`` in the robot frame, rotated into the world), so it
checks the counter wrap-around, the tick scaling and each integration
scheme on a real velocity profile, every reading.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

import numpy as np
import pytest

from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive
from navkit.mapping.io import read_bag_odometry

pytest.importorskip("rosbags")

FOLDER = "robot-localization-odom-imu-bags"
TRACK, RADIUS, PER_TURN, BITS = 0.555, 0.1651, 10_000, 16


@pytest.fixture(scope="module")
def counts(shared_data: Path) -> tuple[np.ndarray, np.ndarray]:
    """Unwrapped cumulative counts of the left and right wheels at each odometry message."""
    path = shared_data / FOLDER / "test1.bag"
    if not path.is_file():
        pytest.skip(f"{path} is not available")
    odom = read_bag_odometry(path)
    dt = np.diff(odom.times)
    v, w = odom.twists[1:, 0], odom.twists[1:, 2]  # each the mean over the interval before it
    per_metre = PER_TURN / (2.0 * math.pi * RADIUS)
    left = np.concatenate(([0.0], np.cumsum((v - w * TRACK / 2.0) * dt))) * per_metre
    right = np.concatenate(([0.0], np.cumsum((v + w * TRACK / 2.0) * dt))) * per_metre
    return np.floor(left).astype(np.int64), np.floor(right).astype(np.int64)


def reference(left: np.ndarray, right: np.ndarray, method: str) -> np.ndarray:
    """Textbook dead reckoning from unwrapped counts; one pose per reading, the first the origin."""
    metres = 2.0 * math.pi * RADIUS / PER_TURN
    x = y = th = 0.0
    poses = [(0.0, 0.0, 0.0)]
    for dn_l, dn_r in zip(np.diff(left).tolist(), np.diff(right).tolist(), strict=True):
        d_l, d_r = dn_l * metres, dn_r * metres
        d, dth = (d_l + d_r) / 2.0, (d_r - d_l) / TRACK
        if method == "arc":
            fx, fy = (
                (d, 0.0) if dth == 0.0 else (d * math.sin(dth) / dth, d * (1 - math.cos(dth)) / dth)
            )
        elif method == "midpoint":
            fx, fy = d * math.cos(dth / 2.0), d * math.sin(dth / 2.0)
        else:
            fx, fy = d, 0.0
        x += math.cos(th) * fx - math.sin(th) * fy
        y += math.sin(th) * fx + math.cos(th) * fy
        th = math.remainder(th + dth, 2.0 * math.pi)
        poses.append((x, y, th))
    return np.array(poses)


def _close(poses: np.ndarray, ref: np.ndarray) -> None:
    np.testing.assert_allclose(poses[:, :2], ref[:, :2], rtol=0, atol=1e-9)
    turn = np.remainder(poses[:, 2] - ref[:, 2] + math.pi, 2.0 * math.pi) - math.pi
    assert np.max(np.abs(turn)) < 1e-11
    assert np.all((poses[:, 2] > -math.pi) & (poses[:, 2] <= math.pi))


@pytest.mark.parametrize("method", ["arc", "midpoint", "first_order"])
def test_wrapped_counters_on_the_husky_drive(
    counts: tuple[np.ndarray, np.ndarray], method: Literal["arc", "midpoint", "first_order"]
) -> None:
    left, right = counts
    wraps = int(max(np.ptp(left), np.ptp(right))) >> BITS
    assert wraps >= 50  # the counters do wrap, many times
    raw_l, raw_r = left % (1 << BITS), right % (1 << BITS)
    ref = reference(left, right, method)
    path = float(np.sum(np.hypot(*np.diff(ref[:, :2], axis=0).T)))
    assert path > 300.0
    drive = DiffDrive(track=TRACK, wheel_radius=RADIUS)
    batch = DiffOdometry(drive, ticks_per_rev=PER_TURN, bits=BITS, method=method)
    poses = batch.update_batch(raw_l, raw_r)
    _close(poses, ref)
    online = DiffOdometry(drive, ticks_per_rev=PER_TURN, bits=BITS, method=method)
    one_by_one = np.array(
        [online.update(int(a), int(b)).as_array() for a, b in zip(raw_l, raw_r, strict=True)]
    )
    _close(one_by_one, ref)
    # Read as counters that never wrap, each wrap is a jump of 2**16 counts (6.8 m of wheel).
    unwrapped = DiffOdometry(drive, ticks_per_rev=PER_TURN, method=method)
    jumped = unwrapped.update_batch(raw_l, raw_r)
    assert np.max(np.hypot(*(jumped[:, :2] - ref[:, :2]).T)) > 10.0
