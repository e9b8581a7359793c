"""Scan repulsion when the scanner's ``angle_min`` varies from scan to scan (review 15).

Run with ``python -m pytest benchmarks/test_bench_scan_jitter.py
--benchmark-only``.

A driver that reports each scan's own start angle (1e-6 rad of jitter here)
misses the beam-table cache at every call, which then builds the directions
again (:meth:`LaserScan.angles`, ``cos``, ``sin``). Peers in one run:

* ``fixed``: the same scanner every call (cache hit), the floor;
* ``jitter``: a new ``angle_min`` every call (a 360° scan crossing -π, whose
  angles need the fold by 2π, and a 270° Hokuyo-like one, which does not);
* ``jitter_wrap_angle``: the same with the angles built through
  ``wrap_angle`` as before review 15 (checks and ``fmod`` on every call).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterator

import numpy as np
import pytest

from navkit.geometry import wrap_angle
from navkit.mapping import LaserScan
from navkit.planning import repulsive_force_from_scan

SCANNERS = {"360": (360, -math.pi, 2.0 * math.pi / 360), "681": (681, -2.0862, 0.0061359)}


def _scans(name: str, jitter: float) -> list[LaserScan]:
    n, start, increment = SCANNERS[name]
    rng = np.random.default_rng(0)
    ranges = rng.uniform(0.2, 5.0, n)
    return [
        LaserScan(
            ranges,
            angle_min=start + float(rng.normal(0.0, jitter)),
            angle_increment=increment,
            range_min=0.1,
            range_max=10.0,
        )
        for _ in range(512)
    ]


def _former_angles(scan: LaserScan) -> np.ndarray:
    raw = scan.angle_min + scan.angle_increment * np.arange(len(scan), dtype=np.float64)
    return np.asarray(wrap_angle(raw), dtype=np.float64)


def _caller(scans: list[LaserScan]) -> Callable[[], object]:
    cycle: Iterator[LaserScan] = itertools.cycle(scans)
    return lambda: repulsive_force_from_scan(next(cycle), influence_radius=1.0)


@pytest.mark.parametrize("scanner", sorted(SCANNERS))
def test_fixed(benchmark, scanner: str) -> None:  # type: ignore[no-untyped-def]
    benchmark.group = f"jitter-{scanner}"
    benchmark(_caller(_scans(scanner, 0.0)))


@pytest.mark.parametrize("scanner", sorted(SCANNERS))
def test_jitter(benchmark, scanner: str) -> None:  # type: ignore[no-untyped-def]
    benchmark.group = f"jitter-{scanner}"
    benchmark(_caller(_scans(scanner, 1e-6)))


@pytest.mark.parametrize("scanner", sorted(SCANNERS))
def test_jitter_wrap_angle(benchmark, scanner: str, monkeypatch: pytest.MonkeyPatch) -> None:  # type: ignore[no-untyped-def]
    benchmark.group = f"jitter-{scanner}"
    monkeypatch.setattr(LaserScan, "angles", _former_angles)
    benchmark(_caller(_scans(scanner, 1e-6)))
