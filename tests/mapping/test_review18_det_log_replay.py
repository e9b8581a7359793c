"""Determinism of mapping on a real log: a replay gives the same bits, and so do saves.

A team replays a CARMEN log to compare with the live run: the same scans in the same
order must give the same trajectory and map, bit for bit, in the same process (no
state kept between mappers or matches), after a pickle round trip of the mapper
mid-log, and the same map files, byte for byte (no timestamps, no absolute paths).
"""

from __future__ import annotations

import pickle
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping import ScanMapper, ScanMatcher
from navkit.mapping.io import read_carmen, write_map

_SCANS = 60


@pytest.fixture(scope="module")
def log(shared_data: Path) -> Any:
    path = shared_data / "carmen-logs" / "intel-corrected.log.gz"
    if not path.is_file():
        pytest.skip(f"{path} is not available")
    return read_carmen(path)


def _mapper() -> ScanMapper:
    # A coarse matcher window keeps the replays quick; the matcher runs at every scan.
    return ScanMapper(resolution=0.1, matcher=ScanMatcher(levels=2))


def _replay(log: Any, mapper: ScanMapper, scans: range) -> list[bytes]:
    out = []
    for k in scans:
        result = mapper.update(log.scans[k], odometry=log.robot_poses[k])
        pose = result.pose
        out.append(np.array([pose.x, pose.y, pose.theta]).tobytes() + repr(result).encode())
    return out


def test_a_replay_gives_the_same_trajectory_and_map(log: Any) -> None:
    first, second = _mapper(), _mapper()
    poses_first = _replay(log, first, range(_SCANS))
    poses_second = _replay(log, second, range(_SCANS))
    assert poses_second == poses_first
    assert second.trajectory.tobytes() == first.trajectory.tobytes()
    assert second.map.logodds.tobytes() == first.map.logodds.tobytes()
    assert len(first.trajectory) > 1  # the mapper moved: the equality is about something
    assert pickle.dumps(second) == pickle.dumps(first)


def test_a_mapper_restored_mid_log_goes_on_as_the_original(log: Any) -> None:
    whole = _mapper()
    _replay(log, whole, range(_SCANS))
    half = _mapper()
    _replay(log, half, range(_SCANS // 2))
    restored = pickle.loads(pickle.dumps(half))
    _replay(log, restored, range(_SCANS // 2, _SCANS))
    assert restored.trajectory.tobytes() == whole.trajectory.tobytes()
    assert restored.map.logodds.tobytes() == whole.map.logodds.tobytes()


def test_the_same_map_saves_to_the_same_bytes_wherever_and_whenever(
    log: Any, tmp_path: Path
) -> None:
    mapper = _mapper()
    _replay(log, mapper, range(20))
    grid = mapper.map
    (tmp_path / "one").mkdir()
    (tmp_path / "two" / "deeper").mkdir(parents=True)
    for mode in ("trinary", "scale"):
        first = write_map(grid, tmp_path / "one" / f"m_{mode}.yaml", mode=mode)
        again = write_map(grid.copy(), tmp_path / "two" / "deeper" / f"m_{mode}.yaml", mode=mode)
        assert again.read_bytes() == first.read_bytes()
        assert again.with_suffix(".yaml").read_bytes() == first.with_suffix(".yaml").read_bytes()
        assert str(tmp_path) not in first.with_suffix(".yaml").read_text()
