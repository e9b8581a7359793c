"""Eighth review of navkit.mapping.io: damaged and malicious files (bombs, lying headers)."""

from __future__ import annotations

import bz2
import gzip
import struct
import tracemalloc
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import _carmen, _map_files, _paths, read_bag_scans, read_carmen, read_map
from navkit.mapping.io._bags import CHUNK_MAX, _Corrupt, _walk_ros1
from navkit.mapping.io._carmen import LINE_MAX

_MAP = (
    "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
    "free_thresh: 0.196\n"
)
# Seven levels of nine aliases: a list of 9**7 (4.8 million) strings in 300 bytes.
_BOMB = "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
    f"{chr(98 + i)}: &{chr(98 + i)} [{', '.join([f'*{chr(97 + i)}'] * 9)}]\n" for i in range(6)
)


@contextmanager
def _peak_memory() -> Iterator[list[int]]:
    """The peak of Python's allocations in the block, bytes (in the list, on exit)."""
    peak: list[int] = []
    tracemalloc.start()
    try:
        yield peak
    finally:
        peak.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()


# ------------------------------------------------------------------ map YAML
@pytest.mark.parametrize(
    "key", ["image", "resolution", "origin", "origin x", "negate", "occupied_thresh", "mode"]
)
def test_yaml_alias_bomb_is_refused_with_a_short_message(tmp_path: Path, key: str) -> None:
    # The error message held repr() of the whole value: walking all its shared
    # parts (forever for a real "billion laughs", 9**10) to print a few megabytes.
    (tmp_path / "m.pgm").write_bytes(b"P5 1 1 255 \xff")
    entries = {"image": "m.pgm", "mode": "trinary"}
    text = _MAP
    if key == "origin x":
        text = text.replace("origin: [0, 0, 0]", "origin: [*g, 0, 0]")
    elif key in entries:
        entries[key] = "*g"
    else:
        text = text.replace(f"{key}: ", f"{key}: *g #", 1)
    path = tmp_path / "m.yaml"
    path.write_text(_BOMB + text + "".join(f"{k}: {v}\n" for k, v in entries.items()))
    with _peak_memory() as peak, pytest.raises(ValueError, match=key.split()[0]) as info:
        read_map(path)
    assert str(path) in str(info.value) and len(str(info.value)) < 500
    assert peak[0] < 4 << 20  # repr() of the whole value: 24 MB of text


# ------------------------------------------------------------------ PGM
class _ReadSizes:
    """A file whose ``read`` records the sizes asked for (read(n) allocates n bytes)."""

    def __init__(self, raw: Any, sizes: list[int]) -> None:
        self._raw, self._sizes = raw, sizes

    def read(self, n: int = -1) -> Any:
        self._sizes.append(n)
        return self._raw.read(n)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._raw, name)

    def __enter__(self) -> _ReadSizes:
        return self

    def __exit__(self, *args: object) -> None:
        self._raw.close()


@pytest.mark.parametrize(
    ("header", "message"),
    [(b"P2 16384 16384 255\n0 0 0\n", "3 of 268435456 values"),
     (b"P5 16384 16384 65535\n\x00\x00", "2 bytes for 16384 x 16384")],
)  # fmt: skip
def test_pgm_declaring_a_huge_raster_is_not_allocated(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, header: bytes, message: str
) -> None:
    # A 25-byte P2 declaring 2**28 pixels asked read() for 8.6 GB (MemoryError
    # under a memory limit, before the truncation was found).
    (tmp_path / "m.pgm").write_bytes(header)
    (tmp_path / "m.yaml").write_text("image: m.pgm\n" + _MAP)
    sizes: list[int] = []
    real_open: Callable[..., Any] = _paths.open_regular

    def spying_open(path: Path, what: str) -> Any:
        fh = real_open(path, what)
        return _ReadSizes(fh, sizes) if path.suffix == ".pgm" else fh

    monkeypatch.setattr(_map_files, "open_regular", spying_open)
    with pytest.raises(ValueError, match=f"truncated: {message}"):
        read_map(tmp_path / "m.yaml")
    assert sizes and max(sizes) <= 1 << 16  # the header's 64 KiB at most


# ------------------------------------------------------------------ CARMEN
@pytest.mark.parametrize("zipped", [False, True])
def test_carmen_line_without_end_is_refused_before_it_is_held(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, zipped: bool
) -> None:
    # A gzip'd file of 1 MB holding a gigabyte without a newline took 2 GB of
    # memory to read as one line; here a line just over the limit, then a good one.
    body = b"FLASER 1 " + b"1" * LINE_MAX + b" 0 0 0 0 0 0 1.0\nFLASER 1 1 0 0 0 0 0 0 1\n"
    path = tmp_path / ("log.gz" if zipped else "log.txt")
    path.write_bytes(gzip.compress(body, 1) if zipped else body)
    with pytest.raises(ValueError, match=f"{path}:1: line longer than {LINE_MAX}"):
        read_carmen(path)
    # Only the first LINE_MAX + 1 characters are held.
    monkeypatch.setattr(_carmen, "LINE_MAX", 1000)
    with _peak_memory() as peak, pytest.raises(ValueError, match=":1: line longer than 1000"):
        read_carmen(path)
    assert peak[0] < 1 << 20
    monkeypatch.undo()
    # A line of exactly the limit is read (and checked as any other line).
    path.write_bytes(b"FLASER 1 1.0 0 0 0 0 0 0 " + b"0" * (LINE_MAX - 27) + b"1\n")
    assert len(read_carmen(path).scans) == 1


