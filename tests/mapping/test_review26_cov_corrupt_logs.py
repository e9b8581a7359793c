"""Damaged logs and bags the default suite never fed the readers (coverage review, session 30).

Each is refused with a ``ValueError`` naming the file (and, for a CARMEN line,
its number) and what is wrong: malformed ``FLASER`` / ``ROBOTLASER1`` lines, a
FLASER log whose readings give no maximum range, ROS 1 bags whose bag header or
index rosbags refuses and the chunk walker cannot read either, and bag messages
that are not finite or cannot be decoded (named by their number on the topic).
"""

from __future__ import annotations

import math
import re
import struct
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import bag_topics, read_bag_odometry, read_bag_scans, read_carmen

_TAIL = "0 0 0 0 0 0 1.0 host 1.0"  # laser pose, odometry pose, timestamps


@pytest.mark.parametrize(
    ("line", "problem"),
    [
        ("FLASER", "malformed FLASER line: no beam count"),
        ("FLASER 0 " + _TAIL, "malformed FLASER line: the beam count must be at least 1"),
        ("ROBOTLASER1 0 -1.57 3.14 0.0175 80 0.1", "malformed ROBOTLASER1 line: only 6 fields"),
        (
            "ROBOTLASER1 0 -1.57 180 1 80 0.1 0 2 1 1 0 " + _TAIL + " 0 0 0 0 0 0",
            "malformed ROBOTLASER1 line: field of view 180 rad exceeds a full turn (2π): the "
            "angles look like degrees",
        ),
        (
            "ROBOTLASER1 0 -1.57 3.14 0.0175 80 0.1 0 0 0 " + _TAIL,
            "malformed ROBOTLASER1 line: the beam count must be at least 1",
        ),
        (
            "ROBOTLASER1 0 -1.57 3.14 0.0175 80 0.1 0 5 1 1",
            "malformed ROBOTLASER1 line: 2 fields after the beam count 5",
        ),
    ],
    ids=[
        "flaser-empty",
        "flaser-no-beams",
        "rl1-short",
        "rl1-degrees",
        "rl1-no-beams",
        "rl1-few-beams",
    ],
)
def test_a_malformed_laser_line_is_named_with_its_number(
    tmp_path: Path, line: str, problem: str
) -> None:
    path = tmp_path / "log.txt"
    path.write_text(f"# a comment\n{line}\n", encoding="ascii")
    with pytest.raises(ValueError) as info:
        read_carmen(path)
    assert str(info.value).startswith(f"{path}:2: {problem}")


@pytest.mark.parametrize("range_min", [0.0, 1.0, 2.0])
def test_flaser_readings_at_or_below_range_min_give_no_maximum_range(
    tmp_path: Path, range_min: float
) -> None:
    # Every reading 1 m or 0 m: with range_min at or above the largest, the largest
    # reading cannot be the scanner's maximum range.
    path = tmp_path / "log.txt"
    top = "1 1 1" if range_min else "0 0 0"
    path.write_text(f"FLASER 3 {top} {_TAIL}\n", encoding="ascii")
    with pytest.raises(ValueError) as info:
        read_carmen(path, range_min=range_min)
    assert str(info.value) == (
        f"{path}: cannot determine a maximum range of the FLASER scans above range_min "
        f"({range_min} m); give range_max"
    )
    scan = read_carmen(path, range_min=range_min, range_max=range_min + 1.0).scans[0]
    assert scan.range_max == range_min + 1.0 and len(scan) == 3


# ---------------------------------------------------------------- ROS 1 bags
_MAGIC = b"#ROSBAG V2.0\n"


def _record(fields: dict[str, bytes], data: bytes = b"") -> bytes:
    """A ROS 1 bag record: its header's ``name=value`` fields, then its data."""
    header = b"".join(
        struct.pack("<I", len(name) + 1 + len(value)) + name.encode() + b"=" + value
        for name, value in fields.items()
    )
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def _bag_header(index_pos: int, conn_count: int = 0, chunk_count: int = 0) -> bytes:
    return _record(
        {
            "op": b"\x03",
            "index_pos": struct.pack("<Q", index_pos),
            "conn_count": struct.pack("<I", conn_count),
            "chunk_count": struct.pack("<I", chunk_count),
        },
        b" " * 16,
    )


