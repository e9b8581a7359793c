"""Exact LiDAR scans from inside a square room, for ScanMapper tests (shared helper)."""

from __future__ import annotations

import math

import numpy as np

from navkit.mapping import LaserScan


def room_scan(
    x: float, y: float, theta: float = 0.0, *, half: float = 4.0, beams: int = 180
) -> LaserScan:
    """A full-circle scan of ``beams`` beams from (x, y, theta) in the room |x|, |y| <= half."""
    a = np.linspace(-math.pi, math.pi, beams, endpoint=False) + theta
    c, s = np.cos(a), np.sin(a)
    with np.errstate(divide="ignore", over="ignore"):
        tx = np.where(c > 0, (half - x) / c, np.where(c < 0, (-half - x) / c, np.inf))
        ty = np.where(s > 0, (half - y) / s, np.where(s < 0, (-half - y) / s, np.inf))
    return LaserScan(
        np.minimum(tx, ty), angle_min=-math.pi, angle_increment=2 * math.pi / beams,
        range_min=0.1, range_max=10.0,
    )  # fmt: skip