# ------------------------------------------------------------------ ROS 1 bags
def _records(data: bytes, pos: int) -> list[list[Any]]:
    """The top-level records of a ROS 1 bag from ``pos``: [position, fields, data]."""
    out: list[list[Any]] = []
    while pos < len(data):
        (header_len,) = struct.unpack_from("<I", data, pos)
        header = data[pos + 4 : pos + 4 + header_len]
        (data_len,) = struct.unpack_from("<I", data, pos + 4 + header_len)
        body = data[pos + 8 + header_len : pos + 8 + header_len + data_len]
        fields, i = [], 0
        while i < len(header):
            (n,) = struct.unpack_from("<I", header, i)
            name, _, value = header[i + 4 : i + 4 + n].partition(b"=")
            fields.append([name, value])
            i += 4 + n
        out.append([pos, fields, body])
        pos += 8 + header_len + data_len
    return out


def _record(fields: list[list[bytes]], body: bytes) -> bytes:
    header = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k + b"=" + v for k, v in fields)
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(body)) + body


def _rebuilt(data: bytes, change: Callable[[list[list[bytes]], bytes], bytes]) -> bytes:
    """The bag ``data`` with each chunk's data replaced by ``change(fields, data)`` (which
    may edit the fields), the positions of the index moved to match."""
    magic = b"#ROSBAG V2.0\n"
    records = _records(data, len(magic))
    moved, pos = {}, len(magic)
    for record in records:
        if dict(map(tuple, record[1]))[b"op"] == b"\x05":
            record[2] = change(record[1], record[2])
        moved[record[0]] = pos
        pos += len(_record(record[1], record[2]))
    for record in records:
        for field in record[1]:
            if field[0] in (b"index_pos", b"chunk_pos"):
                field[1] = struct.pack("<Q", moved[struct.unpack("<Q", field[1])[0]])
    return magic + b"".join(_record(fields, body) for _, fields, body in records)


def _scan_bag(path: Path, compression: str) -> Path:
    rosbag1 = pytest.importorskip("rosbags.rosbag1")
    typesys = pytest.importorskip("rosbags.typesys")
    store = typesys.get_typestore(typesys.Stores.ROS1_NOETIC)
    kind = "sensor_msgs/msg/LaserScan"
    scan, header, time = (store.types[t] for t in (kind, "std_msgs/msg/Header",
                                                    "builtin_interfaces/msg/Time"))  # fmt: skip
    writer = rosbag1.Writer(path)
    writer.set_compression(getattr(rosbag1.Writer.CompressionFormat, compression))
    with writer:
        conn = writer.add_connection("/scan", kind, typestore=store)
        for i in range(3):
            msg = scan(
                header=header(seq=i, stamp=time(sec=i, nanosec=0), frame_id="laser"),
                angle_min=0.0,
                angle_max=0.2,
                angle_increment=0.1,
                time_increment=0.0,
                scan_time=0.0,
                range_min=0.1,
                range_max=5.0,
                ranges=np.ones(3, np.float32),
                intensities=np.zeros(0, np.float32),
            )
            writer.write(conn, i * 10**9, store.serialize_ros1(msg, kind))
    return path


def _codec(compression: str) -> tuple[Callable[[bytes], bytes], Callable[[bytes], bytes]]:
    if compression == "BZ2":
        return bz2.compress, bz2.decompress
    lz4_frame = pytest.importorskip("lz4.frame")
    return lz4_frame.compress, lz4_frame.decompress


@pytest.mark.parametrize("compression", ["BZ2", "LZ4"])
def test_bag_chunk_inflating_past_its_declared_size_is_refused(
    tmp_path: Path, compression: str
) -> None:
    # A 6 KB bag whose chunk inflated to a gigabyte took 2 GB of memory in rosbags
    # (and in the chunk walker); 8 MB here, beyond the 839 bytes the chunk declares.
    compress, decompress = _codec(compression)
    good = _scan_bag(tmp_path / "good.bag", compression)
    assert len(read_bag_scans(good)) == 3

    def padded(fields: list[list[bytes]], body: bytes) -> bytes:
        return compress(decompress(body) + bytes(8 << 20))

    bomb = tmp_path / "bomb.bag"
    bomb.write_bytes(_rebuilt(good.read_bytes(), padded))
    with pytest.raises(ValueError, match=r"decompresses to more than the [0-9]+ bytes") as info:
        read_bag_scans(bomb)
    assert str(bomb) in str(info.value)
    with pytest.raises(_Corrupt, match="decompresses to more than"):
        _walk_ros1(bomb)