_INDEX = len(_MAGIC) + len(_bag_header(0))  # where an index right after the header starts


@pytest.mark.parametrize(
    ("data", "problem"),
    [
        (_MAGIC + _record({"op": b"\x02"}), "no bag header record"),
        (_MAGIC + _bag_header(0), r"the bag is not indexed \(run `rosbag reindex`\)"),
        (
            _MAGIC + _bag_header(_INDEX, chunk_count=1) + _record({"op": b"\x07"}),
            "expected a chunk info record in the index",
        ),
    ],
    ids=["no-header", "unindexed", "not-chunk-info"],
)
def test_a_bag_neither_rosbags_nor_the_walker_reads_is_one_value_error(
    tmp_path: Path, data: bytes, problem: str
) -> None:
    pytest.importorskip("rosbags")
    path = tmp_path / "damaged.bag"
    path.write_bytes(data)
    for read in (bag_topics, read_bag_scans):
        with pytest.raises(
            ValueError, match=rf"^{re.escape(str(path))}: cannot read the ROS 1 bag: .*{problem}$"
        ):
            read(path)
    assert path.read_bytes() == data


def test_an_indexed_bag_without_connections_has_no_topics(tmp_path: Path) -> None:
    pytest.importorskip("rosbags")
    path = tmp_path / "empty.bag"
    path.write_bytes(_MAGIC + _bag_header(_INDEX))
    assert bag_topics(path) == {}
    with pytest.raises(
        ValueError,
        match=r": no sensor_msgs/msg/LaserScan topic; the bag has "
        r"no topics$",
    ):
        read_bag_scans(path)


def _odometry(store: Any, t: float, x: float) -> Any:
    T = store.types
    stamp = T["builtin_interfaces/msg/Time"](sec=int(t), nanosec=0)
    vector = T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0)
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=x, y=0.0, z=0.0),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
    )
    return T["nav_msgs/msg/Odometry"](
        header=T["std_msgs/msg/Header"](stamp=stamp, frame_id="odom"),
        child_frame_id="base_link",
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.eye(6).ravel()),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](
            twist=T["geometry_msgs/msg/Twist"](linear=vector, angular=vector),
            covariance=np.eye(6).ravel(),
        ),
    )


def _ros2_bag(folder: Path, raw: list[bytes]) -> Path:
    from rosbags.rosbag2 import Writer

    with Writer(folder, version=9) as writer:
        conn = writer.add_connection("/odom", _ODOM, typestore=_store())
        for k, data in enumerate(raw):
            writer.write(conn, (k + 1) * 10**9, data)
    return folder


_ODOM = "nav_msgs/msg/Odometry"


def _store() -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_HUMBLE)


def test_a_non_finite_odometry_message_is_named_by_its_number(tmp_path: Path) -> None:
    pytest.importorskip("rosbags")
    store = _store()
    raw = [
        bytes(store.serialize_cdr(_odometry(store, t, x), _ODOM))
        for t, x in ((1.0, 0.0), (2.0, math.nan), (3.0, math.inf))
    ]
    path = _ros2_bag(tmp_path / "bag", raw)
    with pytest.raises(
        ValueError,
        match=rf"^{re.escape(str(path))}: message 1 of /odom has a "
        r"non-finite ",
    ):
        read_bag_odometry(path)
    assert len(read_bag_odometry(_ros2_bag(tmp_path / "sound", raw[:1]))) == 1


def test_an_undecodable_message_is_named_by_its_number(tmp_path: Path) -> None:
    pytest.importorskip("rosbags")
    store = _store()
    good = bytes(store.serialize_cdr(_odometry(store, 1.0, 0.0), _ODOM))
    path = _ros2_bag(tmp_path / "bag", [good, good[:40]])  # the second cut short
    with pytest.raises(
        ValueError,
        match=rf"^{re.escape(str(path))}: message 1 of /odom cannot "
        rf"be decoded as {_ODOM}: ",
    ):
        read_bag_odometry(path)
