"""read_carmen refuses tar archives, plain or compressed (review 27).

Decompressed and read as text, a ``.tar.gz`` of one log gave that log's lines
after a header line the parser skipped, and a tar of several logs gave them
all, one after the other, as if they were one log: a map built from it
overlaid several runs. A tar archive is now refused naming what it is, as a
zip already was.
"""

from __future__ import annotations

import io
import tarfile
from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen

BODY = ("ODOM 0.5 0 0 0 0 0 0.5 h 0.5\n"
        "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 1.0 host 1.0\n"
        ) * 5  # fmt: skip


def _tar(path: Path, mode: str, names: list[str], fmt: int) -> None:
    with tarfile.open(path, mode, format=fmt) as archive:
        for name in names:
            info = tarfile.TarInfo(name)
            data = BODY.encode()
            info.size = len(data)
            archive.addfile(info, io.BytesIO(data))


@pytest.mark.parametrize(
    ("mode", "compressed"),
    [("w", ""), ("w:gz", " (gzip-compressed)"), ("w:bz2", " (bzip2-compressed)"),
     ("w:xz", " (xz-compressed)")],
)  # fmt: skip
@pytest.mark.parametrize("fmt", [tarfile.GNU_FORMAT, tarfile.PAX_FORMAT, tarfile.USTAR_FORMAT])
@pytest.mark.parametrize("names", [["a.log"], ["a.log", "b.log"]])
def test_a_tar_archive_is_refused_naming_it(
    tmp_path: Path, mode: str, compressed: str, fmt: int, names: list[str]
) -> None:
    path = tmp_path / "logs.tar"
    _tar(path, mode, names, fmt)
    before = path.read_bytes()
    with pytest.raises(ValueError, match="a tar archive") as info:
        read_carmen(path)
    assert f"{path}: a tar archive{compressed}, not a CARMEN log" in str(info.value)
    assert path.read_bytes() == before


def test_a_log_line_holding_ustar_where_a_tar_has_it_is_read(tmp_path: Path) -> None:
    # The magic alone is not enough: a tar header has NUL bytes before it.
    comment = "#" + "x" * 256 + "ustar header-like text\n"
    assert comment[257:262] == "ustar"
    path = tmp_path / "log.log"
    path.write_text(comment + BODY)
    plain = tmp_path / "plain.log"
    plain.write_text(BODY)
    got, want = read_carmen(path), read_carmen(plain)
    assert len(got) == len(want) == 5
    for a, b in zip(got.scans, want.scans, strict=True):
        assert (a.ranges == b.ranges).all()
    assert got.robot_poses == want.robot_poses


def test_an_empty_file_still_reads_as_no_laser_lines(tmp_path: Path) -> None:
    path = tmp_path / "empty.log"
    path.write_text("")
    with pytest.raises(ValueError, match="no FLASER") as info:
        read_carmen(path)
    assert "tar" not in str(info.value)
