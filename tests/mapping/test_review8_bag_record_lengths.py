"""The ROS 1 chunk walker refuses a record whose declared lengths exceed the bytes there.

Before, ``_record`` sliced a header or data block short without a word: a message record
inside a chunk declaring more data than the chunk holds was read as a shorter message
(caught, if at all, by the message decoder, without naming the record).
"""

from __future__ import annotations

import struct
from collections.abc import Iterator
from pathlib import Path

import pytest

from navkit.mapping.io import bag_topics, read_bag_imu
from navkit.mapping.io._bags import _Corrupt, _record, _walk_ros1

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer as Writer1

from ros1_imu_messages import IMU, STORE, imu_message

MAGIC = len(b"#ROSBAG V2.0\n")


def write_bag(path: Path) -> bytes:
    """An uncompressed ROS 1 bag of three Imu messages in one chunk; its bytes."""
    with Writer1(path) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE)
        for k in range(3):
            ns = (k + 1) * 10**9
            writer.write(conn, ns, STORE.serialize_ros1(imu_message(ns, float(k)), IMU))
    return path.read_bytes()


def records(data: bytes, pos: int) -> Iterator[tuple[int, bytes, int, int]]:
    """(position, header, data position, data length) of each record from ``pos`` on."""
    while pos < len(data):
        (header_len,) = struct.unpack_from("<I", data, pos)
        (data_len,) = struct.unpack_from("<I", data, pos + 4 + header_len)
        yield pos, data[pos + 4 : pos + 4 + header_len], pos + 8 + header_len, data_len
        pos += 8 + header_len + data_len


def test_a_message_record_longer_than_its_chunk_is_refused(tmp_path: Path) -> None:
    data = write_bag(tmp_path / "sound.bag")
    assert len(read_bag_imu(tmp_path / "sound.bag")) == 3
    chunk_pos, _, at, length = next(r for r in records(data, MAGIC) if b"op=\x05" in r[1])
    last = [r for r in records(data[at : at + length], 0) if b"op=\x02" in r[1]][-1]
    damaged = bytearray(data)
    # The last message declares 50 bytes more than its chunk holds (rosbags refuses
    # this, so the readers fall back on the chunk walker).
    struct.pack_into("<I", damaged, at + last[2] - 4, last[3] + 50)
    path = tmp_path / "lying.bag"
    path.write_bytes(bytes(damaged))
    where = f"record at byte {last[0]} of the chunk at byte {chunk_pos}"
    with pytest.raises(_Corrupt, match=where):
        _walk_ros1(path)
    # bag_topics reads only rosbags' index here (sound), not the chunk.
    assert bag_topics(path) == {"/imu": (IMU, 3)}
    with pytest.raises(ValueError, match=f"cannot read the ROS 1 bag.*{where}") as info:
        read_bag_imu(path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize("cut", ["header", "data"])
def test_record_refuses_lengths_beyond_the_bytes(cut: str) -> None:
    header = struct.pack("<I", 4) + b"op=\x02"
    block = struct.pack("<I", len(header)) + header + struct.pack("<I", 3) + b"abc"
    fields, body, end = _record(block, 0)
    assert (fields, body, end) == ({"op": b"\x02"}, b"abc", len(block))
    lying = bytearray(block)
    struct.pack_into("<I", lying, 0 if cut == "header" else 4 + len(header), 1000)
    with pytest.raises(_Corrupt, match=f"record at byte 0 declares .*{1000}"):
        _record(bytes(lying), 0)
    # Every cut of the record is refused too, never read as a shorter one.
    for n in range(len(block)):
        with pytest.raises(_Corrupt, match="record at byte 0"):
            _record(block[:n], 0)
