"""Review 51 (PORTFILES): CARMEN logs edited or re-saved by other tools, from the real Intel log.

A line's message name was split off at a space only: a tab after it (or a blank
before it), as a hand edit or a spreadsheet export leaves, made a FLASER or ODOM
line an unknown kind, dropped without a word; MRPT's and GMapping's CARMEN
readers split at any blank. A UTF-16 copy (Windows PowerShell 5's ``>``) read as
"no FLASER or ROBOTLASER1 lines"; it is now named.
"""

from __future__ import annotations

import gzip
import re
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import CarmenLog, read_carmen

_LOG = Path("carmen-logs") / "intel-corrected.log.gz"


def _head(shared_data: Path, scans: int = 30) -> bytes:
    """The real log's lines up to its ``scans``-th FLASER line."""
    lines = gzip.decompress((shared_data / _LOG).read_bytes()).split(b"\n")
    kept: list[bytes] = []
    for line in lines:
        kept.append(line)
        scans -= line.startswith(b"FLASER ")
        if scans == 0:
            break
    return b"\n".join(kept) + b"\n"


def _assert_same(got: CarmenLog, ref: CarmenLog) -> None:
    assert len(got.scans) == len(ref.scans)
    for a, b in zip(got.scans, ref.scans, strict=True):
        assert np.array_equal(a.ranges, b.ranges)
        assert a.range_max == b.range_max
    assert np.array_equal(got.times, ref.times)
    assert np.array_equal(got.odometry, ref.odometry)
    assert got.laser_poses == ref.laser_poses
    assert got.robot_poses == ref.robot_poses


@pytest.mark.parametrize(
    ("label", "edit"),
    [
        ("tab after every name", lambda t: re.sub(rb"(?m)^(FLASER|ODOM) ", rb"\1\t", t)),
        ("tabs between all fields", lambda t: t.replace(b" ", b"\t")),
        ("blanks before every name", lambda t: re.sub(rb"(?m)^(FLASER|ODOM)", rb" \t\1", t)),
        (
            "tab after the name, CRLF",
            lambda t: t.replace(b"FLASER ", b"FLASER\t").replace(b"\n", b"\r\n"),
        ),
    ],
)
def test_blanks_around_the_message_name_read_as_spaces(
    shared_data: Path, tmp_path: Path, label: str, edit: object
) -> None:
    text = _head(shared_data)
    (tmp_path / "ref.log").write_bytes(text)
    ref = read_carmen(tmp_path / "ref.log")
    assert len(ref.scans) == 30 and len(ref.odometry) > 30
    assert callable(edit)
    (tmp_path / "edited.log").write_bytes(edit(text))
    _assert_same(read_carmen(tmp_path / "edited.log"), ref)


def test_one_tabbed_line_among_spaced_ones_is_not_lost(shared_data: Path, tmp_path: Path) -> None:
    # The silent case: the others still read, so nothing said a scan was missing.
    text = _head(shared_data)
    (tmp_path / "ref.log").write_bytes(text)
    ref = read_carmen(tmp_path / "ref.log")
    assert b"\nFLASER " in text
    (tmp_path / "edited.log").write_bytes(text.replace(b"\nFLASER ", b"\nFLASER\t", 1))
    _assert_same(read_carmen(tmp_path / "edited.log"), ref)


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-be", "utf-32"])
def test_utf16_and_utf32_copies_are_named(shared_data: Path, tmp_path: Path, encoding: str) -> None:
    text = _head(shared_data, scans=3).decode("ascii")
    data = text.encode(encoding)
    if encoding == "utf-16-be":
        data = b"\xfe\xff" + data
    (tmp_path / "log.txt").write_bytes(data)
    with pytest.raises(ValueError, match=r"log\.txt: UTF-16 text \(or UTF-32\), not a CARMEN log"):
        read_carmen(tmp_path / "log.txt")
    (tmp_path / "log.txt.gz").write_bytes(gzip.compress(data))
    with pytest.raises(ValueError, match=r"log\.txt\.gz: UTF-16 text"):
        read_carmen(tmp_path / "log.txt.gz")
