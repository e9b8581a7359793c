"""read_carmen reads bzip2 and xz logs as gzip'd ones, and names other packings (session 30).

A bzip2-compressed log said "no FLASER or ROBOTLASER1 lines" (its bytes read as
text); the reader already told gzip by its first bytes, so bzip2 and xz (both in
Python's standard library) are read the same way, and a zip, 7z, zstd or lz4
file is refused naming what it is.
"""

from __future__ import annotations

import bz2
import gzip
import lzma
import tracemalloc
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import _carmen, read_carmen

BODY = ("ODOM 0.5 0 0 0 0 0 0.5 h 0.5\n"
        "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 1.0 host 1.0\n"
        "ROBOTLASER1 0 -0.5 1.0 0.25 8.0 0.01 0 5 1.5 1.5 1.5 1.5 1.5 0 "
        "1.0 2.0 0.1 0.9 2.0 0.1 0 0 0 0 0 2.0 host 2.1\n"
        ) * 20  # fmt: skip
CODECS: dict[str, Callable[[bytes], bytes]] = {
    "gzip": gzip.compress, "bzip2": bz2.compress, "xz": lzma.compress,
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(CODECS))
@pytest.mark.parametrize("suffix", [".log", ".gz", ".bz2", ".xz"])
def test_a_compressed_log_reads_as_the_plain_one(tmp_path: Path, name: str, suffix: str) -> None:
    plain = tmp_path / "plain.log"
    plain.write_text(BODY)
    packed = tmp_path / f"packed{suffix}"  # told by its first bytes, whatever its name
    packed.write_bytes(CODECS[name](BODY.encode()))
    want, got = read_carmen(plain), read_carmen(packed)
    assert len(got) == len(want) == 40
    np.testing.assert_array_equal(got.times, want.times)
    np.testing.assert_array_equal(got.odometry, want.odometry)
    assert [s.range_max for s in got.scans] == [s.range_max for s in want.scans]
    assert got.laser_poses == want.laser_poses


def test_concatenated_bzip2_streams_are_read_whole(tmp_path: Path) -> None:
    path = tmp_path / "log.bz2"  # as `cat a.bz2 b.bz2` or pbzip2 write them
    path.write_bytes(bz2.compress(BODY.encode()) + bz2.compress(BODY.encode()))
    assert len(read_carmen(path)) == 80


@pytest.mark.parametrize("name", ["bzip2", "xz"])
def test_a_damaged_compressed_log_names_its_compression(tmp_path: Path, name: str) -> None:
    good = CODECS[name]((BODY * 50).encode())
    for label, data in [
        ("truncated", good[: len(good) // 2]),
        ("garbled", good[:24] + bytes(64) + good[88:]),
    ]:
        path = tmp_path / f"{label}.log"
        path.write_bytes(data)
        with pytest.raises(ValueError, match=rf"corrupt or truncated {name} file \(after") as info:
            read_carmen(path)
        assert str(path) in str(info.value)


def _zip(body: bytes) -> bytes:
    import io

    out = io.BytesIO()
    with zipfile.ZipFile(out, "w") as archive:
        archive.writestr("log.txt", body)
    return out.getvalue()


@pytest.mark.parametrize(
    ("head", "what"),
    [(None, "zip archive"), (b"\x28\xb5\x2f\xfd", "zstd-compressed file"),
     (b"7z\xbc\xaf\x27\x1c", "7z archive"), (b"\x04\x22\x4d\x18", "lz4-compressed file")],
)  # fmt: skip
def test_other_packings_are_named(tmp_path: Path, head: bytes | None, what: str) -> None:
    path = tmp_path / "log"
    path.write_bytes(_zip(BODY.encode()) if head is None else head + bytes(100))
    with pytest.raises(ValueError, match=rf"^{path}: a {what}, not a CARMEN log: .*decompress"):
        read_carmen(path)


def test_text_starting_like_a_magic_number_is_still_text(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"  # "BZh" without its block-size digit is no bzip2 header
    path.write_text("BZhx comment\n" + BODY)
    assert len(read_carmen(path)) == 40


def test_a_bzip2_log_without_newlines_is_refused_before_it_is_held(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Megabytes of one byte compress to a few hundred bytes: read as one line, they
    # would fill the memory; only LINE_MAX + 1 characters are read.
    path = tmp_path / "log.bz2"
    path.write_bytes(bz2.compress(b"FLASER 1 " + b"1" * (8 << 20)))
    monkeypatch.setattr(_carmen, "LINE_MAX", 1000)
    tracemalloc.start()
    try:
        with pytest.raises(ValueError, match=":1: line longer than 1000"):
            read_carmen(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2 << 20
