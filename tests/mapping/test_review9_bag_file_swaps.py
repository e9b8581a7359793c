"""Bag readers read only regular files, also what rosbags opens after navkit's checks.

rosbags opens a ROS 1 bag (``path.open("rb")``), a ROS 2 bag's metadata.yaml
(``read_text()``) and its storage files by name, after navkit's own checks: a
FIFO swapped in between blocked the read for ever (no writer). navkit now hands
rosbags a path whose opens check the descriptor (``open_regular``), and reads
the bag's magic, chunks and records through checked descriptors too. (SQLite
storage files are opened by SQLite itself, by name: a documented limit.)
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("rosbags")

from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

from fifo_guard import unblocked
from file_swaps import swap_after_stats, to_fifo
from navkit.mapping.io import read_bag_scans

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")

SCAN = "sensor_msgs/msg/LaserScan"


def _scan(store: Any, ranges: list[float]) -> Any:
    t = store.types
    fields = {name for name, _ in store.fielddefs["std_msgs/msg/Header"][1]}
    extra = {"seq": 0} if "seq" in fields else {}
    header = t["std_msgs/msg/Header"](
        stamp=t["builtin_interfaces/msg/Time"](sec=1, nanosec=0), frame_id="laser", **extra
    )
    return t[SCAN](
        header=header, angle_min=0.0, angle_max=0.5 * (len(ranges) - 1), angle_increment=0.5,
        time_increment=0.0, scan_time=0.1, range_min=0.1, range_max=10.0,
        ranges=np.array(ranges, dtype=np.float32), intensities=np.array([], dtype=np.float32),
    )  # fmt: skip


def _bag1(path: Path) -> Path:
    store = get_typestore(Stores.ROS1_NOETIC)
    with Writer1(path) as writer:
        conn = writer.add_connection("/scan", SCAN, typestore=store)
        writer.write(conn, 1_000_000_000, store.serialize_ros1(_scan(store, [1.0, 2.0]), SCAN))
    return path


def _bag2(folder: Path) -> Path:
    store = get_typestore(Stores.ROS2_HUMBLE)
    with Writer2(folder, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/scan", SCAN, typestore=store)
        writer.write(conn, 1_000_000_000, store.serialize_cdr(_scan(store, [1.0, 2.0]), SCAN))
    return folder


@pytest.mark.parametrize("after", [1, 2, 3, 4])
def test_ros1_bag_swapped_for_a_fifo_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, after: int
) -> None:
    # Stats on the bag: navkit's exists(), is_dir(), is_file(), then rosbags'
    # exists() before it opens the file (the old code blocked after the 3rd and 4th).
    bag = _bag1(tmp_path / "b.bag")
    assert len(read_bag_scans(bag)) == 1
    swap_after_stats(monkeypatch, bag, after, to_fifo(bag))
    message = "is neither a ROS 1 bag file" if after < 3 else "is not a regular file"
    with pytest.raises(ValueError, match=f"{bag} {message}"):
        unblocked(lambda: read_bag_scans(bag), bag)


@pytest.mark.parametrize("name", ["metadata.yaml", "b2.mcap"])
def test_ros2_bag_file_swapped_for_a_fifo_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str
) -> None:
    folder = _bag2(tmp_path / "b2")
    assert len(read_bag_scans(folder)) == 1
    target = folder / name
    assert target.is_file()
    # The last stat before rosbags opens it: its exists() check of the file.
    stats = {"metadata.yaml": 2, "b2.mcap": 1}[name]
    swap_after_stats(monkeypatch, target, stats, to_fifo(target))
    with pytest.raises(ValueError, match=f"{folder}.*{target} is not a regular file"):
        unblocked(lambda: read_bag_scans(folder), target)
