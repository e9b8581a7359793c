"""The damage check after a malformed line stops where the parser would (review 28, LAST).

Review 27 reads the rest of a compressed log after a malformed line, to tell a
damaged file (whose check fails at its end) from a malformed line. Its docstring
says this costs "at most what reading the whole file costs"; but the parser
refuses a line longer than ``LINE_MAX`` (binary data, as a decompression bomb) at
once, while the check read through all of it: a 4.7 MB gzip file of one malformed
line and 1 GB of zeros took 0.81 s to refuse instead of 0.01 s for the same file
without the line, in proportion to the data decompressed. The check now stops
at such a line, as the parser does (0.03 s for that file).
"""

from __future__ import annotations

import gzip
from collections.abc import Iterator
from pathlib import Path

import pytest

from navkit.mapping.io import _carmen, read_carmen


def test_the_damage_check_stops_at_binary_data(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "bomb.log.gz"
    zeros = b"\0" * (1 << 20)
    with gzip.open(path, "wb") as fh:
        fh.write(b"FLASER 3 1.0 2.0 x\n")  # malformed: too few fields
        for _ in range(8 * _carmen.LINE_MAX >> 20):  # eight lines beyond LINE_MAX
            fh.write(zeros)
    read: list[int] = []
    lines = _carmen._lines

    def counted(*args: object) -> Iterator[str]:
        for line in lines(*args):  # type: ignore[arg-type]
            read.append(len(line))
            yield line

    monkeypatch.setattr(_carmen, "_lines", counted)
    with pytest.raises(ValueError, match=r":1: malformed FLASER line"):
        read_carmen(path)
    # The malformed line and the first line beyond LINE_MAX, not the eight (before: 9
    # lines, 64 MiB).
    assert len(read) == 2
    assert read[1] == _carmen.LINE_MAX + 1


def test_a_damaged_file_is_still_named_damaged(tmp_path: Path) -> None:
    # A log whose bad line is followed by text and a truncated end: the check reads on.
    path = tmp_path / "cut.log.gz"
    body = b"FLASER 3 1.0 2.0 x\n" + b"ODOM 0.5 0 0 0 0 0 0.5 h 0.5\n" * 20000
    path.write_bytes(gzip.compress(body)[:-12])
    with pytest.raises(ValueError, match=r"corrupt or truncated gzip file \(line 1 came out"):
        read_carmen(path)
