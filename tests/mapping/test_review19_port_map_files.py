"""Map files, PGM images and CARMEN logs from Windows, read on Linux (the portability review).

Windows refuses to open a folder as a file with ``PermissionError`` (not
``IsADirectoryError``), writes text files with CRLF line ends, and a map
YAML written there may name its image with backslashes (``maps\\office.pgm``).
Folders are simulated by a fake ``os.open`` that behaves as Windows' does.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_carmen, read_map, write_map
from navkit.mapping.io._map_files import read_map_yaml, read_pgm

_NAME = st.text(alphabet="abcdefghijklmnopqrstuvwxyz0123456789_-", min_size=1, max_size=8)


def _windows_open(monkeypatch: pytest.MonkeyPatch) -> None:
    """``os.open`` of a folder fails as on Windows: EACCES."""
    real = os.open

    def fake(path: Any, flags: int, mode: int = 0o777, *, dir_fd: Any = None) -> int:
        if os.path.isdir(path):
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        return real(path, flags, mode, dir_fd=dir_fd)

    monkeypatch.setattr(os, "open", fake)


def test_folder_read_as_pgm_or_yaml_is_named_a_directory(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    folder = tmp_path / "map.pgm"
    folder.mkdir()
    _windows_open(monkeypatch)
    with pytest.raises(ValueError, match=r"PGM image .*map\.pgm is a directory"):
        read_pgm(folder)
    with pytest.raises(ValueError, match=r"map YAML file .*map\.pgm is a directory"):
        read_map_yaml(folder)
    with pytest.raises(ValueError, match="not a regular file"):  # checked by name first
        read_carmen(folder)


def test_unreadable_file_still_raises_permission_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pgm = tmp_path / "a.pgm"
    pgm.write_bytes(b"P5 1 1 255 \x00")
    real = os.open

    def refuse(path: Any, flags: int, mode: int = 0o777, *, dir_fd: Any = None) -> int:
        if os.fspath(path) == os.fspath(pgm):
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        return real(path, flags, mode, dir_fd=dir_fd)

    monkeypatch.setattr(os, "open", refuse)
    with pytest.raises(PermissionError):
        read_pgm(pgm)


def _grid(cells: list[list[int]]) -> OccupancyGrid:
    """0 free, 1 occupied, 2 unknown."""
    p = np.choose(np.array(cells), [0.0, 1.0, 0.5])
    return OccupancyGrid.from_probabilities(p, resolution=0.25)


_CELLS = st.integers(1, 5).flatmap(
    lambda cols: st.lists(
        st.lists(st.integers(0, 2), min_size=cols, max_size=cols), min_size=1, max_size=5
    )
)


@given(cells=_CELLS, folders=st.lists(_NAME, min_size=1, max_size=3), crlf=st.booleans())
@settings(max_examples=25, deadline=None)
def test_windows_written_yaml_reads_as_on_windows(
    tmp_path_factory: pytest.TempPathFactory, cells: list[list[int]], folders: list[str],
    crlf: bool,
) -> None:  # fmt: skip
    root = tmp_path_factory.mktemp("winmap")
    sub = root.joinpath(*folders)
    sub.mkdir(parents=True, exist_ok=True)
    grid = _grid(cells)
    write_map(grid, sub / "m.yaml")
    text = (sub / "m.yaml").read_text(encoding="utf-8")
    text = text.replace("image: m.pgm", "image: " + "\\".join([*folders, "m.pgm"]))
    if crlf:
        text = text.replace("\n", "\r\n")
    (root / "m.yaml").write_bytes(text.encode("utf-8"))
    meta = read_map_yaml(root / "m.yaml")
    assert meta.image == sub / "m.pgm"
    back = read_map(root / "m.yaml")
    assert np.array_equal(back.occupied(), grid.occupied())
    assert np.array_equal(back.unknown(), grid.unknown())


def test_a_file_named_with_a_backslash_comes_first(tmp_path: Path) -> None:
    # Where a backslash is no separator a file may have one in its name: that file is
    # the image, as before.
    grid = _grid([[1, 0]])
    write_map(grid, tmp_path / "m.yaml")
    (tmp_path / "sub").mkdir()
    (tmp_path / "m.pgm").rename(tmp_path / "sub\\m.pgm")
    text = (tmp_path / "m.yaml").read_text(encoding="utf-8")
    (tmp_path / "m.yaml").write_text(text.replace("image: m.pgm", "image: sub\\m.pgm"),
                                     encoding="utf-8")  # fmt: skip
    assert read_map_yaml(tmp_path / "m.yaml").image == tmp_path / "sub\\m.pgm"
    assert read_map(tmp_path / "m.yaml").occupied().tolist() == [[True, False]]


def test_windows_absolute_image_path_is_named(tmp_path: Path) -> None:
    write_map(_grid([[0]]), tmp_path / "m.yaml")
    text = (tmp_path / "m.yaml").read_text(encoding="utf-8")
    (tmp_path / "m.yaml").write_text(text.replace("image: m.pgm", "image: C:\\maps\\m.pgm"),
                                     encoding="utf-8")  # fmt: skip
    with pytest.raises(FileNotFoundError, match="a Windows path"):
        read_map_yaml(tmp_path / "m.yaml")


@given(cells=_CELLS, maxval=st.integers(1, 65535))
@settings(max_examples=25, deadline=None)
def test_crlf_pgm_headers_and_p2_rasters(
    tmp_path_factory: pytest.TempPathFactory, cells: list[list[int]], maxval: int
) -> None:
    folder = tmp_path_factory.mktemp("crlfpgm")
    values = np.array(cells) * maxval // 2
    rows, cols = values.shape
    body = "\n".join(" ".join(map(str, row)) for row in values.tolist())
    lf = f"P2\n# a comment\n{cols} {rows}\n{maxval}\n{body}\n"
    (folder / "lf.pgm").write_bytes(lf.encode())
    (folder / "crlf.pgm").write_bytes(lf.replace("\n", "\r\n").encode())
    assert np.array_equal(read_pgm(folder / "crlf.pgm"), read_pgm(folder / "lf.pgm"))
    # P5: CRLF between header fields; the single byte after maxval is the raster's
    # separator (a second one would be a pixel).
    raster = values.astype(">u2" if maxval > 255 else np.uint8).tobytes()
    head = f"P5\r\n# by Windows\r\n{cols} {rows}\r\n{maxval}\n".encode()
    (folder / "p5.pgm").write_bytes(head + raster)
    assert np.array_equal(read_pgm(folder / "p5.pgm"), read_pgm(folder / "lf.pgm"))


def test_crlf_carmen_log_reads_as_lf(tmp_path: Path) -> None:
    lines = [
        "# a comment",
        "ODOM 0.5 0.25 0.1 0.2 0 0 10.0 host 10.0",
        "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.5 host 12.6",
        "ROBOTLASER1 0 -1.5 3.0 0.5 20.0 0 0 3 1.0 2.0 3.0 0 1 2 0 0 1 2 0 "
        "0.5 0.5 0.5 1 13.0 host 13.0",
    ]
    text = "\n".join(lines) + "\n"
    (tmp_path / "lf.log").write_bytes(text.encode())
    (tmp_path / "crlf.log").write_bytes(text.replace("\n", "\r\n").encode())
    lf, crlf = read_carmen(tmp_path / "lf.log"), read_carmen(tmp_path / "crlf.log")
    assert len(crlf.scans) == len(lf.scans) == 2
    assert np.array_equal(crlf.times, lf.times)
    assert np.array_equal(crlf.odometry, lf.odometry)
    for a, b in zip(crlf.scans, lf.scans, strict=True):
        assert np.array_equal(a.ranges, b.ranges)
    assert crlf.laser_poses == lf.laser_poses


@pytest.mark.parametrize(
    ("encoding", "bom"),
    [
        ("utf-8", b"\xef\xbb\xbf"),  # Notepad's UTF-8
        ("utf-16-le", b"\xff\xfe"),  # Windows PowerShell 5's ">" and Out-File
        ("utf-16-be", b"\xfe\xff"),
        ("utf-32-le", b"\xff\xfe\x00\x00"),
        ("utf-32-be", b"\x00\x00\xfe\xff"),
    ],
)
def test_yaml_with_a_byte_order_mark_reads_as_utf8(
    tmp_path: Path, encoding: str, bom: bytes
) -> None:
    grid = _grid([[1, 0, 2], [0, 0, 1]])
    write_map(grid, tmp_path / "m.yaml")
    text = (tmp_path / "m.yaml").read_text(encoding="utf-8").replace("\n", "\r\n")
    (tmp_path / "w.yaml").write_bytes(bom + text.encode(encoding))
    assert read_map_yaml(tmp_path / "w.yaml") == read_map_yaml(tmp_path / "m.yaml")
    back = read_map(tmp_path / "w.yaml")
    assert np.array_equal(back.occupied(), grid.occupied())
    # The saves that look at an existing YAML read it too: the image is this map's,
    # so saving over it is no clash with "another map's image".
    (tmp_path / "w.pgm").write_bytes((tmp_path / "m.pgm").read_bytes())
    (tmp_path / "w.yaml").write_bytes(bom + text.replace("m.pgm", "w.pgm").encode(encoding))
    write_map(grid, tmp_path / "w.yaml")


def test_utf16_without_its_mark_is_refused(tmp_path: Path) -> None:
    (tmp_path / "m.yaml").write_bytes("image: m.pgm\n".encode("utf-16-le"))
    with pytest.raises(ValueError, match=r"not a map YAML|expected 'key: value'"):
        read_map_yaml(tmp_path / "m.yaml")


def test_broken_utf16_is_named(tmp_path: Path) -> None:
    (tmp_path / "m.yaml").write_bytes(b"\xff\xfe" + "image: m".encode("utf-16-le") + b"\x00\xd8")
    with pytest.raises(ValueError, match=r"not UTF-16 text \(byte 0x00 at offset 18\)"):
        read_map_yaml(tmp_path / "m.yaml")
