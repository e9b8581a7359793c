"""Review 47 (FRESH): the bag readers' two ROS 1 paths give one answer, and a
ROS 2 bag's declared count.

Review 47 made the ROS 1 chunk walker (the path of bags whose index rosbags
refuses) stream a topic chunk by chunk when the bag's messages are in
record-time order and gather and sort them otherwise, and the odometry and IMU
readers gather their rows in one block of the count the bag declares. Here:

* every stream of every real bag in the shared data reads the same, array for
  array, through the walker as through rosbags (the walker forced by refusing
  the index check that sends a damaged bag to it);
* a bag written out of record-time order (shuffled times over many small
  chunks, two topics in opposite orders, equal record times in two chunks)
  reads the same through both, and from a read-only file;
* a ROS 2 bag whose ``metadata.yaml`` declares more messages than it holds is
  the documented ``ValueError`` naming the bag, however many it declares;
* a bag rewritten in place between the walker's two passes, its size and time
  stamps kept, is refused, not handed out of record-time order (BAGFIX).
"""

from __future__ import annotations

import os
import random
import re
import stat
import struct
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import navkit.mapping.io._bags as bags
from navkit.mapping.io import bag_topics, read_bag_imu, read_bag_odometry, read_bag_scans

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

STORE1 = get_typestore(Stores.ROS1_NOETIC)
STORE2 = get_typestore(Stores.ROS2_HUMBLE)
IMU = "sensor_msgs/msg/Imu"
READERS: dict[str, Callable[..., Any]] = {
    "nav_msgs/msg/Odometry": read_bag_odometry,
    IMU: read_bag_imu,
    "sensor_msgs/msg/LaserScan": read_bag_scans,
}


def _arrays(result: Any) -> dict[str, Any]:
    """A reader's result as plain values: its arrays, its scans' ranges, its texts."""
    out: dict[str, Any] = {}
    for name in dir(result):
        if name.startswith("_"):
            continue
        value = getattr(result, name)
        if isinstance(value, (np.ndarray, str)):
            out[name] = value
        elif name == "scans":
            out[name] = [(s.ranges, s.angle_min, s.angle_increment) for s in value]
    return out


def _same(a: dict[str, Any], b: dict[str, Any]) -> None:
    assert a.keys() == b.keys()
    for name, value in a.items():
        if isinstance(value, np.ndarray):
            assert value.dtype == b[name].dtype, name
            np.testing.assert_array_equal(value, b[name], err_msg=name, strict=True)
        elif name == "scans":
            assert len(value) == len(b[name])
            for (r1, a1, i1), (r2, a2, i2) in zip(value, b[name], strict=True):
                np.testing.assert_array_equal(r1, r2, strict=True)
                assert (a1, i1) == (a2, i2)
        else:
            assert value == b[name], name


def _streams(path: Path) -> list[tuple[str, str]]:
    out = []
    for topic, entry in bag_topics(path).items():
        for msgtype, _ in entry if isinstance(entry[0], tuple) else (entry,):
            if msgtype in READERS:
                out.append((topic, msgtype))
    return out


def _read_all(path: Path) -> dict[tuple[str, str], dict[str, Any]]:
    return {
        (topic, msgtype): _arrays(READERS[msgtype](path, topic=topic))
        for topic, msgtype in _streams(path)
    }


REAL_BAGS = [
    "robot-localization-odom-imu-bags/test1.bag",
    "robot-localization-odom-imu-bags/test2.bag",
    "rosbag-hokuyo-laserscan-demo/demo.bag",
]


