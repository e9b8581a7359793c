"""Damaged bags that lost messages without an error now fail or are read whole (review 30).

- ROS 1: a zeroed index data record made rosbags list fewer messages (2362 of
  test2.bag's 3060), silently. The chunk-info records still count them all: a
  difference now sends the bag to navkit's chunk walker, which reads the chunks.
- ROS 2: a storage file without checksums (an MCAP without chunk CRCs, as
  rosbags-convert writes) can lose messages without an error from rosbags; the
  count in metadata.yaml now tells.
- A seek past the largest file offset (a damaged ``index_pos``) escaped as a bare
  ``OSError: [Errno 22] Invalid argument`` naming no file.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("rosbags")

from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

from navkit.mapping.io import read_bag_odometry, read_bag_scans

RL = "robot-localization-odom-imu-bags"
SCAN = "sensor_msgs/msg/LaserScan"


def _damaged_copy(shared_data: Path, tmp_path: Path, edit: Any) -> Path:
    bag = tmp_path / "test2.bag"
    shutil.copyfile(shared_data / RL / "test2.bag", bag)
    data = bytearray(bag.read_bytes())
    edit(data)
    bag.write_bytes(bytes(data))
    return bag


def test_ros1_bag_with_a_zeroed_index_record_is_read_whole(
    shared_data: Path, tmp_path: Path
) -> None:
    whole = read_bag_odometry(shared_data / RL / "test2.bag")
    assert len(whole) == 3060

    def zero(data: bytearray) -> None:
        data[235196:239292] = bytes(4096)  # an index data record after a chunk

    got = read_bag_odometry(_damaged_copy(shared_data, tmp_path, zero))
    assert len(got) == len(whole)
    np.testing.assert_array_equal(got.times, whole.times)
    np.testing.assert_array_equal(got.poses, whole.poses)


def test_ros1_bag_whose_index_lies_past_any_offset_is_a_value_error(
    shared_data: Path, tmp_path: Path
) -> None:
    def far(data: bytearray) -> None:
        data[77] = 0x7D  # the top byte of the header's index_pos

    bag = _damaged_copy(shared_data, tmp_path, far)
    with pytest.raises(ValueError, match=re.escape(f"{bag}: cannot read the ROS 1 bag")):
        read_bag_odometry(bag)


def _scan(store: Any, k: int) -> Any:
    t = store.types
    header = t["std_msgs/msg/Header"](
        stamp=t["builtin_interfaces/msg/Time"](sec=k, nanosec=0), frame_id="laser"
    )
    return t[SCAN](
        header=header, angle_min=0.0, angle_max=0.5, angle_increment=0.5, time_increment=0.0,
        scan_time=0.1, range_min=0.1, range_max=10.0,
        ranges=np.array([1.0, 2.0], dtype=np.float32), intensities=np.array([], dtype=np.float32),
    )  # fmt: skip


def _bag2(folder: Path, count: int) -> Path:
    store = get_typestore(Stores.ROS2_HUMBLE)
    with Writer2(folder, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/scan", SCAN, typestore=store)
        for k in range(count):
            writer.write(conn, (k + 1) * 10**9, store.serialize_cdr(_scan(store, k + 1), SCAN))
    return folder


def _declare(folder: Path, count: int) -> None:
    meta = folder / "metadata.yaml"
    text = meta.read_text()
    topic = "  - message_count: 5\n    topic_metadata:"  # the topic's (not the file's or bag's)
    assert text.count(topic) == 1
    meta.write_text(text.replace(topic, topic.replace("5", str(count))))


def test_ros2_bag_intact_reads_every_message(tmp_path: Path) -> None:
    assert len(read_bag_scans(_bag2(tmp_path / "b", 5))) == 5


@pytest.mark.parametrize("declared", [7, 3])
def test_ros2_bag_whose_messages_do_not_match_its_metadata_is_refused(
    tmp_path: Path, declared: int
) -> None:
    folder = _bag2(tmp_path / "b", 5)
    _declare(folder, declared)
    with pytest.raises(
        ValueError,
        match=rf"cannot read the ROS 2 bag: metadata\.yaml declares {declared} messages on "
        r"'/scan' but 5 could be read: the bag is damaged, or its metadata\.yaml is stale",
    ):
        read_bag_scans(folder)
