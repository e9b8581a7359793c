"""Valid bags pass review 30's message-count checks whole (review 31, FRESH).

Review 30 made a ROS 2 topic whose messages do not add up to the count in
``metadata.yaml`` an error (``_counted``), and sent a ROS 1 bag whose index
counts differ from its chunk-info counts to the chunk walker
(``_check_index``). Both compare sums over connections: these bags, valid and
common, have several connections or storage files per topic, and must be read
once, whole, without an error and (ROS 1) without the walker:

- ROS 2: a topic with two connections (two QoS profiles: two entries in
  ``metadata.yaml``), in both storage formats; a bag split over two storage
  files (one ``metadata.yaml`` counting both); zstd compression by file and by
  message; the topic chosen by the caller beside another one of the same type.
- ROS 1: a topic with two connections (two publishers), over many chunks,
  uncompressed, bz2 and lz4.

Checked (the functions patched in a separate process): with ``_with_bag``
declaring the first connection's count alone, both two-connection ROS 2 tests
fail ("declares 3 messages on '/scan' but 5 could be read"); with
``_check_index`` summing the first chunk-info record alone, every ROS 1 test
fails (the walker is used).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("rosbags")

import yaml
from rosbags.interfaces import (
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

import navkit.mapping.io._bags as bags
from navkit.mapping.io import read_bag_scans

SCAN = "sensor_msgs/msg/LaserScan"
STORE2 = get_typestore(Stores.ROS2_HUMBLE)
STORE1 = get_typestore(Stores.ROS1_NOETIC)
QOS = Qos(
    QosHistory.KEEP_LAST, 5, QosReliability.RELIABLE, QosDurability.VOLATILE, QosTime(0, 0),
    QosTime(0, 0), QosLiveliness.AUTOMATIC, QosTime(0, 0), False,
)  # fmt: skip


def _scan(store: Any, k: int) -> bytes:
    t = store.types
    fields = {name for name, _ in store.fielddefs["std_msgs/msg/Header"][1]}
    extra = {"seq": 0} if "seq" in fields else {}  # ROS 1 headers have a sequence number
    header = t["std_msgs/msg/Header"](
        stamp=t["builtin_interfaces/msg/Time"](sec=k, nanosec=0), frame_id="laser", **extra
    )
    msg = t[SCAN](
        header=header, angle_min=0.0, angle_max=0.5, angle_increment=0.5, time_increment=0.0,
        scan_time=0.1, range_min=0.1, range_max=10.0,
        ranges=np.array([1.0, float(k)], dtype=np.float32),
        intensities=np.array([], dtype=np.float32),
    )  # fmt: skip
    if store is STORE1:
        return bytes(store.serialize_ros1(msg, SCAN))
    return bytes(store.serialize_cdr(msg, SCAN))


def _assert_scans(path: Path, stamps: list[int], **kwargs: Any) -> None:
    scans = read_bag_scans(path, **kwargs)
    np.testing.assert_array_equal(scans.times, np.array(stamps, dtype=float))
    np.testing.assert_array_equal([s.ranges[1] for s in scans.scans], np.array(stamps, float))


@pytest.mark.parametrize(
    "plugin", [StoragePlugin.SQLITE3, StoragePlugin.MCAP], ids=lambda p: p.name
)
def test_ros2_topic_with_two_connections(tmp_path: Path, plugin: StoragePlugin) -> None:
    folder = tmp_path / "bag"
    with Writer2(folder, version=9, storage_plugin=plugin) as writer:
        first = writer.add_connection("/scan", SCAN, typestore=STORE2)
        second = writer.add_connection("/scan", SCAN, typestore=STORE2, offered_qos_profiles=[QOS])
        for k in range(1, 6):
            writer.write(first if k <= 3 else second, k * 10**9, _scan(STORE2, k))
    assert (folder / "metadata.yaml").read_text().count("name: /scan") == 2
    _assert_scans(folder, [1, 2, 3, 4, 5])


@pytest.mark.parametrize(
    "plugin", [StoragePlugin.SQLITE3, StoragePlugin.MCAP], ids=lambda p: p.name
)
def test_ros2_bag_split_over_two_files(tmp_path: Path, plugin: StoragePlugin) -> None:
    # What `ros2 bag record --max-bag-duration` leaves: one metadata.yaml, counts
    # over every file. Built from two one-file bags.
    parts = []
    for name, stamps in (("a", range(1, 4)), ("b", range(4, 6))):
        with Writer2(tmp_path / name, version=9, storage_plugin=plugin) as writer:
            conn = writer.add_connection("/scan", SCAN, typestore=STORE2)
            for k in stamps:
                writer.write(conn, k * 10**9, _scan(STORE2, k))
        meta = yaml.safe_load((tmp_path / name / "metadata.yaml").read_text())
        parts.append(meta["rosbag2_bagfile_information"])
    info = parts[0]
    second = parts[1]["relative_file_paths"][0]
    moved = "a_1" + second[second.index(".") :]
    shutil.move(tmp_path / "b" / second, tmp_path / "a" / moved)
    info["relative_file_paths"].append(moved)
    info["files"].append({**parts[1]["files"][0], "path": moved})
    info["message_count"] = 5
    info["topics_with_message_count"][0]["message_count"] = 5
    text = yaml.safe_dump({"rosbag2_bagfile_information": info})
    (tmp_path / "a" / "metadata.yaml").write_text(text)
    _assert_scans(tmp_path / "a", [1, 2, 3, 4, 5])


@pytest.mark.parametrize(
    "mode", [CompressionMode.FILE, CompressionMode.MESSAGE], ids=lambda m: m.name
)
def test_ros2_bag_compressed(tmp_path: Path, mode: CompressionMode) -> None:
    writer = Writer2(tmp_path / "bag", version=9)
    writer.set_compression(mode, CompressionFormat.ZSTD)
    with writer:
        conn = writer.add_connection("/scan", SCAN, typestore=STORE2)
        for k in range(1, 6):
            writer.write(conn, k * 10**9, _scan(STORE2, k))
    _assert_scans(tmp_path / "bag", [1, 2, 3, 4, 5])


def test_ros2_topic_chosen_beside_another(tmp_path: Path) -> None:
    with Writer2(tmp_path / "bag", version=9) as writer:
        scan = writer.add_connection("/scan", SCAN, typestore=STORE2)
        other = writer.add_connection("/scan2", SCAN, typestore=STORE2)
        for k in range(1, 8):
            writer.write(scan if k % 2 else other, k * 10**9, _scan(STORE2, k))
    _assert_scans(tmp_path / "bag", [1, 3, 5, 7], topic="/scan")
    _assert_scans(tmp_path / "bag", [2, 4, 6], topic="/scan2")


@pytest.mark.parametrize("compression", [None, "bz2", "lz4"])
def test_ros1_topic_with_two_connections_over_many_chunks(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, compression: str | None
) -> None:
    if compression == "lz4":
        pytest.importorskip("lz4")
    path = tmp_path / "two.bag"
    writer = Writer1(path)
    if compression is not None:
        writer.set_compression(getattr(Writer1.CompressionFormat, compression.upper()))
    writer.chunk_threshold = 300  # a few messages a chunk
    with writer:
        publishers = [
            writer.add_connection("/scan", SCAN, typestore=STORE1, callerid=caller)
            for caller in ("/a", "/b")
        ]
        other = writer.add_connection("/other", SCAN, typestore=STORE1, callerid="/c")
        for k in range(1, 31):
            conn = other if k % 5 == 0 else publishers[k % 2]
            writer.write(conn, k * 10**9, _scan(STORE1, k))

    def no_walk(bag_path: Path) -> Any:
        raise AssertionError(f"a valid bag went to the chunk walker: {bag_path}")

    monkeypatch.setattr(bags, "_walk_ros1", no_walk)
    _assert_scans(path, [k for k in range(1, 31) if k % 5], topic="/scan")
    # Many chunks, the topic's two connections in most of them.
    with bags._rosbags()[0].Reader(path) as reader:
        assert len(reader.chunk_infos) > 5
