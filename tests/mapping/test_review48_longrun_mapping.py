"""Long runs of the mapping layer: what 10^5 scans leave behind (review 48, LONGRUN).

A map updated for hours must stay able to change: the log-odds ``clamp`` bounds
how many contradicting scans a cell saturated by any number of hits needs to
flip (a door seen shut for hours, then open). Checked against a float32 replay
of the same additions (the grid stores float32), and for 10 and 10^4 hits alike
(10^5 in the slow test). A scan mapper fed one scan over and over from a robot
standing still must come to rest and stay there bit for bit, its map unwritten.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.types import FloatArray
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.mapping._logodds import DEFAULT_CLAMP, DEFAULT_HIT, DEFAULT_MISS, logit

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from room_scans import room_scan

_WALL = LaserScan([2.0], angle_min=0.0, angle_increment=0.1, range_min=0.05, range_max=3.0)
_OPEN = LaserScan([math.inf], angle_min=0.0, angle_increment=0.1, range_min=0.05, range_max=3.0)
_POSE = (0.05, 0.05, 0.0)
_HECTOR = (logit(0.9), logit(0.4), (-50.0, 50.0))
_OCTOMAP = (DEFAULT_HIT, DEFAULT_MISS, DEFAULT_CLAMP)


def _replay(start: float, step: float, stop: float, rising: bool) -> int:
    """Additions of ``step`` to ``start`` in float32 until past ``stop`` (an oracle)."""
    value, n = np.float32(start), 0
    while (value <= stop) if rising else (value >= stop):
        value = np.float32(value + np.float32(step))
        n += 1
    return n


def _saturated(
    model: tuple[float, float, tuple[float, float]], hits: int
) -> tuple[OccupancyGrid, tuple[int, int]]:
    """A grid whose wall cell (returned too) ``hits`` scans have hit."""
    hit, miss, clamp = model
    grid = OccupancyGrid(np.zeros((1, 40), dtype=np.float32), resolution=0.1)
    cell = tuple(grid.world_to_cell([2.05, 0.05]).tolist())
    for _ in range(hits):
        integrate_scan(grid, _WALL, _POSE, hit=hit, miss=miss, clamp=clamp)
    return grid, (cell[0], cell[1])


def _scans_until(grid: OccupancyGrid, cell: tuple[int, int], scan: LaserScan, free: bool,
                 model: tuple[float, float, tuple[float, float]]) -> int:  # fmt: skip
    """Scans of ``scan`` until ``cell`` is free (``free``) or occupied."""
    hit, miss, clamp = model
    n = 0
    while not (grid.free() if free else grid.occupied())[cell]:
        integrate_scan(grid, scan, _POSE, hit=hit, miss=miss, clamp=clamp)
        n += 1
        assert n <= 100_000
    return n


def _flips(model: tuple[float, float, tuple[float, float]], hits: int) -> tuple[float, int, int]:
    """The wall cell's log-odds after ``hits`` scans, then the scans to free, then to occupied."""
    grid, cell = _saturated(model, hits)
    saturated = float(grid.logodds[cell])
    to_free = _scans_until(grid, cell, _OPEN, True, model)
    # Down to the lower bound, then count the hits back up from there.
    hit, miss, clamp = model
    for _ in range(to_free * 10):
        integrate_scan(grid, _OPEN, _POSE, hit=hit, miss=miss, clamp=clamp)
    assert float(grid.logodds[cell]) == pytest.approx(clamp[0], abs=1e-5)
    return saturated, to_free, _scans_until(grid, cell, _WALL, False, model)


@pytest.mark.parametrize(
    ("model", "free", "occupied"),
    [(_OCTOMAP, 13, 4), (_HECTOR, 127, 24)],
    ids=["octomap", "hector"],
)
@pytest.mark.parametrize("hits", [200, 10_000])
def test_flip_counts_are_bounded_by_the_clamp(
    model: tuple[float, float, tuple[float, float]], free: int, occupied: int, hits: int
) -> None:
    hit, miss, (low, high) = model
    saturated, to_free, to_occupied = _flips(model, hits)
    assert saturated == pytest.approx(high, abs=1e-5)  # clamped, not hits * hit
    # The numbers the docstrings give, and a float32 replay's.
    assert to_free == free == _replay(high, miss, logit(0.196), rising=False)
    assert to_occupied == occupied == _replay(low, hit, logit(0.65), rising=True)


