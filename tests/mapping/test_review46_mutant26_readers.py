"""Mutants of review 46's reader changes that no earlier test told apart (MUTANT26).

The rules those changes set, pinned where a mutant of them still passed:
a loop of symbolic links folders above the file is named as the loop, not as
a folder below it, and other operating-system errors are passed on, not
called a missing file; the MovingAI scenario reader's test for a file cut
inside its last optimal length (a blank or CR after the length ends it,
an exponent is no decimals, lengths printed with varying decimals are not
checked, sizes written out up to 40 digits); and the ROS 1 chunk walker's
comparison of each chunk with its chunk-info record (the record's length
against its connection count, messages beyond the counts, a connection the
record does not list, a connection listed twice).
"""

from __future__ import annotations

import errno
import math
import re
import struct
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import navkit.mapping.io._map_files as map_files
from link_trees import loop
from navkit._shared.counts import bytes_text
from navkit.mapping.io import (
    read_bag_scans,
    read_carmen,
    read_movingai_map,
    read_movingai_scenarios,
)

SETS = "movingai-grid-benchmarks"
DEMO = "rosbag-hokuyo-laserscan-demo"

READERS: dict[str, Callable[[Any], Any]] = {
    "read_carmen": read_carmen,
    "read_movingai_map": read_movingai_map,
    "read_movingai_scenarios": read_movingai_scenarios,
    "read_bag_scans": read_bag_scans,
}


def _reader(name: str) -> Callable[[Any], Any]:
    if name == "read_bag_scans":
        pytest.importorskip("rosbags")
    return READERS[name]


# ------------------------------------------------------------------ paths
@pytest.mark.parametrize("name", list(READERS))
def test_a_loop_folders_above_the_file_is_named_not_a_folder_inside_it(
    tmp_path: Path, name: str
) -> None:
    read = _reader(name)
    looped = loop(tmp_path)
    path = looped / "x" / "y" / "z.file"
    with pytest.raises(FileNotFoundError) as info:
        read(path)
    assert str(info.value).endswith(f"{path} does not exist ({looped} is a loop of symbolic links)")


@pytest.mark.parametrize("name", list(READERS))
def test_other_system_errors_are_passed_on_not_called_a_missing_file(
    tmp_path: Path, name: str
) -> None:
    read = _reader(name)
    with pytest.raises(OSError) as info:
        read(tmp_path / ("n" * 300))  # beyond NAME_MAX (255)
    assert not isinstance(info.value, FileNotFoundError), info.value
    assert info.value.errno == errno.ENAMETOOLONG


def test_a_loop_hides_the_systems_bare_error(tmp_path: Path) -> None:
    looped = tmp_path / "a.map"
    looped.symlink_to(looped)
    with pytest.raises(FileNotFoundError) as info:
        read_movingai_map(looped)
    assert info.value.__cause__ is None
    assert info.value.__suppress_context__  # no "Too many levels of symbolic links" above it


# ------------------------------------------------------------------ scenario lengths
def _problems(shared_data: Path, count: int) -> list[bytes]:
    """The version line and the first ``count`` problem lines of the real arena scenarios."""
    lines = (shared_data / SETS / "dao/arena.map.scen").read_bytes().split(b"\n")
    assert all(line.rsplit(b".", 1)[1].isdigit() for line in lines[1 : count + 1])
    return lines[: count + 1]


def _with_length(line: bytes, word: bytes) -> bytes:
    return line.rsplit(b"\t", 1)[0] + b"\t" + word


@pytest.mark.parametrize("end", [b" ", b"\t", b"\r", b" \t "])
def test_a_blank_or_cr_after_the_last_length_ends_it(
    shared_data: Path, tmp_path: Path, end: bytes
) -> None:
    """A file cut after a blank or a CRLF's CR holds the whole last length: read as written,
    whatever its decimals."""
    lines = _problems(shared_data, 4)
    path = tmp_path / "arena.map.scen"
    for word in (b"2.4142", b"2", b"2.4142135"):
        path.write_bytes(b"\n".join([*lines[:-1], _with_length(lines[-1], word)]) + end)
        assert read_movingai_scenarios(path).optimal_lengths[-1] == float(word)
        path.write_bytes(b"\n".join([*lines[:-1], _with_length(lines[-1], word)]))
        with pytest.raises(ValueError, match=":5: the file ends inside this line"):
            read_movingai_scenarios(path)


