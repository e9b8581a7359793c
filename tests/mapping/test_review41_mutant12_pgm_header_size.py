"""A PGM header of up to 64 KiB is read, one byte more is refused (MUTANT12).

Mutation review 41: ``_PGM_HEADER_MAX`` at 32 KiB instead of 64 KiB survived, as no
test read a header near the documented bound ("A PGM header (magic, comments,
width, height, maxval) must fit in 64 KiB"). A comment fills the header up to
exactly 65536 bytes, the whitespace byte after ``maxval`` included, or one more.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import read_map

_LIMIT = 64 * 1024


def _header(size: int, magic: bytes) -> bytes:
    """A PGM header for 2 x 1 pixels of maxval 255, of exactly ``size`` bytes."""
    tail = b"\n2 1\n255\n"
    head = magic + b"\n#" + b" comment" * (size // 8)
    return head[: size - len(tail)] + tail


def _map(folder: Path, header: bytes, raster: bytes) -> Path:
    (folder / "m.pgm").write_bytes(header + raster)
    path = folder / "m.yaml"
    path.write_text(
        "image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n"
    )
    return path


@pytest.mark.parametrize(("magic", "raster"), [(b"P5", b"\x00\xfe"), (b"P2", b"0 254\n")])
def test_a_header_of_64_kib_is_read(tmp_path: Path, magic: bytes, raster: bytes) -> None:
    header = _header(_LIMIT, magic)
    assert len(header) == _LIMIT
    grid = read_map(_map(tmp_path, header, raster))
    # Black (0) is occupied, near-white (254) free: the pixels after the header.
    assert grid.occupied().tolist() == [[True, False]]
    assert grid.free().tolist() == [[False, True]]


@pytest.mark.parametrize(("magic", "raster"), [(b"P5", b"\x00\xfe"), (b"P2", b"0 254\n")])
def test_a_header_one_byte_longer_is_refused_naming_the_image(
    tmp_path: Path, magic: bytes, raster: bytes
) -> None:
    header = _header(_LIMIT + 1, magic)
    assert len(header) == _LIMIT + 1
    with pytest.raises(ValueError, match=r"m\.pgm: PGM header must end with one whitespace"):
        read_map(_map(tmp_path, header, raster))
