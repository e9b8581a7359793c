"""MeasurementLog.from_streams peaks near twice its log, not four times (review 28).

The stream blocks stayed alive until the log was returned, and the log copied
the arrays its own ``np.where`` had just made: four streams of 10⁶ rows peaked
at 1264 MB for a 304 MB log.
"""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.estimation import MeasurementLog

N = 50_000


def _streams() -> dict[str, object]:
    rng = np.random.default_rng(28)
    t = np.sort(rng.uniform(0.0, 100.0, (4, N)), axis=1)
    return {
        "odometry": (t[0], rng.normal(size=N), rng.normal(size=N)),
        "yaw": (t[1], rng.uniform(-3.0, 3.0, N)),
        "yaw_rate": (t[2], rng.normal(size=N)),
        "acceleration": (t[3], rng.normal(size=N)),
        "yaw_variance": rng.uniform(1e-4, 1e-2, N),
    }


def _log_bytes(log: MeasurementLog) -> int:
    return log.times.nbytes + log.values.nbytes + log.variances.nbytes + log.observed.nbytes


def test_from_streams_peaks_near_twice_its_log() -> None:
    streams = _streams()
    peak, log = peak_bytes(lambda: MeasurementLog.from_streams(**streams))  # type: ignore[arg-type]
    size = _log_bytes(log)
    assert peak < 2.6 * size, f"peak {peak / 1e6:.1f} MB for a {size / 1e6:.1f} MB log"


def test_the_log_is_read_only_c_ordered_and_as_before() -> None:
    streams = _streams()
    log = MeasurementLog.from_streams(**streams)  # type: ignore[arg-type]
    for arr in (log.times, log.values, log.variances, log.observed):
        assert arr.flags.c_contiguous and not arr.flags.writeable
    # The same rows as a plain merge, stable at equal times.
    kinds = ("odometry", "yaw", "yaw_rate", "acceleration")
    times = np.concatenate([streams[k][0] for k in kinds])  # type: ignore[index]
    order = np.argsort(times, kind="stable")
    assert np.array_equal(log.times, times[order])
    yaw_rows = log.observed[:, 0]
    assert np.array_equal(np.sort(log.values[yaw_rows, 0]), np.sort(streams["yaw"][1]))  # type: ignore[index]


def test_a_fortran_ordered_log_is_stored_c_ordered() -> None:
    values = np.asfortranarray(np.ones((3, 4)))
    variances = np.asfortranarray(np.full((3, 4), 1e-3))
    observed = np.asfortranarray(np.ones((3, 4), dtype=bool))
    log = MeasurementLog([0.0, 1.0, 2.0], values, variances, observed)
    assert log.values.flags.c_contiguous and log.variances.flags.c_contiguous
    values[0, 0] = 5.0  # the caller's arrays are not the log's
    assert log.values[0, 0] == 1.0