@pytest.mark.parametrize("name", REAL_BAGS)
def test_every_stream_of_a_real_bag_reads_the_same_through_the_walker(
    shared_data: Path, name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = shared_data / name
    direct = _read_all(path)
    assert direct  # odometry, IMU or scans: something to compare
    monkeypatch.setattr(bags, "_check_index", _refuse)
    walks = _count_walks(monkeypatch)
    through_walker = _read_all(path)
    assert walks == [path] * (len(direct) + 1)  # bag_topics, then each stream
    assert through_walker.keys() == direct.keys()
    for key, arrays in direct.items():
        _same(arrays, through_walker[key])


def _refuse(reader: Any) -> None:
    """Send every ROS 1 bag to the chunk walker, as a bag whose index counts disagree."""
    raise bags._RosbagsFailed("sent to the walker by the test")


def _count_walks(monkeypatch: pytest.MonkeyPatch) -> list[Path]:
    """The bags the walker will read, in order (a list filled as it is called)."""
    walks: list[Path] = []
    walk = bags._walk_ros1

    def counted(path: Path) -> Any:
        walks.append(Path(path))
        return walk(path)

    monkeypatch.setattr(bags, "_walk_ros1", counted)
    return walks


def _vector(z: float) -> Any:
    return STORE1.types["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=z)


def _imu(store: Any, k: int) -> Any:
    t = store.types
    eye = np.eye(3).ravel()
    header = {"stamp": t["builtin_interfaces/msg/Time"](sec=k, nanosec=0), "frame_id": "imu"}
    if store is STORE1:
        header["seq"] = k
    return t[IMU](
        header=t["std_msgs/msg/Header"](**header),
        orientation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        orientation_covariance=eye,
        angular_velocity=_vector(0.1 * k),
        angular_velocity_covariance=eye,
        linear_acceleration=_vector(9.8),
        linear_acceleration_covariance=eye,
    )


def _shuffled_bag(path: Path) -> Path:
    """Two IMU topics over many small chunks, recorded out of time order: ``/a`` at
    shuffled times, ``/b`` at the reverse of them, then two ``/a`` messages of one
    record time (in two chunks: kept in file order)."""
    times = list(range(1, 200))
    random.Random(4747).shuffle(times)
    with Writer(path) as writer:
        writer.chunk_threshold = 2000  # a few messages a chunk
        a = writer.add_connection("/a", IMU, typestore=STORE1)
        b = writer.add_connection("/b", IMU, typestore=STORE1)
        for t in times:
            writer.write(a, t * 10**9, STORE1.serialize_ros1(_imu(STORE1, t), IMU))
            writer.write(b, (200 - t) * 10**9, STORE1.serialize_ros1(_imu(STORE1, 1000 + t), IMU))
        for k in (500, 501):
            writer.write(a, 50 * 10**9, STORE1.serialize_ros1(_imu(STORE1, k), IMU))
    return path


def test_a_bag_out_of_time_order_reads_the_same_through_the_walker(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = _shuffled_bag(tmp_path / "shuffled.bag")
    assert len(bags._walk_ros1(path).counts) == 2
    direct = {topic: _arrays(read_bag_imu(path, topic=topic)) for topic in ("/a", "/b")}
    for topic in ("/a", "/b"):
        assert np.all(np.diff(direct[topic]["record_times"]) >= 0.0)
    # The two messages of one record time in the order written (stamps 500, 501 s).
    at_50 = direct["/a"]["times"][direct["/a"]["record_times"] == 50.0]
    np.testing.assert_array_equal(at_50, [50.0, 500.0, 501.0])
    monkeypatch.setattr(bags, "_check_index", _refuse)
    walks = _count_walks(monkeypatch)
    os.chmod(path, stat.S_IRUSR)  # read-only: the walker opens it twice, to read only
    for topic in ("/a", "/b"):
        _same(direct[topic], _arrays(read_bag_imu(path, topic=topic)))
    assert walks == [path, path]


def _ros2_imu_bag(folder: Path, count: int, declared: int) -> Path:
    with Writer2(folder, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE2)
        for k in range(1, count + 1):
            writer.write(conn, k * 10**9, STORE2.serialize_cdr(_imu(STORE2, k), IMU))
    meta = folder / "metadata.yaml"
    text = meta.read_text()
    entry = f"  - message_count: {count}\n    topic_metadata:"
    assert text.count(entry) == 1
    meta.write_text(text.replace(entry, entry.replace(str(count), str(declared))))
    return folder


def test_a_ros2_bag_declaring_a_few_more_messages_is_refused(tmp_path: Path) -> None:
    folder = _ros2_imu_bag(tmp_path / "bag", 3, 7)
    with pytest.raises(ValueError, match=re.escape(f"{folder}: cannot read the ROS 2 bag")):
        read_bag_imu(folder)


@pytest.mark.parametrize("declared", [10**12, 10**17])
def test_a_ros2_bag_declaring_absurdly_many_messages_is_the_documented_error(
    tmp_path: Path, declared: int
) -> None:
    # Review 47's one block of the declared count: 10**12 IMU rows are 284 TiB
    # (MemoryError), 10**17 more than an array may hold (NumPy's ValueError, naming
    # no bag: the match below fails, AssertionError). Before, the rows grew from 64
    # and the bag was refused as with 7 declared above; now the block is no larger
    # than the bag's files could fill (BAGFIX).
    folder = _ros2_imu_bag(tmp_path / "bag", 3, declared)
    with pytest.raises(ValueError, match=re.escape(f"{folder}: cannot read the ROS 2 bag")):
        read_bag_imu(folder)


def _row_blocks(monkeypatch: pytest.MonkeyPatch, width: int) -> list[tuple[int, ...]]:
    """The shapes of the ``(n, width)`` float64 blocks np.empty allocates from now on."""
    shapes: list[tuple[int, ...]] = []
    empty = np.empty

    def spied(shape: Any, *args: Any, **kwargs: Any) -> Any:
        if isinstance(shape, tuple) and len(shape) == 2 and shape[1] == width:
            shapes.append(shape)
        return empty(shape, *args, **kwargs)

    monkeypatch.setattr(np, "empty", spied)
    return shapes


@pytest.mark.parametrize("declared", [300, 10**12])
def test_a_ros2_bags_rows_are_one_block_of_its_count_as_far_as_its_files_allow(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, declared: int
) -> None:
    # An uncompressed bag (as rosbags writes MCAP by default) of 300 IMU messages: the
    # declared count is one block; an absurd one, a block no larger than its files.
    folder = _ros2_imu_bag(tmp_path / "bag", 300, declared)
    stored = sum(f.stat().st_size for f in folder.iterdir())
    blocks = _row_blocks(monkeypatch, 39)
    if declared == 300:
        assert len(read_bag_imu(folder)) == 300
        assert blocks == [(300, 39)]
        return
    with pytest.raises(ValueError, match=re.escape("declares 1000000000000 messages")):
        read_bag_imu(folder)
    # The first block: the 300 messages fit (no doubling for an uncompressed bag), and
    # it is no larger than the files.
    assert blocks[0][0] >= 300 and blocks[0][0] * 39 * 8 <= stored, (blocks, stored)


def test_a_bag_rewritten_between_the_passes_with_its_time_stamp_kept_is_not_read_unsorted(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Where the modification time has a coarse resolution (1 s on ext3 and HFS+, 2 s
    # on FAT), or a tool puts it back, a same-size rewrite between the walker's two
    # passes keeps the bag's identity (device, inode, size, mtime). Swapping the
    # first two messages' record times so made the walker, which found the bag in
    # time order on its first pass, hand them out as 2 s, 1 s, 3 s, ...: neither
    # the record-time order it promises nor a refusal.
    path, data = _ordered_bag_and_its_rewrite(tmp_path / "rewritten.bag")
    walk = bags._walk_ros1

    def rewritten_after_the_first_pass(bag_path: Path) -> Any:
        bag = walk(bag_path)
        kept = os.stat(bag_path)
        with open(bag_path, "r+b") as fh:
            fh.write(data)
        os.utime(bag_path, ns=(kept.st_atime_ns, kept.st_mtime_ns))
        return bag

    monkeypatch.setattr(bags, "_check_index", _refuse)
    monkeypatch.setattr(bags, "_walk_ros1", rewritten_after_the_first_pass)
    try:
        imu = read_bag_imu(path)
    except ValueError as exc:  # a refusal naming the bag is as good
        assert str(path) in str(exc)
        return
    assert np.all(np.diff(imu.record_times) >= 0.0), imu.record_times


def _ordered_bag_and_its_rewrite(path: Path) -> tuple[Path, bytearray]:
    """Five IMU messages in record-time order, and the bag's bytes with the first two
    messages' record times swapped (1 s and 2 s: same size, out of order)."""
    with Writer(path) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE1)
        for k in range(1, 6):
            writer.write(conn, k * 10**9, STORE1.serialize_ros1(_imu(STORE1, k), IMU))
    data = bytearray(path.read_bytes())
    times = [m.end() for m in re.finditer(rb"time=", data)]
    first, second = times[0], times[1]  # the first two message records' (sec, nsec)
    assert struct.unpack("<II", data[first : first + 8]) == (1, 0)
    data[first : first + 8], data[second : second + 8] = (
        data[second : second + 8],
        data[first : first + 8],
    )
    return path, data


def test_a_rewrite_no_time_stamp_tells_is_refused_at_the_message_out_of_order(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Where the status-change time is as coarse as the modification time (ext3: 1 s),
    # a rewrite within the second keeps every field of the identity (device, inode,
    # size, both times): made so here, the walker's second pass meets 2 s then 1 s.
    path, data = _ordered_bag_and_its_rewrite(tmp_path / "rewritten.bag")
    identity = bags._identity
    monkeypatch.setattr(bags, "_identity", lambda fh: identity(fh)[:3])  # no time stamps
    bag = bags._walk_ros1(path)
    path.write_bytes(data)
    messages = bag.messages("/imu", IMU)
    assert next(messages)[0] == 2 * 10**9  # the first message read: nothing to compare yet
    with pytest.raises(bags._Corrupt, match=re.escape("no longer in record-time order")):
        next(messages)


def test_a_bag_rewritten_with_its_modification_time_put_back_is_refused_before_reading(
    tmp_path: Path,
) -> None:
    # The status-change time follows the rewrite and the utime: the walker's second
    # pass refuses the file before reading a message.
    path, data = _ordered_bag_and_its_rewrite(tmp_path / "rewritten.bag")
    bag = bags._walk_ros1(path)
    kept = os.stat(path)
    path.write_bytes(data)
    # The kernel's file clock ticks every few milliseconds: put the time back until the
    # change time is past the bag's (a rewrite in the same tick is the case above).
    deadline = time.monotonic() + 5.0
    os.utime(path, ns=(kept.st_atime_ns, kept.st_mtime_ns))
    while os.stat(path).st_ctime_ns == kept.st_ctime_ns and time.monotonic() < deadline:
        time.sleep(0.001)
        os.utime(path, ns=(kept.st_atime_ns, kept.st_mtime_ns))
    now = os.stat(path)
    assert (now.st_size, now.st_mtime_ns) == (kept.st_size, kept.st_mtime_ns)
    assert now.st_ctime_ns != kept.st_ctime_ns
    with pytest.raises(bags._Corrupt, match="the bag file changed while it was read"):
        next(bag.messages("/imu", IMU))
