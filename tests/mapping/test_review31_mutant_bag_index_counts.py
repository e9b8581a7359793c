"""A sound ROS 1 bag is read by rosbags, not sent to the chunk walker (review 31, mutants).

``_check_index`` compares each connection's message count from the index with the
sum of the chunk-info records' counts; a difference sends the bag to navkit's chunk
walker. The walker reads the same messages, so the existing tests (which compare
what is read) passed with the comparison broken in ways that flag every bag with
several connections, or with a connection without messages, as damaged:
``declared.get(0, conn_id)`` for ``declared.get(conn_id, 0)`` (all connections
compared with connection 0's count) and a default of 1 for a connection no chunk
lists. Here the walker is replaced by a failure, so a sound bag must pass the check.
Checked: each test fails on those mutants of ``_bags.py`` and passes on HEAD.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("rosbags")

from rosbags.rosbag1 import Writer as Writer1
from rosbags.typesys import Stores, get_typestore

from navkit.mapping.io import _bags, bag_topics

INT32 = "std_msgs/msg/Int32"
STORE1 = get_typestore(Stores.ROS1_NOETIC)


@pytest.fixture
def no_walker(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(bag_path: Path) -> Any:
        raise AssertionError(f"the chunk walker read the sound bag {bag_path}")

    monkeypatch.setattr(_bags, "_walk_ros1", refuse)


def _write(path: Path, counts: dict[str, int]) -> Path:
    int32 = STORE1.types[INT32]
    with Writer1(path) as writer:
        for topic, count in counts.items():
            conn = writer.add_connection(topic, INT32, typestore=STORE1)
            for i in range(count):
                writer.write(conn, 1_000_000 * (i + 1), STORE1.serialize_ros1(int32(data=i), INT32))
    return path


@pytest.mark.usefixtures("no_walker")
def test_connections_of_different_counts_pass_the_index_check(tmp_path: Path) -> None:
    path = _write(tmp_path / "three.bag", {"/a": 3, "/b": 4, "/c": 5})
    assert bag_topics(path) == {"/a": (INT32, 3), "/b": (INT32, 4), "/c": (INT32, 5)}


@pytest.mark.usefixtures("no_walker")
def test_a_connection_without_messages_passes_the_index_check(tmp_path: Path) -> None:
    # rosbags lists the empty connection (count 0); no chunk-info record names it.
    path = _write(tmp_path / "empty.bag", {"/a": 3, "/silent": 0})
    assert bag_topics(path) == {"/a": (INT32, 3), "/silent": (INT32, 0)}


@pytest.mark.usefixtures("no_walker")
def test_the_shared_sound_bags_pass_the_index_check(shared_data: Path) -> None:
    # The counts rosbags reads from the index (checked against its chunk-info records).
    folder = shared_data / "robot-localization-odom-imu-bags"
    topics = bag_topics(folder / "test1.bag")
    assert {name: entry[1] for name, entry in topics.items()} == {
        "/imu/data": 11865,
        "/husky_velocity_controller/odom": 3952,
        "/fix": 989,
    }
