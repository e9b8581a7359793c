"""The mapping guide's figures for a noise-free replica of the aces building (review 54, FRESH3).

820b5c0 (review 53, SCANMATCH) wrote in the mapping guide that ``ScanMapper``
on noise-free scans of a replica of the aces building, at the log's corrected
poses and with them as odometry, "still drifts 0.24 m mean at 5 cm cells, 0.04
m at 2.5 cm, 0.46 m at 10 cm". The replica its own tests build (walls joining
neighbouring returns of every 5th scan, a 180-beam noise-free LiDAR) gives
0.40, 0.037 and 0.20 m, at 820b5c0 as today: the 5 cm and 10 cm figures were
not those of that replica, and 10 cm cells drift less than 5 cm ones, where the
guide had them drift more. As a drift per metre (the guide's own measure
since 974941c: over 10 m of corrected travel) 5 cm and 10 cm cells drift
alike, 0.38 % and 0.37 %, and 2.5 cm cells 0.10 %; the real scans 0.81 %,
0.97 % and 0.81 % (finer cells do not help them). Also measured: a real aces
scan matched from its corrected pose to the map of the scans before it lands
0.26 cell forward of that pose on the mean (the guide said 0.29), the
replica's 0.11 cell; in the mapper that bias leaves the replica 0.23 % long
along the track (the guide said 0.35 %). The guide now gives these figures;
this pins them.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.mapping.io import CarmenLog, read_carmen

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from aces_replica import replica_scans


@pytest.fixture(scope="module")
def aces(shared_data: Path) -> CarmenLog:
    return read_carmen(shared_data / "carmen-logs" / "aces-corrected.log.gz")


def _poses(log: CarmenLog) -> np.ndarray:
    return np.array([[p.x, p.y, p.theta] for p in log.laser_poses])


_replica = replica_scans  # the replica of review 53 (tests/aces_replica.py)


def _drift(log: CarmenLog, scans: list[LaserScan], resolution: float) -> tuple[float, float, float]:
    """A default mapper's mean distance (m) from the corrected poses, given them as
    odometry, its drift in % of the distance over 10 m of corrected travel, and the
    signed part of that drift along the track (%, positive: too far)."""
    truth = _poses(log)
    mapper = ScanMapper(pose=log.laser_poses[0], resolution=resolution)
    for scan, odometry in zip(scans, truth, strict=True):
        mapper.update(scan, odometry=odometry)
    est = np.asarray(mapper.trajectory)
    travel = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(truth[:, :2], axis=0).T))])
    errors, along = [], []
    for i in range(len(truth)):
        j = int(np.searchsorted(travel, travel[i] + 10.0))
        if j >= len(truth):
            break
        want = Pose2D(*truth[j]).relative_to(Pose2D(*truth[i]))
        got = Pose2D(*est[j]).relative_to(Pose2D(*est[i]))
        errors.append(math.hypot(got.x - want.x, got.y - want.y) / (travel[j] - travel[i]))
        length2 = want.x**2 + want.y**2
        along.append(((got.x - want.x) * want.x + (got.y - want.y) * want.y) / length2)
    mean = float(np.hypot(*(est[:, :2] - truth[:, :2]).T).mean())
    return mean, 100.0 * float(np.mean(errors)), 100.0 * float(np.mean(along))


def test_the_replicas_drift_by_cell_size(aces: CarmenLog) -> None:
    # Measured (mean m, % of distance): 5 cm 0.400, 0.375; 2.5 cm 0.037, 0.098;
    # 10 cm 0.202, 0.367 (820b5c0's guide: 0.24, 0.04 and 0.46 m). Along the track at
    # 5 cm: +0.23 % (the guide said 0.35 %): the matches' forward bias of 0.11 cell,
    # 5.7 mm a keyframe about 0.7 m apart (0.8 %), mostly cancels in the mapper.
    replica = _replica(aces)
    five, fine, ten = (_drift(aces, replica, r) for r in (0.05, 0.025, 0.1))
    assert 0.3 < five[0] < 0.5 and 0.3 < five[1] < 0.45, five
    assert fine[0] < 0.06 and fine[1] < 0.15, fine
    assert 0.15 < ten[0] < 0.3 and 0.3 < ten[1] < 0.45, ten
    assert ten[0] < five[0]  # the guide had 10 cm cells drift further
    assert 0.15 < five[2] < 0.3, five


def test_finer_cells_do_not_help_the_real_scans(aces: CarmenLog) -> None:
    # Measured: 0.81 % at 5 cm, 0.97 % at 2.5 cm, 0.81 % at 10 cm (0.745, 1.72, 0.737 m).
    scans = list(aces.scans)
    five, fine, ten = (_drift(aces, scans, r) for r in (0.05, 0.025, 0.1))
    assert 0.7 < five[1] < 0.9 and 0.7 < ten[1] < 0.9, (five, ten)
    assert fine[1] > five[1] and fine[0] > five[0], (fine, five)


def _forward(log: CarmenLog, scans: list[LaserScan]) -> float:
    """Mean forward offset (cells of 5 cm) of each scan matched from its corrected
    pose to the map of the scans before it at theirs (the default mapper's matcher)."""
    truth = _poses(log)
    lo = truth[:, :2].min(axis=0) - 32.0
    width, height = truth[:, :2].max(axis=0) + 32.0 - lo
    grid = OccupancyGrid.empty(width=width, height=height, resolution=0.05, origin=(*lo, 0.0))
    matcher = ScanMatcher(
        translation_weight=1.0, rotation_weight=1.0, search_distance=0.1, search_angle=0.1
    )
    forward = []
    for k, pose in enumerate(log.laser_poses):
        if k:
            found = matcher.match(matcher.pyramid(grid), scans[k], pose).pose
            forward.append(found.relative_to(pose).x / 0.05)
        integrate_scan(grid, scans[k], pose)
    return float(np.mean(forward))


@pytest.mark.slow
def test_the_forward_bias_of_the_real_and_the_replicas_scans(aces: CarmenLog) -> None:
    # Measured 0.259 cell (real scans; the guide said 0.29) and 0.115 (the replica).
    real = _forward(aces, list(aces.scans))
    replica = _forward(aces, _replica(aces))
    assert 0.22 < real < 0.28, real
    assert 0.09 < replica < 0.14, replica