@pytest.mark.parametrize(
    ("word", "said"), [(b"3", "no"), (b"3.", "0"), (b"3.2", "1"), (b"3.2071067", "7")]
)
def test_the_refusal_names_both_counts_of_decimals(
    shared_data: Path, tmp_path: Path, word: bytes, said: str
) -> None:
    lines = _problems(shared_data, 3)
    path = tmp_path / "arena.map.scen"
    path.write_bytes(b"\n".join([*lines[:-1], _with_length(lines[-1], word)]))
    with pytest.raises(ValueError) as info:
        read_movingai_scenarios(path)
    assert str(info.value) == (
        f"{path}:4: the file ends inside this line, its optimal_length {word.decode()!r} printed "
        f"with {said} decimals where every other line has 8: it looks truncated; end the line "
        "with a newline if it is whole"
    )


@pytest.mark.parametrize("word", [b"2.000000005", b"24.1421356237"])
def test_a_last_length_with_more_decimals_is_no_cut(
    shared_data: Path, tmp_path: Path, word: bytes
) -> None:
    """A cut leaves fewer decimals, never more: such a whole last line is read, not called
    truncated (the function's own docstring says "fewer")."""
    lines = _problems(shared_data, 3)
    path = tmp_path / "arena.map.scen"
    path.write_bytes(b"\n".join([*lines[:-1], _with_length(lines[-1], word)]))
    assert read_movingai_scenarios(path).optimal_lengths[-1] == float(word)


@pytest.mark.parametrize("word", [b"1.2e1", b"1.2E1", b"12.0e0", b"1.234E+01"])
def test_a_last_length_with_an_exponent_has_no_decimals(tmp_path: Path, word: bytes) -> None:
    """The digits after the point of ``1.2E1`` are no decimals of the file's ``%.3f``."""
    path = tmp_path / "a.map.scen"
    lines = [
        b"version 1",
        b"0\ta.map\t9\t9\t0\t0\t1\t1\t1.414",
        b"0\ta.map\t9\t9\t0\t0\t1\t0\t1.000",
    ]
    path.write_bytes(b"\n".join([*lines, b"2\ta.map\t9\t9\t0\t0\t8\t4\t" + word]))
    with pytest.raises(ValueError, match=r":4: .* printed with no decimals where every other"):
        read_movingai_scenarios(path)
    path.write_bytes(b"\n".join([*lines, b"2\ta.map\t9\t9\t0\t0\t8\t4\t" + word, b""]))
    assert read_movingai_scenarios(path).optimal_lengths[-1] == float(word)


@pytest.mark.parametrize(
    "words",
    [
        [b"1", b"2.50", b"1.2"],  # an integer among the lengths: printed with varying decimals
        [b"2.50", b"1", b"1.2"],
        [b"1.41421356", b"2.4142136", b"1.41"],  # the two before differ
        [b"1.41421356", b"1.41421356", b"2.4142136", b"1.41421356", b"1.41"],
        [b"1", b"2", b"1.5"],  # printed without decimals: nothing to compare with
        [b"1.5e1", b"2.0E0", b"2.5"],
    ],
)
def test_lengths_printed_with_varying_decimals_or_none_are_not_checked(
    tmp_path: Path, words: list[bytes]
) -> None:
    path = tmp_path / "a.map.scen"
    lines = [b"0\ta.map\t9\t9\t0\t0\t1\t1\t" + word for word in words]
    path.write_bytes(b"\n".join([b"version 1", *lines]))
    assert read_movingai_scenarios(path).optimal_lengths.tolist() == [float(w) for w in words]


@pytest.mark.parametrize("digits", [39, 40, 41, 42])
def test_sizes_are_written_out_up_to_40_digits(tmp_path: Path, digits: int) -> None:
    size = int("9" * digits)
    said = re.escape(str(size) if digits <= 40 else f"999999... ({digits} digits)")
    path = tmp_path / "huge.map"
    path.write_bytes(f"type octile\nheight 7\nwidth {size}\nmap\n..\n".encode())
    with pytest.raises(
        ValueError, match=rf"^{re.escape(str(path))}: 7 x {said} cells, more than 2\*\*26"
    ):
        read_movingai_map(path)
    scenarios = tmp_path / "huge.map.scen"
    for fields, words in (
        (f"{size}\ta.map\t3\t3", f"bucket {said} is more than"),
        (f"0\ta.map\t{size}\t2", f"a map of 2 x {said} cells, more than"),
    ):
        scenarios.write_bytes(f"version 1\n{fields}\t0\t0\t1\t1\t1.0\n".encode())
        with pytest.raises(ValueError, match=rf"^{re.escape(str(scenarios))}:2: {words}"):
            read_movingai_scenarios(scenarios)


