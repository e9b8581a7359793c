"""Mutation-testing gaps of the map_server YAML / image reading and writing (review 10).

Mutants of ``navkit/mapping/io/_map_files.py`` that the earlier tests let through:
a ``mode`` not lower-cased (map_server lower-cases it), a quoted ``negate: "true"``
read as false, a PGM ``maxval`` of 256 read with one byte a sample or one of 65536
accepted (the PGM specification: 1 byte below 256, else 2; maxval < 65536),
``raw`` mode not rounding a 16-bit grey to a whole percentage (map_server:
``round(shade * 255)``), the colour channels of a 16-bit RGB PNG not averaged,
and trinary mode writing unknown cells at the edge of the unknown band rather
than in its middle when 205 is not unknown. Expected values are computed here
from those rules, not from navkit.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

OCC, FREE = 0.65, 0.196


def _yaml(folder: Path, image: str, *, mode: str | None = "trinary", negate: str = "0",
          occ: float = OCC, free: float = FREE) -> Path:
    text = (
        f"image: {image}\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: {negate}\n"
        f"occupied_thresh: {occ}\nfree_thresh: {free}\n"
    )
    if mode is not None:
        text += f"mode: {mode}\n"
    path = folder / "m.yaml"
    path.write_text(text)
    return path


def _p5(folder: Path, levels: list[int], maxval: int, *, name: str = "m.pgm") -> None:
    """A one-row binary PGM: 1 byte a sample below maxval 256, else 2 (big-endian)."""
    dtype = np.uint8 if maxval < 256 else np.dtype(">u2")
    body = np.asarray(levels, dtype=np.int64).astype(dtype).tobytes()
    (folder / name).write_bytes(f"P5\n{len(levels)} 1\n{maxval}\n".encode() + body)


def _p(grid: OccupancyGrid) -> np.ndarray:
    """The probabilities from the log-odds, independently of OccupancyGrid.probability."""
    logodds = np.asarray(grid.logodds, dtype=np.float64)
    out: np.ndarray = 1.0 / (1.0 + np.exp(-logodds))
    return out


def _scale_p(p: np.ndarray) -> np.ndarray:
    """map_server's scale mode for opaque pixels of occupancy ``p``, as the grid stores it."""
    out: np.ndarray = np.clip(np.where(p > OCC, 1.0, np.where(p < FREE, 0.0, p)), 0.001, 0.999)
    return out


# --------------------------------------------------------------------- YAML values
@pytest.mark.parametrize("spelling", ["Trinary", "TRINARY", "Scale", "SCALE", "Raw", "RAW"])
def test_the_mode_is_read_whatever_its_case(tmp_path: Path, spelling: str) -> None:
    """map_server lower-cases ``mode``: ``Trinary`` is trinary, ``Raw`` is raw."""
    _p5(tmp_path, [0, 40, 100, 205, 230, 254], 255)
    lower = read_map(_yaml(tmp_path, "m.pgm", mode=spelling.lower()))
    other = read_map(_yaml(tmp_path, "m.pgm", mode=spelling))
    np.testing.assert_array_equal(other.logodds, lower.logodds)
    # The three modes read these levels differently, so the case cannot be ignored by luck.
    by_mode = {m: read_map(_yaml(tmp_path, "m.pgm", mode=m)).logodds for m in
               ("trinary", "scale", "raw")}
    for m, logodds in by_mode.items():
        if m != spelling.lower():
            assert not np.array_equal(logodds, other.logodds)


def test_the_mode_defaults_to_trinary(tmp_path: Path) -> None:
    _p5(tmp_path, [0, 40, 100, 205, 230, 254], 255)
    np.testing.assert_array_equal(
        read_map(_yaml(tmp_path, "m.pgm", mode=None)).logodds,
        read_map(_yaml(tmp_path, "m.pgm", mode="trinary")).logodds,
    )


@pytest.mark.parametrize(("text", "same_as"), [
    ('"true"', "1"), ("'TRUE'", "1"), ('"True"', "1"), ('"1"', "1"),
    ('"false"', "0"), ("'FALSE'", "0"), ('"0"', "0"), ("true", "1"), ("false", "0"),
])
def test_a_quoted_negate_means_what_it_says(tmp_path: Path, text: str, same_as: str) -> None:
    # 40 is occupied with negate 0 (p = 1 - 40/255 = 0.84) and free with negate 1 (0.16).
    _p5(tmp_path, [40, 230], 255)
    plain = read_map(_yaml(tmp_path, "m.pgm", negate=same_as))
    spelled = read_map(_yaml(tmp_path, "m.pgm", negate=text))
    np.testing.assert_array_equal(spelled.logodds, plain.logodds)
    assert plain.occupied()[0, 0] == (same_as == "0")
    assert plain.free()[0, 0] == (same_as == "1")


