"""Where a ScanMapper driven through a large site stops growing (review 34, long runs).

``ScanMapper`` grows its map up to ``OccupancyGrid.MAX_CELLS`` cells of the
finest level; nothing said what a scan beyond that does. The mapping guide now
says: the map stops growing, a scan whose guessed pose lies outside keeps that
guess (reason ``"guess outside the map"``) and writes only the cells inside. A
real map of 2**28 cells takes 1.4 GB, so the limit is lowered here for the run.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import box

import navkit.mapping._scan_mapper as scan_mapper_module
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, ScanMapper
from navkit.sim import Circle, Lidar, World

ROOT = Path(__file__).resolve().parents[2]
LENGTH = 40.0
WORLD = World(
    [box(-2.0, -2.0, LENGTH + 2.0, 2.0).exterior]
    + [Circle((float(x), 1.5 if int(x) % 4 else -1.5), 0.2) for x in np.arange(1.0, LENGTH, 2.0)]
)
LIDAR = Lidar(n_beams=180, noise=None, range_max=6.0)


def _guide() -> str:
    return " ".join((ROOT / "docs/guides/mapping.md").read_text(encoding="utf-8").split())


def _drive(mapper: ScanMapper) -> list[tuple[str, Pose2D, Pose2D]]:
    out = []
    for x in np.arange(0.0, LENGTH - 2.0, 0.5):
        odometry = Pose2D(float(x), 0.0, 0.0)
        result = mapper.update(LIDAR.scan(WORLD, odometry), odometry=odometry)
        out.append((result.reason, result.pose, odometry))
    return out


def test_the_guide_states_the_limit() -> None:
    cells = OccupancyGrid.MAX_CELLS
    assert cells == 2**28
    side = math.isqrt(cells) * 0.05
    assert round(side) == 819
    assert round(cells * 4 * 4 / 3 / 1e9, 1) == 1.4  # finest level and a third more, GB
    text = _guide()
    assert "up to `OccupancyGrid.MAX_CELLS` (2²⁸) cells of its finest level" in text
    assert "819 m square or a 1.6 km × 410 m strip (1.4 GB of levels)" in text
    assert '(`reason` `"guess outside the map"`' in text


def test_beyond_the_limit_the_map_stays_and_scans_keep_their_guess(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The first map, ±10 m at 5 cm, is 160,000 cells; it grows to at most 2**18.
    monkeypatch.setattr(scan_mapper_module, "MAX_CELLS", 2**18)
    mapper = ScanMapper(resolution=0.05)
    runs = _drive(mapper)
    grid = mapper.map
    assert grid.shape[0] * grid.shape[1] <= 2**18
    right = grid.origin.x + grid.shape[1] * grid.resolution
    assert right < LENGTH - 4.0  # the route leaves it
    inside = [r for r in runs if r[2].x < right - 1.0]
    outside = [r for r in runs if r[2].x >= right]
    assert inside and outside
    assert all(reason != "guess outside the map" for reason, _, _ in inside[1:])
    first = runs.index(outside[0])
    for k in range(first, len(runs)):
        reason, pose, odometry = runs[k]
        assert reason == "guess outside the map"
        # The guess kept: the last pose moved by the odometry increment.
        _, last, last_odometry = runs[k - 1]
        assert pose == last.compose(odometry.relative_to(last_odometry))
    # The mapping inside the map went on.
    assert np.count_nonzero(grid.logodds > 0.0) > 100


def test_under_the_limit_the_same_route_grows_the_map() -> None:
    mapper = ScanMapper(resolution=0.05)
    runs = _drive(mapper)
    assert mapper.map.shape[1] > 400
    assert all(reason != "guess outside the map" for reason, _, _ in runs)
