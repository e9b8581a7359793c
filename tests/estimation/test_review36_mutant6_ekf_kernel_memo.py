"""The EKF's kernels are compiled once per size, however many filters use them.

Mutation gap (MUTANT6): ``predict_kernel`` without its memo (``_PREDICT[n] =
kernel`` deleted) passed every test: each new filter built and loaded its
kernel again (from numba's cache, milliseconds a filter) and kept one more
dispatcher alive for good, a leak in a program that makes filters in a loop.
"""

from __future__ import annotations

import numpy as np

from navkit.estimation import ExtendedKalmanFilter, _ekf_kernels


def _use(n: int, m: int) -> None:
    ekf = ExtendedKalmanFilter(np.zeros(n), np.eye(n))
    ekf.predict(lambda x: x, np.eye(n), 0.1 * np.eye(n))
    ekf.update(np.zeros(m), lambda x: x[:m], np.eye(m, n), np.eye(m))


def test_new_filters_of_a_size_seen_compile_no_new_kernel() -> None:
    _use(3, 2)
    before = _ekf_kernels.kernel_dispatchers()
    for _ in range(4):
        _use(3, 2)
    after = _ekf_kernels.kernel_dispatchers()
    assert len(after) == len(before)
    assert all(a is b for a, b in zip(after, before, strict=True))


def test_the_kernel_entries_are_the_same_objects_on_every_request() -> None:
    assert _ekf_kernels.predict_kernel(4) is _ekf_kernels.predict_kernel(4)
    assert _ekf_kernels.update_kernel(4, 3) is _ekf_kernels.update_kernel(4, 3)