# --------------------------------------------------------------------- PGM maxval
@pytest.mark.parametrize("maxval", [256, 257, 1000, 65535])
def test_a_pgm_maxval_of_256_or_more_has_two_byte_samples(tmp_path: Path, maxval: int) -> None:
    levels = [0, maxval * 2 // 5, maxval // 2 + 1, maxval * 3 // 5, maxval * 3 // 4, maxval]
    _p5(tmp_path, levels, maxval)
    grid = read_map(_yaml(tmp_path, "m.pgm", mode="scale"))
    # Scale mode: p = 1 - v / maxval, 1 above occupied_thresh, 0 below free_thresh
    # (clipped by the grid to [0.001, 0.999]).
    expected = _scale_p(1.0 - np.asarray(levels, dtype=np.float64) / maxval)
    np.testing.assert_allclose(_p(grid)[0], expected, rtol=0, atol=1e-5)


@pytest.mark.parametrize("ascii_pgm", [False, True])
def test_a_pgm_maxval_of_65536_is_refused_naming_the_file(tmp_path: Path, ascii_pgm: bool) -> None:
    if ascii_pgm:
        (tmp_path / "m.pgm").write_bytes(b"P2\n2 1\n65536\n0 1\n")
    else:
        (tmp_path / "m.pgm").write_bytes(b"P5\n2 1\n65536\n" + b"\x00\x00\x00\x01")
    with pytest.raises(ValueError, match=r"m\.(yaml|pgm).*maxval"):
        read_map(_yaml(tmp_path, "m.pgm"))


# --------------------------------------------------------------------- raw mode
def test_raw_mode_rounds_a_16_bit_grey_to_a_whole_percentage(tmp_path: Path) -> None:
    """map_server's raw mode: ``round(shade * 255)``, a percentage when <= 100, else unknown."""
    levels = [257 * 37 + 100, 257 * 60 - 120, 257 * 12 + 128, 257 * 100 + 128, 257 * 100 + 129]
    _p5(tmp_path, levels, 65535)
    grid = read_map(_yaml(tmp_path, "m.pgm", mode="raw"))
    percent = np.round(np.asarray(levels, dtype=np.float64) * 255.0 / 65535.0)
    assert percent.tolist() == [37.0, 60.0, 12.0, 100.0, 101.0]
    expected = np.clip(np.where(percent > 100, 0.5, percent / 100.0), 0.001, 0.999)
    np.testing.assert_allclose(_p(grid)[0], expected, rtol=0, atol=1e-6)


# --------------------------------------------------------------------- 16-bit colour PNG
def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def _rgb16_png(rgb: np.ndarray) -> bytes:
    """A PNG of colour type 2 (RGB), 16 bits a sample, filter 0."""
    rows, cols, _ = rgb.shape
    samples = rgb.astype(">u2")
    raw = b"".join(b"\x00" + row.tobytes() for row in samples)
    header = struct.pack(">IIBBBBB", cols, rows, 16, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw))
            + _chunk(b"IEND", b""))


@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_a_16_bit_rgb_png_is_read_as_the_mean_of_its_channels(tmp_path: Path, mode: str) -> None:
    pytest.importorskip("PIL")
    rgb = np.array([[[65535, 0, 0], [0, 65535, 65535], [40000, 20000, 3000],
                     [60000, 60000, 1000], [60000, 65535, 50000]]], dtype=np.uint16)
    (tmp_path / "m.png").write_bytes(_rgb16_png(rgb))
    grid = read_map(_yaml(tmp_path, "m.png", mode=mode))
    p = 1.0 - rgb.astype(np.float64).mean(axis=2)[0] / 65535.0
    if mode == "trinary":
        got = np.where(grid.occupied()[0], 1, np.where(grid.free()[0], 0, -1))
        expected = np.where(p > OCC, 1, np.where(p < FREE, 0, -1))
        np.testing.assert_array_equal(got, expected)
        assert len(set(expected.tolist())) == 3  # all three classes are exercised
    else:
        np.testing.assert_allclose(_p(grid)[0], _scale_p(p), rtol=0, atol=1e-5)
        assert np.sum((p > FREE) & (p < OCC)) >= 2  # in-between values are compared


# --------------------------------------------------------------------- writing
def test_trinary_writes_unknown_cells_in_the_middle_of_the_band_when_205_is_not_unknown(
    tmp_path: Path,
) -> None:
    # 205 reads p = 1 - 205/255 = 0.196 < free_thresh 0.4: free, so another grey is needed.
    occ, free = 0.9, 0.4
    logodds = np.array([[0.0, 5.0, -5.0]])  # unknown (p = 0.5), occupied, free
    grid = OccupancyGrid(logodds, resolution=0.05, occupied_thresh=occ, free_thresh=free)
    yaml_path = tmp_path / "m.yaml"
    assert write_map(grid, yaml_path) == tmp_path / "m.pgm"
    data = (tmp_path / "m.pgm").read_bytes()
    pixels = np.frombuffer(data[-3:], dtype=np.uint8)
    levels = np.arange(256)
    reading = 1.0 - levels / 255.0
    band = levels[(free <= reading) & (reading <= occ)]
    middle = 0.5 * (free + occ)
    want = int(band[np.argmin(np.abs((1.0 - band / 255.0) - middle))])
    assert want == 89  # 1 - 89/255 = 0.651, the level nearest 0.65
    assert pixels.tolist() == [want, 0, 254]
    back = read_map(yaml_path)
    np.testing.assert_array_equal(back.unknown(), grid.unknown())
