"""diff-astar's scan localiser at a standing robot in the scenario's house (review 47).

The check that scans pull a wrong start back onto the robot's pose, once for
the centred LiDAR (``test_diff_astar``) and once for a mounted one (review 46's
mount tests): it was written out in both.
"""

from __future__ import annotations

import math

import numpy as np

from navkit.geometry import Pose2D
from navkit.sim import EncoderReading, Lidar, ScanReading


def assert_pulls_a_wrong_start_back(lidar: Lidar) -> None:
    """Scans by ``lidar`` correct a 10 cm, 3 degree error of the initial pose (20 matched)."""
    from navkit.sim.scenarios._diff_astar import DRIVE
    from navkit.sim.scenarios._diff_astar_localizer import ScanLocalizer
    from navkit.sim.scenarios._diff_astar_sites import site

    place = site("house")
    truth = Pose2D(-1.0, -4.0, 0.4)
    wrong = Pose2D(truth.x + 0.07, truth.y - 0.07, truth.theta + math.radians(3.0))
    loc = ScanLocalizer(place.field, DRIVE, lidar, ticks_per_rev=4096, bits=16, start=wrong)
    ticks = np.array([100, 200])
    for k in range(20):
        t = 0.1 * k
        loc.observe(t, ScanReading(t, lidar.scan(place.world, truth)))
        loc.observe(t, EncoderReading(t, ticks))
    est = loc.pose
    assert loc.matches == 20
    assert math.hypot(est.x - truth.x, est.y - truth.y) < 0.005, est
    assert abs(est.theta - truth.theta) < math.radians(0.2), est
