"""Bag readers on damaged copies of the real bags (review 46).

A bag cut anywhere, or with a flipped bit in a compressed chunk, is refused with
a ``ValueError`` naming it (or, for a flip rosbags cannot see, read as the
bag holds); a message declaring 2**31 ranges is refused naming the message,
without allocating them. ROS 1 bags carry no checksum: a flipped bit in an
uncompressed message's numbers (demo.bag) reads as another number, which no
reader can tell.
"""

from __future__ import annotations

import random
import re
import struct
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from memory_peak import peak_bytes
from navkit.mapping.io import read_bag_imu, read_bag_odometry, read_bag_scans

pytest.importorskip("rosbags")

RL = "robot-localization-odom-imu-bags"
DEMO = "rosbag-hokuyo-laserscan-demo"


def _odometry(path: Path) -> tuple[bytes, ...]:
    odom = read_bag_odometry(path)
    return tuple(
        getattr(odom, name).tobytes()
        for name in ("times", "record_times", "poses", "twists", "twist_covariances")
    )


def _imu(path: Path) -> tuple[bytes, ...]:
    imu = read_bag_imu(path, topic="/imu/data")
    return tuple(
        getattr(imu, name).tobytes()
        for name in ("times", "record_times", "orientations", "angular_velocities")
    )


def _scans(path: Path) -> tuple[bytes, ...]:
    scans = read_bag_scans(path)
    return (scans.times.tobytes(), np.array([s.ranges for s in scans.scans]).tobytes())


def _damage(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> dict[str, int]:
    """Read ``count`` cut and ``count`` bit-flipped copies of bag ``name``; how each came out."""
    data = (shared_data / name).read_bytes()
    path = tmp_path / "damaged.bag"
    path.write_bytes(data)
    whole = read(path)
    rng = random.Random(f"46{name}")
    outcomes = {"refused": 0, "same": 0, "other numbers": 0}
    for kind in ("cut", "flip"):
        for _ in range(count):
            offset = rng.randrange(len(data))
            if kind == "cut":
                damaged = data[:offset]
            else:
                flipped = bytearray(data)
                flipped[offset] ^= 1 << rng.randrange(8)
                damaged = bytes(flipped)
            path.write_bytes(damaged)
            try:
                got = read(path)
            except ValueError as exc:
                assert str(path) in str(exc), exc
                outcomes["refused"] += 1
                continue
            assert kind == "flip", f"a bag cut at byte {offset} of {len(data)} was read"
            outcomes["same" if got == whole else "other numbers"] += 1
    return outcomes


@pytest.mark.parametrize(
    ("name", "read", "count"),
    [(f"{RL}/test2.bag", _odometry, 12), (f"{DEMO}/demo.bag", _scans, 12)],
)
def test_damaged_bags_are_refused_naming_them(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> None:
    outcomes = _damage(shared_data, tmp_path, name, read, count)
    if name.endswith("test2.bag"):  # compressed chunks: their damage is seen
        assert outcomes["other numbers"] == 0, outcomes


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "read", "count"),
    [
        (f"{RL}/test2.bag", _odometry, 150),
        (f"{RL}/test1.bag", _imu, 50),
        (f"{DEMO}/demo.bag", _scans, 100),
    ],
)
def test_many_damaged_bags_are_refused_naming_them(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> None:
    outcomes = _damage(shared_data, tmp_path, name, read, count)
    if "/test" in name:
        assert outcomes["other numbers"] == 0, outcomes


@pytest.mark.parametrize("count", [2**31, 2**32 - 1, 682])
def test_a_scan_declaring_too_many_ranges_is_refused_without_allocating_them(
    shared_data: Path, tmp_path: Path, count: int
) -> None:
    data = bytearray((shared_data / DEMO / "demo.bag").read_bytes())
    # The first message's range count (681), after its five float32 angles and ranges.
    at = data.index(struct.pack("<I", 681))
    data[at : at + 4] = struct.pack("<I", count)
    path = tmp_path / "huge.bag"
    path.write_bytes(bytes(data))

    def read() -> str:
        with pytest.raises(ValueError, match="message 0 of /scan cannot be decoded") as info:
            read_bag_scans(path)
        return str(info.value)

    peak, message = peak_bytes(read)
    assert message.startswith(str(path))
    assert peak < 8 * len(data)  # the bag read whole, not 4 bytes x 2**31


def _scan_bag(path: Path, count: int) -> None:
    """An uncompressed ROS 1 bag of ``count`` scans (rosbags' own writer: a sound index)."""
    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS1_NOETIC)
    types = store.types
    with Writer(path) as writer:
        conn = writer.add_connection("/scan", "sensor_msgs/msg/LaserScan", typestore=store)
        for k in range(count):
            stamp = types["builtin_interfaces/msg/Time"](sec=100 + k, nanosec=0)
            msg = types["sensor_msgs/msg/LaserScan"](
                header=types["std_msgs/msg/Header"](seq=k, stamp=stamp, frame_id="laser"),
                angle_min=-1.0, angle_max=1.0, angle_increment=0.5, time_increment=0.0,
                scan_time=0.1, range_min=0.1, range_max=5.0,
                ranges=np.arange(1, 6, dtype=np.float32), intensities=np.zeros(0, np.float32),
            )  # fmt: skip
            raw = store.serialize_ros1(msg, "sensor_msgs/msg/LaserScan")
            writer.write(conn, (100 + k) * 10**9, raw)


def _message_fields(data: bytes) -> list[tuple[int, int]]:
    """(offset of the op value, offset of the conn value) of each message record's header."""
    out = []
    for match in re.finditer(b"op=\x02", data):
        op = match.start() + 3
        out.append((op, data.index(b"conn=", op - 40, op + 40) + 5))  # fields in any order
    return out


@pytest.mark.parametrize("field", ["op", "conn"])
def test_a_damaged_message_record_is_refused_not_dropped(tmp_path: Path, field: str) -> None:
    """rosbags refuses the bag; the chunk walker then read the others, dropping the damaged
    message unseen: it now counts each chunk's messages against its chunk info record."""
    path = tmp_path / "scans.bag"
    _scan_bag(path, 10)
    assert len(read_bag_scans(path)) == 10
    data = bytearray(path.read_bytes())
    op, conn = _message_fields(bytes(data))[3]
    if field == "op":
        data[op] = 3  # a bag header record's op
    else:
        data[conn] ^= 1  # connection 1, which the bag does not declare
    path.write_bytes(bytes(data))
    with pytest.raises(ValueError, match="holds 9 messages of connection 0, its chunk info"):
        read_bag_scans(path)


@pytest.mark.parametrize("field", ["op", "conn"])
def test_a_damaged_message_record_of_the_real_demo_bag_is_refused(
    shared_data: Path, tmp_path: Path, field: str
) -> None:
    """demo.bag is always read by the chunk walker (its index data record is damaged)."""
    data = bytearray((shared_data / DEMO / "demo.bag").read_bytes())
    op, conn = _message_fields(bytes(data))[100]
    if field == "op":
        data[op] = 3
    else:
        data[conn] ^= 1
    path = tmp_path / "demo.bag"
    path.write_bytes(bytes(data))
    with pytest.raises(
        ValueError, match=r"^" + str(path) + r": cannot read the ROS 1 bag: .*holds"
    ):
        read_bag_scans(path)