@pytest.mark.parametrize(
    ("rows", "cols"), [(10**10, 10**10), (3, 2**26), (10**20, 7), (2**40, 2**40)]
)
def test_a_map_too_large_says_the_bytes_its_terrain_would_take(
    tmp_path: Path, rows: int, cols: int
) -> None:
    path = tmp_path / "huge.map"
    path.write_bytes(f"type octile\nheight {rows}\nwidth {cols}\nmap\n..\n".encode())
    with pytest.raises(ValueError) as info:
        read_movingai_map(path)
    assert str(info.value) == (
        f"{path}: {rows} x {cols} cells, more than 2**26 = {2**26} "
        f"({bytes_text(4 * rows * cols)} of <U1 terrain; 256 MiB at most)"
    )


@pytest.mark.parametrize("bits", [999, 1000, 1023, 1024, 1025, 1029, 1100])
def test_sizes_near_the_largest_float_are_refused_naming_the_file(
    tmp_path: Path, bits: int
) -> None:
    """4.0 x cells overflows a float from 1024 bits on (OverflowError): such sizes are said
    as more bytes than exist."""
    path = tmp_path / "huge.map"
    rows = 2**bits - 1
    path.write_bytes(f"type octile\nheight {rows}\nwidth 1\nmap\n..\n".encode())
    with pytest.raises(ValueError) as info:
        read_movingai_map(path)
    size = bytes_text(4.0 * rows) if bits < 1000 else bytes_text(math.inf)
    assert str(info.value).endswith(
        f" cells, more than 2**26 = {2**26} ({size} of <U1 terrain; 256 MiB at most)"
    )
    assert str(info.value).startswith(f"{path}: {str(rows)[:6]}... ({len(str(rows))} digits) x 1")


# ------------------------------------------------------------------ ROS 1 chunk walker
def _fields(header: bytes) -> dict[str, tuple[int, int]]:
    """Each field of a record header: (offset of its value in ``header``, its length)."""
    out, at = {}, 0
    while at < len(header):
        (size,) = struct.unpack_from("<I", header, at)
        name = header[at + 4 : at + 4 + size].split(b"=", 1)[0]
        out[name.decode()] = (at + 4 + len(name) + 1, size - len(name) - 1)
        at += 4 + size
    return out


def _chunk_infos(data: bytes) -> list[tuple[int, int, int]]:
    """(position, header length, data length) of each chunk-info record of a ROS 1 bag."""
    header_len = struct.unpack_from("<I", data, 13)[0]
    header = data[17 : 17 + header_len]
    at, size = _fields(header)["index_pos"]
    pos = struct.unpack("<Q", header[at : at + size])[0]
    out = []
    while pos < len(data):
        header_len = struct.unpack_from("<I", data, pos)[0]
        data_len = struct.unpack_from("<I", data, pos + 4 + header_len)[0]
        at, _ = _fields(data[pos + 4 : pos + 4 + header_len])["op"]
        if data[pos + 4 + at] == 6:
            out.append((pos, header_len, data_len))
        pos += 8 + header_len + data_len
    return out


def _rewrite_chunk_info(
    data: bytes, which: int, entries: list[tuple[int, int]], count: int | None = None
) -> bytes:
    """``data`` with chunk-info record ``which`` listing ``entries`` (connection, messages), its
    ``count`` field ``len(entries)`` unless given."""
    pos, header_len, data_len = _chunk_infos(data)[which]
    header = bytearray(data[pos + 4 : pos + 4 + header_len])
    at, _ = _fields(bytes(header))["count"]
    header[at : at + 4] = struct.pack("<I", len(entries) if count is None else count)
    body = b"".join(struct.pack("<II", *entry) for entry in entries)
    record = struct.pack("<I", header_len) + header + struct.pack("<I", len(body)) + body
    return data[:pos] + record + data[pos + 8 + header_len + data_len :]


