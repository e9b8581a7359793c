"""Scans whose ``angle_min`` varies from scan to scan (a jittering driver).

Every such scan misses the scan repulsion's table cache and builds the beam
directions again from :meth:`LaserScan.angles`, which skips ``wrap_angle``'s
checks and ``fmod`` where the angles allow. These tests hold the shortcut to
``wrap_angle``'s result bit for bit (properties over the whole accepted
range, and the edges of the fold), and the forces of jittering scans to those
computed with the directions built the former way. The time saved is in
``benchmarks/test_bench_review15_threads_scan_jitter.py``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.planning.reactive._scan_repulsion as scan_repulsion
from navkit.geometry import wrap_angle
from navkit.mapping import LaserScan
from navkit.planning import piecewise_repulsive_force_from_scan, repulsive_force_from_scan

TURN = 2.0 * math.pi


def _wrapped(scan: LaserScan) -> np.ndarray:
    """The beam angles as ``LaserScan.angles`` documents them, through ``wrap_angle``."""
    n = scan.ranges.shape[0]
    raw = scan.angle_min + scan.angle_increment * np.arange(n, dtype=np.float64)
    return np.asarray(wrap_angle(raw), dtype=np.float64)


def _scan(
    n: int, angle_min: float, increment: float, ranges: np.ndarray | None = None
) -> LaserScan:
    r = np.ones(n) if ranges is None else ranges
    return LaserScan(
        r, angle_min=angle_min, angle_increment=increment, range_min=0.05, range_max=10.0
    )


EDGES = [
    -math.pi,
    math.pi,
    float(np.nextafter(-math.pi, 0.0)),
    float(np.nextafter(-math.pi, -7.0)),
    float(np.nextafter(math.pi, 7.0)),
    float(np.nextafter(math.pi, 0.0)),
    -TURN,
    TURN,
    float(np.nextafter(-TURN, 0.0)),
    float(np.nextafter(TURN, 0.0)),
    -TURN - 5e-6,
    TURN + 5e-6,
    0.0,
    -0.0,
]


@pytest.mark.parametrize("angle_min", EDGES)
@pytest.mark.parametrize("beams", [1, 2, 360, 1441])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_angles_at_the_edges_of_the_fold_are_wrap_angles_bit_for_bit(
    angle_min: float, beams: int, sign: float
) -> None:
    for increment in (sign * TURN / beams, sign * 1e-3, sign * math.pi / max(beams - 1, 1)):
        try:
            scan = _scan(beams, angle_min, increment)
        except ValueError:  # beyond the accepted span or angles
            continue
        got = scan.angles()
        assert got.dtype == np.float64
        assert got.tobytes() == _wrapped(scan).tobytes()
        assert np.all(got > -math.pi) and np.all(got <= math.pi)


@settings(max_examples=300, deadline=None)
@given(
    beams=st.integers(1, 2000),
    angle_min=st.floats(-TURN - 1e-5, TURN + 1e-5),
    fraction=st.floats(1e-9, 1.0),
    sign=st.sampled_from([1.0, -1.0]),
)
def test_angles_are_wrap_angles_bit_for_bit(
    beams: int, angle_min: float, fraction: float, sign: float
) -> None:
    increment = sign * fraction * TURN / max(beams - 1, 1)
    try:
        scan = _scan(beams, angle_min, increment)
    except ValueError:  # beyond the accepted span or angles
        return
    first = scan.angles()
    assert first.tobytes() == _wrapped(scan).tobytes()
    second = scan.angles()
    assert second is not first and second.flags.writeable  # a new array every call
    second[0] = 99.0
    assert scan.angles().tobytes() == first.tobytes()


@pytest.fixture
def former_tables(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """Clear the repulsion's caches before and after (its tables are built anew)."""
    scan_repulsion._TABLES.clear()
    monkeypatch.setattr(scan_repulsion, "_LAST", (0.0, 0.0, 0, np.empty(0), np.empty(0)))
    yield
    scan_repulsion._TABLES.clear()


@pytest.mark.usefixtures("former_tables")
@pytest.mark.parametrize(("beams", "base"), [(360, -math.pi), (681, -2.0862), (1081, -2.35619)])
def test_jittering_scans_get_the_forces_of_directions_built_with_wrap_angle(
    beams: int, base: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(beams)
    increment = TURN / beams if base == -math.pi else -2.0 * base / (beams - 1)
    scans = [
        _scan(beams, base + float(rng.normal(0.0, 1e-6)), increment, rng.uniform(0.06, 3.0, beams))
        for _ in range(40)
    ]
    got = [
        (
            repulsive_force_from_scan(s, influence_radius=1.5).tobytes(),
            piecewise_repulsive_force_from_scan(s, obstacle_radius=0.2, spread=1.0).tobytes(),
        )
        for s in scans
    ]
    if base == -math.pi:  # some full-turn scans start below -π: the fold is exercised
        assert any(s.angle_min < -math.pi for s in scans)
        assert any(s.angle_min > -math.pi for s in scans)
    scan_repulsion._TABLES.clear()
    monkeypatch.setattr(scan_repulsion, "_LAST", (0.0, 0.0, 0, np.empty(0), np.empty(0)))
    monkeypatch.setattr(LaserScan, "angles", _wrapped)
    former = [
        (
            repulsive_force_from_scan(s, influence_radius=1.5).tobytes(),
            piecewise_repulsive_force_from_scan(s, obstacle_radius=0.2, spread=1.0).tobytes(),
        )
        for s in scans
    ]
    assert got == former