def test_bag_chunk_declaring_more_than_the_limit_is_refused(tmp_path: Path) -> None:
    good = _scan_bag(tmp_path / "good.bag", "BZ2")

    def declared(fields: list[list[bytes]], body: bytes) -> bytes:
        for field in fields:
            if field[0] == b"size":
                field[1] = struct.pack("<I", CHUNK_MAX + 1)
        return body

    huge = tmp_path / "huge.bag"
    huge.write_bytes(_rebuilt(good.read_bytes(), declared))
    with pytest.raises(ValueError, match=f"declares {CHUNK_MAX + 1} bytes decompressed"):
        read_bag_scans(huge)


# ------------------------------------------------------------------ ROS 2 bags
def _imu_bag2(folder: Path, compression: str = "") -> Path:
    rosbag2 = pytest.importorskip("rosbags.rosbag2")
    enums = pytest.importorskip("rosbags.rosbag2.enums")
    typesys = pytest.importorskip("rosbags.typesys")
    store = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
    kind = "sensor_msgs/msg/Imu"
    types = store.types
    vec, quat = types["geometry_msgs/msg/Vector3"], types["geometry_msgs/msg/Quaternion"]
    writer = rosbag2.Writer(folder, version=9)
    if compression:
        writer.set_compression(getattr(enums.CompressionMode, compression),
                               enums.CompressionFormat.ZSTD)  # fmt: skip
    with writer:
        conn = writer.add_connection("/imu", kind, typestore=store)
        for i in range(3):
            stamp = types["builtin_interfaces/msg/Time"](sec=i, nanosec=0)
            msg = types[kind](
                header=types["std_msgs/msg/Header"](stamp=stamp, frame_id="imu"),
                orientation=quat(x=0.0, y=0.0, z=0.0, w=1.0),
                orientation_covariance=np.zeros(9),
                angular_velocity=vec(x=0.0, y=0.0, z=0.1 * i),
                angular_velocity_covariance=np.zeros(9),
                linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
                linear_acceleration_covariance=np.zeros(9),
            )
            writer.write(conn, i * 10**9 + 1, store.serialize_cdr(msg, kind))
    return folder


@pytest.mark.parametrize(
    ("field", "line"),
    [("topic name", "name: /imu"), ("topic type", "type: sensor_msgs/msg/Imu"),
     ("message count", "message_count: 3")],
)  # fmt: skip
def test_ros2_metadata_field_of_another_yaml_type_is_refused(
    tmp_path: Path, field: str, line: str
) -> None:
    # A topic's name, type or count given as a list (here an alias bomb of 9**7
    # strings) raised TypeError or AttributeError from deep in the readers.
    from navkit.mapping.io import bag_topics, read_bag_imu

    folder = _imu_bag2(tmp_path / "bag")
    meta = (folder / "metadata.yaml").read_text()
    key = line.split(":")[0]
    # The count is the topic's (indented), not the bag's total (first in the file).
    at = meta.index(line, meta.index("topics_with_message_count"))
    meta = meta[:at] + f"{key}: *g" + meta[at + len(line) :]
    (folder / "metadata.yaml").write_text(_BOMB + meta)
    for read in (bag_topics, read_bag_imu):
        with pytest.raises(ValueError, match=f"cannot read the ROS 2 bag: a {field} is a list"
                           ) as info:  # fmt: skip
            read(folder)
        assert str(folder) in str(info.value) and len(str(info.value)) < 500


def test_ros2_metadata_over_the_limit_is_refused_unread(tmp_path: Path) -> None:
    from navkit.mapping.io import read_bag_imu
    from navkit.mapping.io._bags import METADATA_MAX

    folder = _imu_bag2(tmp_path / "bag")
    assert len(read_bag_imu(folder)) == 3
    path = folder / "metadata.yaml"
    text = path.read_text()
    # A valid YAML all the same (a comment): rosbags parsed all of it in pure Python.
    path.write_text(text + "#" * (METADATA_MAX + 1 - len(text)) + "\n")
    with pytest.raises(ValueError, match=f"{path}: {METADATA_MAX + 2} bytes is too large"):
        read_bag_imu(folder)


@pytest.mark.parametrize("compression", ["FILE", "MESSAGE"])
def test_ros2_bags_compressed_with_zstd_are_read(tmp_path: Path, compression: str) -> None:
    # As the module docstring says (with the warning that rosbags bounds nothing there).
    from navkit.mapping.io import read_bag_imu

    plain = read_bag_imu(_imu_bag2(tmp_path / "plain"))
    packed = read_bag_imu(_imu_bag2(tmp_path / "packed", compression))
    assert len(packed) == 3
    assert np.array_equal(packed.angular_velocities, plain.angular_velocities)
    assert np.array_equal(packed.times, plain.times)