def _demo(shared_data: Path) -> tuple[bytes, list[list[tuple[int, int]]]]:
    pytest.importorskip("rosbags")
    data = (shared_data / DEMO / "demo.bag").read_bytes()
    listed = []
    for pos, header_len, data_len in _chunk_infos(data):
        body = data[pos + 8 + header_len : pos + 8 + header_len + data_len]
        listed.append(list(struct.iter_unpack("<II", body)))
    # The premise: demo.bag is read by the chunk walker, two chunks of connection 0.
    assert [[conn for conn, _ in entries] for entries in listed] == [[0], [0]]
    return data, listed


def _ranges(path: Path) -> bytes:
    return np.array([scan.ranges for scan in read_bag_scans(path).scans]).tobytes()


@pytest.mark.parametrize("count", [0, 2, 9])
def test_a_chunk_info_count_other_than_its_entries_is_refused(
    shared_data: Path, tmp_path: Path, count: int
) -> None:
    data, listed = _demo(shared_data)
    path = tmp_path / "demo.bag"
    path.write_bytes(_rewrite_chunk_info(data, 0, listed[0], count))
    with pytest.raises(ValueError) as info:
        read_bag_scans(path)
    chunk = struct.unpack("<Q", _chunk_pos(data, 0))[0]
    assert str(info.value).endswith(
        f"the chunk info record of the chunk at byte {chunk} lists {count} connections in "
        "8 bytes (8 bytes each)"
    )
    assert str(info.value).startswith(f"{path}: cannot read the ROS 1 bag")


def _chunk_pos(data: bytes, which: int) -> bytes:
    pos, header_len, _ = _chunk_infos(data)[which]
    header = data[pos + 4 : pos + 4 + header_len]
    at, size = _fields(header)["chunk_pos"]
    return header[at : at + size]


@pytest.mark.parametrize(("which", "change"), [(0, -1), (0, 1), (1, -1), (1, 5)])
def test_a_chunk_holding_other_than_its_count_is_refused_with_both_counts(
    shared_data: Path, tmp_path: Path, which: int, change: int
) -> None:
    """Fewer messages listed than the chunk holds too (a count lowered, not only a message
    record lost)."""
    data, listed = _demo(shared_data)
    ((conn, held),) = listed[which]
    path = tmp_path / "demo.bag"
    path.write_bytes(_rewrite_chunk_info(data, which, [(conn, held + change)]))
    chunk = struct.unpack("<Q", _chunk_pos(data, which))[0]
    with pytest.raises(ValueError) as info:
        read_bag_scans(path)
    assert str(info.value).endswith(
        f"the chunk at byte {chunk} holds {held} messages of connection {conn}, its chunk info "
        f"record {held + change}"
    )


def test_a_chunk_of_a_connection_its_record_does_not_list_is_refused(
    shared_data: Path, tmp_path: Path
) -> None:
    data, listed = _demo(shared_data)
    ((conn, held),) = listed[1]
    path = tmp_path / "demo.bag"
    path.write_bytes(_rewrite_chunk_info(data, 1, []))
    with pytest.raises(ValueError, match=f"holds {held} messages of connection {conn}, its chunk"):
        read_bag_scans(path)


def test_a_connection_listed_twice_counts_both_entries(shared_data: Path, tmp_path: Path) -> None:
    data, listed = _demo(shared_data)
    path = tmp_path / "demo.bag"
    path.write_bytes(data)
    whole = _ranges(path)
    for which in (0, 1):
        ((conn, held),) = listed[which]
        split = [(conn, held // 3), (conn, held - held // 3)]
        path.write_bytes(_rewrite_chunk_info(data, which, split))
        assert _ranges(path) == whole


# ------------------------------------------------------------------ tile coverage
@pytest.mark.parametrize("dense", [1, 3, 1 << 15])
@pytest.mark.parametrize("first", [1, 2, 5])
def test_rows_above_every_tile_are_uncovered(dense: int, first: int) -> None:
    """The bands start at row 0, not at the first tile's top row (review 46's sweep)."""
    width, height = 9, 8
    strips = np.array([(0, k, width, k + 1) for k in range(first, height)], np.int64)
    tiles = np.array([(x, y, x + 3, y + 3) for x in (0, 3, 6) for y in (first, 4, 7)], np.int64)
    for boxes in (strips, tiles, np.concatenate([strips, tiles])):
        assert not map_files._boxes_cover(boxes, width, height, dense)
        top = np.array([(0, 0, width, first)], np.int64)
        assert map_files._boxes_cover(np.concatenate([boxes, top]), width, height, dense)
