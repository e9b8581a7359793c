"""Long runs of ScanMapper: what it keeps per scan, and a robot standing still does not drift.

What a long run keeps per scan (24 bytes of trajectory, nothing else) is tested in
test_review14_scan_mapper_trajectory.py.
"""

from __future__ import annotations

import numpy as np
from room_scans import room_scan

from navkit.mapping import ScanMapper


def test_a_robot_standing_still_converges_to_one_pose() -> None:
    """Scan after scan of the same room from the same place: the pose settles, no random walk."""
    mapper = ScanMapper(resolution=0.05)
    scan = room_scan(0.013, 0.021)
    for _ in range(40):
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    settled = mapper.pose.as_array()
    for _ in range(200):
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    np.testing.assert_allclose(mapper.pose.as_array(), settled, atol=1e-12)
    # Within half a cell of where it started (the grid's optimum, not the exact pose).
    assert float(np.hypot(*settled[:2])) < 0.025
