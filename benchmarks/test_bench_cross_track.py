"""Cross-track distances of a run against its reference path (review 20, XT).

Run with ``python -m pytest benchmarks/test_bench_cross_track.py --benchmark-only``.

A 30,001-pose run along a 10,000-vertex reference path (a 1 km sine wave, the
poses within about half a metre of it), the workload of ``Metrics``'
cross-track error for a long run. Contestants, in the same run:

* ``plain``: ``point_polyline_distances``, every pose against every segment
  (what ``cross_track`` ran for every path before review 20; it still runs it
  for paths of at most ``SIMPLE_MAX_SEGMENTS`` segments);
* ``chunked``: ``point_polyline_distances_chunked`` with its boxes
  (``chunk_boxes``, included in the time), what ``cross_track`` runs for
  longer paths.

Both must return the same floats (``np.array_equal``). The ``chunked`` test's
``extra_info["speedup"]`` is the plain loop's median time over its own (the
plain loop timed once more if its test did not run first).
"""

from __future__ import annotations

import functools
import time
from typing import Any

import numpy as np
import pytest

from navkit.sim._polyline_distance_kernels import (
    chunk_boxes,
    point_polyline_distances,
    point_polyline_distances_chunked,
)

N_POINTS = 30_001
N_VERTICES = 10_000
_MEDIANS: dict[str, float] = {}


@functools.cache
def workload() -> tuple[np.ndarray, np.ndarray]:
    """(points, path): the poses of the run and the reference path."""
    rng = np.random.default_rng(0)
    s = np.linspace(0.0, 1000.0, N_VERTICES)
    path = np.column_stack([s, np.sin(s / 10.0)])
    points = np.column_stack([np.linspace(0.0, 1000.0, N_POINTS), rng.normal(0.0, 0.5, N_POINTS)])
    return points, path


def plain() -> np.ndarray:
    points, path = workload()
    out = np.empty(points.shape[0])
    point_polyline_distances(points, path, out)
    return out


def chunked() -> np.ndarray:
    points, path = workload()
    out = np.empty(points.shape[0])
    point_polyline_distances_chunked(points, path, chunk_boxes(path), out)
    return out


@pytest.mark.parametrize("who", ["plain", "chunked"])
def test_cross_track(benchmark: Any, who: str) -> None:
    call = plain if who == "plain" else chunked
    call()  # compiled (or loaded from the cache) outside the timing
    benchmark.group = "cross-track, 3e4 poses x 1e4-vertex path"
    # The plain loop takes seconds: three rounds.
    got = benchmark.pedantic(call, rounds=3, iterations=1) if who == "plain" else benchmark(call)
    if benchmark.stats is not None:  # None under --benchmark-disable
        _MEDIANS[who] = float(benchmark.stats.stats.median)
    if who == "chunked":
        assert np.array_equal(got, plain())
        if "plain" not in _MEDIANS:
            start = time.perf_counter()
            plain()
            _MEDIANS["plain"] = time.perf_counter() - start
        if "chunked" in _MEDIANS:
            benchmark.extra_info["speedup"] = round(_MEDIANS["plain"] / _MEDIANS["chunked"], 1)
