"""diff-astar's ScanLocalizer weighs beams by the LiDAR's absolute noise too (review 49, FRESH).

``RangeNoise(absolute=)`` (review 49) gives a band's standard deviation as
``sigma[b] * r + absolute[b]``; the scenario's localiser built each beam's
variance from ``sigma`` alone (``floor**2 + (sigma * r)**2``), so a LiDAR whose
short range is specified in millimetres (the LDS-01's ±15 mm below 0.5 m,
``sigma`` 0 there) had those beams weighted as if exact but for ``floor``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

import navkit.sim.scenarios._diff_astar_localizer as localizer
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import EncoderReading, Lidar, RangeNoise, ScanReading, World
from navkit.sim.scenarios._diff_astar_kernels import match_scan

_FLOOR = 0.02


def _room() -> OccupancyGrid:
    occupied = np.zeros((60, 80), dtype=bool)
    occupied[[0, -1], :] = True
    occupied[:, [0, -1]] = True
    occupied[40:48, 55:70] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05)


def _variances(noise: RangeNoise, monkeypatch: pytest.MonkeyPatch) -> tuple[Any, Any]:
    """The ranges matched and the variances the localiser gave ``match_scan`` for them."""
    seen: list[np.ndarray] = []

    def spy(xs: Any, ys: Any, variance: np.ndarray, *rest: Any) -> Any:
        seen.append(variance.copy())
        return match_scan(xs, ys, variance, *rest)

    monkeypatch.setattr(localizer, "match_scan", spy)
    grid = _room()
    lidar = Lidar(noise=noise, n_beams=90)
    clean = Lidar(noise=None, n_beams=90)
    truth = Pose2D(0.7, 0.6, 0.3)
    loc = localizer.ScanLocalizer(
        localizer.LikelihoodField.from_grid(grid), DiffDrive(track=0.3, wheel_radius=0.05),
        lidar, ticks_per_rev=1024, bits=16, start=truth, floor=_FLOOR,
    )  # fmt: skip
    scan = clean.scan(World(grid=grid), truth)  # exact ranges: the bands are known
    loc.observe(0.0, EncoderReading(0.0, np.array([0, 0])))
    loc.observe(0.0, ScanReading(0.0, scan))
    loc.observe(0.0, EncoderReading(0.0, np.array([0, 0])))
    assert loc.matches == 1 and len(seen) == 1
    ranges = scan.ranges[scan.valid_mask()][:: loc._step]
    return ranges, seen[0]


def test_absolute_noise_weighs_the_beams(monkeypatch: pytest.MonkeyPatch) -> None:
    noise = RangeNoise(limits=(1.0, math.inf), sigma=(0.0, 0.05), absolute=(0.015, 0.004))
    ranges, variance = _variances(noise, monkeypatch)
    near = ranges < 1.0
    assert near.any() and (~near).any()
    sd = np.where(near, 0.015, 0.05 * ranges + 0.004)
    np.testing.assert_allclose(variance, _FLOOR**2 + sd**2, rtol=1e-12)


def test_relative_noise_alone_is_weighed_as_before(monkeypatch: pytest.MonkeyPatch) -> None:
    noise = RangeNoise(limits=(1.5, math.inf), sigma=(0.01, 0.03))
    ranges, variance = _variances(noise, monkeypatch)
    rel = np.where(ranges < 1.5, 0.01, 0.03)
    # Bit for bit the relative model's weights (the scenario's figures unchanged).
    np.testing.assert_array_equal(variance, _FLOOR**2 + (rel * ranges) ** 2)
