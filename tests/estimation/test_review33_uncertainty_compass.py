"""CompassCalibration's yaw error: what its docstring now states about the latched reading.

The first reading becomes θ0, so its noise is in every yaw: each later yaw's
error is the difference of two readings' noise (variance 2σ²) and two yaws
share the first reading's (correlation 1/2). Monte Carlo over seeded
calibrations, with the 1e-6 chi-square band for the variance and the normal
band of Fisher's z for the correlation.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2, norm

from navkit.estimation import CompassCalibration

FALSE_ALARM = 1e-6


def test_latched_first_reading_doubles_the_variance_and_correlates_the_yaws() -> None:
    rng = np.random.default_rng(8)
    count, sigma_deg, heading = 4000, 2.0, 123.0
    errors = np.empty((count, 3))
    for i in range(count):
        cal = CompassCalibration()
        raw = heading + sigma_deg * rng.standard_normal(3)  # the robot standing still
        errors[i] = [cal(float(d)) for d in raw]  # the true yaw is 0
    assert np.all(errors[:, 0] == 0.0)
    sigma = math.radians(sigma_deg)
    lo, hi = chi2.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], count) / count
    for k in (1, 2):
        ratio = float(np.mean(errors[:, k] ** 2)) / (2 * sigma**2)
        assert lo < ratio < hi, ratio
    r = float(np.corrcoef(errors[:, 1], errors[:, 2])[0, 1])
    z = float(norm.ppf(1 - FALSE_ALARM / 2)) / math.sqrt(count - 3)
    assert math.tanh(math.atanh(0.5) - z) < r < math.tanh(math.atanh(0.5) + z), r
