"""The LiDAR's beam jitter and range limits have the distributions its docstring states.

``Lidar``: a beam cast off its nominal angle by a zero-mean Gaussian error of
standard deviation ``angle_jitter``; range noise by band, then REP 117 (a
reading below ``range_min`` reads ``-inf``, one at or beyond ``range_max``
``+inf``). The noise moves only what a beam found: a wall beyond
``range_max`` reads ``+inf`` whatever the noise, one just inside reads
``+inf`` with the probability that its noise carries it out (its finite
readings a truncated sample, biased short), and ``range_min`` has no such
edge. A dropout (NaN) takes any beam, one that found nothing too. Bands at
a 1e-6 false-alarm rate (``tests/noise_bands.py``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import binom, kstest, norm
from shapely.geometry import LineString

from navkit.sim import Lidar, RangeNoise, World

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from noise_bands import FALSE_ALARM, Z, check_normal

SIGMA = 0.05
NOISE = RangeNoise(limits=(math.inf,), sigma=(SIGMA,))


def wall_ahead(distance: float) -> World:
    """A wall across the x axis ``distance`` m ahead of the origin."""
    return World(LineString([(distance, -100.0), (distance, 100.0)]))


def beam_readings(lidar: Lidar, world: World, scans: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.concatenate(
        [lidar.scan(world, (0.0, 0.0, 0.0), seed=rng).ranges for _ in range(scans)]
    )


def check_count(count: int, n: int, p: float) -> None:
    lo, hi = binom.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], n, p)
    assert lo <= count <= hi, (count, n * p, lo, hi)


def test_beam_jitter_is_a_signed_zero_mean_normal_error() -> None:
    # A wall at 45° to the beam, 1 m from the sensor along its normal: a beam cast
    # at error e reads 1 / cos(e - π/4), so e = π/4 - arccos(1 / r), sign and all
    # (the wall straight ahead gives only |e|).
    world = World(LineString([(-50.0, 50.0 + math.sqrt(2.0)), (50.0, -50.0 + math.sqrt(2.0))]))
    jitter = 0.05
    lidar = Lidar(n_beams=1, fov=0.1, noise=None, range_max=50.0, angle_jitter=jitter)
    assert lidar.angles().tolist() == [0.0]
    ranges = beam_readings(lidar, world, 4000, seed=8)
    error = math.pi / 4 - np.arccos(1.0 / ranges)
    check_normal(error, 0.0, jitter)
    assert kstest(error / jitter, norm.cdf).pvalue > FALSE_ALARM


def test_a_wall_beyond_range_max_reads_no_return_whatever_the_noise() -> None:
    lidar = Lidar(n_beams=8, fov=0.1, range_max=12.0, noise=NOISE)
    readings = beam_readings(lidar, wall_ahead(12.05), 500, seed=9)  # 5 % noise: 11.45 to 12.65
    assert np.all(readings == math.inf)


def test_near_range_max_the_noise_carries_readings_out_and_the_rest_read_short() -> None:
    distance, range_max = 11.9, 12.0
    lidar = Lidar(n_beams=8, fov=0.1, range_max=range_max, noise=NOISE)
    readings = beam_readings(lidar, wall_ahead(distance), 2000, seed=10)
    edge = (range_max / distance - 1.0) / SIGMA  # the standard score that reaches range_max
    check_count(int(np.sum(readings == math.inf)), readings.size, float(norm.sf(edge)))
    finite = readings[np.isfinite(readings)]
    assert finite.max() < range_max
    # The finite readings: the noise truncated at range_max, below the distance on average.
    ratio = float(norm.pdf(edge) / norm.cdf(edge))
    mean = distance * (1.0 - SIGMA * ratio)
    std = distance * SIGMA * math.sqrt(1.0 - edge * ratio - ratio**2)
    assert abs(finite.mean() - mean) < Z * std / math.sqrt(finite.size), (finite.mean(), mean)
    assert finite.mean() < distance - 0.1 * SIGMA * distance


@pytest.mark.parametrize("distance", [0.14, 0.16])
def test_range_min_has_no_edge_for_the_noise(distance: float) -> None:
    lidar = Lidar(n_beams=8, fov=0.1, range_min=0.15, noise=NOISE)
    readings = beam_readings(lidar, wall_ahead(distance), 2000, seed=11)
    assert not np.any(readings == math.inf)
    # Too close (-inf) exactly when the noisy reading is below range_min, from either side.
    p_close = float(norm.cdf((0.15 / distance - 1.0) / SIGMA))
    check_count(int(np.sum(readings == -math.inf)), readings.size, p_close)
    finite = readings[np.isfinite(readings)]
    assert finite.min() >= 0.15


def test_dropouts_take_beams_that_found_nothing_too() -> None:
    lidar = Lidar(n_beams=90, noise=None, range_max=5.0, dropout=0.2)
    readings = beam_readings(lidar, wall_ahead(3.0), 200, seed=12)
    lidar_angles = np.tile(lidar.angles(), 200)
    nothing = np.abs(lidar_angles) >= math.pi / 2  # behind the sensor: no return
    assert 0 < nothing.sum() < nothing.size
    for found in (nothing, ~nothing):
        check_count(int(np.isnan(readings[found]).sum()), int(found.sum()), 0.2)
    kept = readings[nothing & ~np.isnan(readings)]
    assert np.all(kept == math.inf)
