"""Long runs of ScanMapper: what it keeps per scan, and a robot standing still does not drift.

What a long run keeps per scan (24 bytes of trajectory, nothing else) is tested in
test_review14_scan_mapper_trajectory.py.
"""

from __future__ import annotations

import math

import numpy as np

from navkit.mapping import LaserScan, ScanMapper

N_BEAMS = 180
ANGLES = np.linspace(-math.pi, math.pi, N_BEAMS, endpoint=False)


def _room_scan(x: float, y: float, half: float = 4.0) -> LaserScan:
    """A scan from (x, y), heading 0, inside the square room |x|, |y| <= half."""
    c, s = np.cos(ANGLES), np.sin(ANGLES)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, (half - x) / c, np.where(c < 0, (-half - x) / c, np.inf))
        ty = np.where(s > 0, (half - y) / s, np.where(s < 0, (-half - y) / s, np.inf))
    return LaserScan(
        np.minimum(tx, ty), angle_min=-math.pi, angle_increment=2 * math.pi / N_BEAMS,
        range_min=0.1, range_max=10.0,
    )  # fmt: skip


def test_a_robot_standing_still_converges_to_one_pose() -> None:
    """Scan after scan of the same room from the same place: the pose settles, no random walk."""
    mapper = ScanMapper(resolution=0.05)
    scan = _room_scan(0.013, 0.021)
    for _ in range(40):
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    settled = mapper.pose.as_array()
    for _ in range(200):
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    np.testing.assert_allclose(mapper.pose.as_array(), settled, atol=1e-12)
    # Within half a cell of where it started (the grid's optimum, not the exact pose).
    assert float(np.hypot(*settled[:2])) < 0.025
