"""Acceptance bands for seeded noise statistics, and an estimator that logs readings.

Every band has the same two-sided false-alarm rate, ``FALSE_ALARM`` (1e-6):
a test at a fixed seed that passes once passes for good, and one whose model
is wrong by more than the band fails. Used by the simulator's noise tests.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2, norm

from navkit.sim import Reading

FALSE_ALARM = 1e-6
Z = float(norm.ppf(1 - FALSE_ALARM / 2))  # 4.89


class ReadingLog:
    """An :class:`~navkit.sim.Estimator` that keeps every reading with its delivery time."""

    pose = None

    def __init__(self) -> None:
        self.readings: list[Reading] = []
        self.delivered: list[float] = []

    def observe(self, t: float, reading: Reading) -> None:
        self.readings.append(reading)
        self.delivered.append(t)

    def of(self, kind: type) -> list[Reading]:
        """The readings of one type, in delivery order."""
        return [r for r in self.readings if isinstance(r, kind)]


def check_normal(sample: np.ndarray, mean: float, std: float) -> None:
    """``sample`` (normal) has the mean and standard deviation given, within the bands."""
    n = sample.size
    assert abs(sample.mean() - mean) < Z * std / math.sqrt(n), (sample.mean(), mean)
    lo, hi = chi2.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], n - 1) / (n - 1)
    ratio = sample.var(ddof=1) / std**2
    assert lo < ratio < hi, (ratio, lo, hi)


def check_spread(sample: np.ndarray, mean: float, std: float) -> None:
    """``sample`` (of any shape of distribution) has this mean and standard deviation.

    Large-sample bands: the mean within ``Z σ / √n``, the variance within
    ``Z √((m4 - s⁴) / n)`` of ``std²`` (``m4`` the sample's fourth central
    moment), which holds for a distribution that is not normal, where the
    chi-square band of :func:`check_normal` does not.
    """
    n = sample.size
    assert abs(sample.mean() - mean) < Z * std / math.sqrt(n), (sample.mean(), mean)
    centred = sample - sample.mean()
    var = float(np.mean(centred**2))
    m4 = float(np.mean(centred**4))
    assert abs(var - std**2) < Z * math.sqrt((m4 - var**2) / n), (math.sqrt(var), std)


def check_uncorrelated(a: np.ndarray, b: np.ndarray) -> None:
    """The correlation of ``a`` and ``b`` is within ``Z / √n`` of 0."""
    r = float(np.corrcoef(a, b)[0, 1])
    assert abs(r) < Z / math.sqrt(a.size), r