@pytest.mark.slow
def test_flip_count_after_a_hundred_thousand_hits() -> None:
    assert _flips(_OCTOMAP, 100_000)[1:] == _flips(_OCTOMAP, 10)[1:] == (13, 4)


def test_unclamped_flip_count_grows_with_the_hits() -> None:
    # What the clamp prevents: without it the memory of a cell grows with its hits.
    wide = (DEFAULT_HIT, DEFAULT_MISS, (-1e6, 1e6))
    counts = [_scans_until(*_saturated(wide, hits), _OPEN, True, wide) for hits in (100, 400)]
    assert counts[0] > 200
    assert counts[1] > 800


def _still(matcher: ScanMatcher | None, odometry: bool, scans: int) -> FloatArray:
    """Poses of a mapper fed one room scan ``scans`` times from a robot standing still."""
    scan = room_scan(0.31, 0.17, 0.1, half=3.0, beams=180)
    mapper = ScanMapper(pose=(0.31, 0.17, 0.1), matcher=matcher)
    for _ in range(scans):
        mapper.update(scan, (0.0, 0.0, 0.0) if odometry else None)
        if mapper.trajectory.shape[0] == 2:
            written = mapper.map.logodds.copy()
    # Standing still writes nothing after the first scan.
    np.testing.assert_array_equal(mapper.map.logodds, written)
    return mapper.trajectory


@pytest.mark.parametrize("odometry", [False, True], ids=["constant-velocity", "odometry"])
def test_mapper_standing_still_without_pull_stays_put_exactly(odometry: bool) -> None:
    poses = _still(ScanMatcher(), odometry, 300)
    # The first matches move the pose by the grid's discretisation (about 1.5 cm here).
    assert math.dist(poses[0, :2], poses[-1, :2]) < 0.03
    # Bit for bit with odometry (the guess is the last pose); from the constant-velocity
    # guess the last pose and the one before differ by an ulp or two, and so may the match.
    tolerance = 0.0 if odometry else 1e-12
    np.testing.assert_allclose(poses[100:], np.broadcast_to(poses[-1], poses[100:].shape),
                               rtol=0.0, atol=tolerance)  # fmt: skip


@pytest.mark.parametrize("odometry", [False, True], ids=["constant-velocity", "odometry"])
def test_mapper_standing_still_with_the_default_pull_does_not_drift(odometry: bool) -> None:
    # The default matcher's pull towards each guess keeps the pose moving within a
    # few millimetres (a cycle: 13 poses without odometry, 5 with it), documented
    # in ScanMapper's Notes; bounded, not a drift.
    poses = _still(None, odometry, 600)
    later = poses[100:]
    assert float(np.ptp(later[:, :2], axis=0).max()) < 0.01
    assert float(np.ptp(later[:, 2])) < 1e-3
    # No trend: the second half's mean is the first's.
    half = later.shape[0] // 2
    assert np.abs(later[:half].mean(axis=0) - later[half:].mean(axis=0)).max() < 1e-3


@pytest.mark.slow
def test_mapper_standing_still_for_five_thousand_scans_stays_in_its_band() -> None:
    poses = _still(None, True, 5000)
    band = np.ptp(poses[100:600], axis=0)
    np.testing.assert_array_equal(np.ptp(poses[100:], axis=0), band)


@pytest.mark.xfail(
    strict=True,
    reason="known (review 48): a coarse-to-fine match may end worse than its guess by the "
    "finest level's cost plus the pull; keeping the guess then would let the pose settle",
)
def test_mapper_standing_still_with_odometry_and_the_default_pull_settles() -> None:
    poses = _still(None, True, 300)
    np.testing.assert_array_equal(poses[100:], np.broadcast_to(poses[-1], poses[100:].shape))
