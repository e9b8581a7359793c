"""Lidar beam angles follow navkit's angle convention: (-π, π], -π never.

A full-circle Lidar's first beam points backwards. ``Lidar.angles()`` returns
it as -π, while the LaserScan the same lidar produces gives that beam as +π
(``LaserScan.angles()`` wraps): the two beam-angle functions of one sensor
disagreed, and one broke the convention. Found in review 13 (angle lens);
``Lidar.angles`` now wraps (the kernels still cast the unwrapped directions, so
scans are unchanged bit for bit). ``angle_min`` is the ROS message field
(-π for full-circle scanners, as in ROS drivers) and is not checked here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import box

from navkit.sim import Lidar, World


@pytest.mark.parametrize("n_beams", [1, 4, 360])
def test_full_circle_beam_angles_are_wrapped(n_beams: int) -> None:
    lidar = Lidar(n_beams=n_beams, noise=None)
    angles = lidar.angles()
    assert np.all(angles > -math.pi) and np.all(angles <= math.pi)
    assert angles[0] == math.pi


def test_lidar_and_its_scans_give_the_same_beam_angles() -> None:
    lidar = Lidar(n_beams=8, noise=None)
    scan = lidar.scan(World(box(0.0, 0.0, 4.0, 3.0).exterior), (1.0, 1.0, 0.0))
    np.testing.assert_array_equal(lidar.angles(), scan.angles())
