"""Fusion batches of several threads at once, now that ``update_batch`` releases the GIL.

``PlanarFusion`` has state and serves one thread at a time; filters of their
own in several threads, fed one shared ``MeasurementLog`` at once, each end
bit-identical to a lone run.
"""

from __future__ import annotations

import numpy as np

from navkit.estimation import MeasurementLog, PlanarFusion
from thread_runs import concurrent_results


def test_filters_of_each_thread_fusing_one_log() -> None:
    rng = np.random.default_rng(0)
    t = np.arange(1, 4001) * 0.005
    log = MeasurementLog.from_streams(
        odometry=(t[::4], rng.normal(0.5, 0.01, t[::4].size), rng.normal(0.1, 0.01, t[::4].size)),
        yaw_rate=(t, rng.normal(0.1, 0.02, t.size)),
    )

    def fuse(i: int) -> tuple[bytes, bytes, bytes]:
        fusion = PlanarFusion(pose=(0.1 * i, 0.0, 0.0))
        res = fusion.update_batch(log)
        return (np.asarray(res.status).tobytes(), np.asarray(fusion.x).tobytes(),
                np.asarray(fusion.P).tobytes())  # fmt: skip

    calls = [lambda i=i: fuse(i) for i in range(4)]
    serial = [call() for call in calls]
    for results in concurrent_results(calls, rounds=3):
        assert results == serial
