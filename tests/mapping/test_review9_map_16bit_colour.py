"""Map images with 16 bits per colour channel: read at full depth, or refused; never truncated.

Pillow opens 16-bit RGB, grey + alpha and RGBA PNGs as 8-bit "RGB"/"RGBA" (the
high byte of every sample), which moved pixels near a threshold to the other
side. Nav2's map_server (GraphicsMagick) averages the full-depth channels:
``shade = mean(channels) / 65535``, ``p = 1 - shade``, and in scale mode any
alpha below 65535 is unknown. The images are written here with numpy, zlib and
struct (Pillow cannot write 16-bit colour).
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

pytest.importorskip("PIL")

# PNG colour types with their channel count.
_RGB, _GREY_ALPHA, _RGBA = 2, 4, 6
_CHANNELS = {_RGB: 3, _GREY_ALPHA: 2, _RGBA: 4}


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def _png16(samples: np.ndarray, colour_type: int, *, sub_filter: bool = False) -> bytes:
    """A non-interlaced PNG of 16-bit ``samples`` (rows, cols, channels)."""
    rows, cols, channels = samples.shape
    assert channels == _CHANNELS[colour_type]
    bpp = 2 * channels
    raw = b""
    for row in samples:
        line = row.astype(">u2").tobytes()
        if sub_filter:  # filter 1 (Sub): each byte minus the byte one pixel left
            left = bytes(bpp) + line[:-bpp]
            line = bytes((a - b) & 255 for a, b in zip(line, left, strict=True))
        raw += (b"\x01" if sub_filter else b"\x00") + line
    header = struct.pack(">IIBBBBB", cols, rows, 16, colour_type, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", header)
        + _chunk(b"IDAT", zlib.compress(raw))
        + _chunk(b"IEND", b"")
    )


def _tiff16_rgb(samples: np.ndarray) -> bytes:
    """An uncompressed little-endian TIFF of 16-bit RGB ``samples`` (rows, cols, 3)."""
    rows, cols, _ = samples.shape
    data = samples.astype("<u2").tobytes()
    n = 9
    bps_offset = 8 + 2 + 12 * n + 4
    data_offset = bps_offset + 6

    def long(tag: int, value: int) -> bytes:
        return struct.pack("<HHII", tag, 4, 1, value)

    def short(tag: int, value: int) -> bytes:
        return struct.pack("<HHIHH", tag, 3, 1, value, 0)

    entries = [
        long(256, cols),
        long(257, rows),
        struct.pack("<HHII", 258, 3, 3, bps_offset),  # BitsPerSample 16, 16, 16
        short(259, 1),  # no compression
        short(262, 2),  # RGB
        long(273, data_offset),
        short(277, 3),
        long(278, rows),
        long(279, len(data)),
    ]
    return (
        b"II*\x00"
        + struct.pack("<IH", 8, n)
        + b"".join(entries)
        + b"\x00\x00\x00\x00"
        + struct.pack("<HHH", 16, 16, 16)
        + data
    )


def _write(folder: Path, image: bytes, name: str, mode: str, free: float = 0.196) -> Path:
    (folder / name).write_bytes(image)
    yaml_path = folder / "map.yaml"
    yaml_path.write_text(
        f"image: {name}\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
        f"occupied_thresh: 0.65\nfree_thresh: {free}\nmode: {mode}\n"
    )
    return yaml_path


def _nav2_trinary(samples: np.ndarray, colour_type: int, occ: float, free: float) -> np.ndarray:
    """Nav2's trinary class of each pixel: 1 occupied, 0 free, -1 unknown (image rows)."""
    s = samples.astype(np.float64)
    if colour_type == _RGB:
        channels = [s[..., 0], s[..., 1], s[..., 2]]
    elif colour_type == _GREY_ALPHA:  # GraphicsMagick: grey in red, green and blue
        channels = [s[..., 0]] * 3 + [s[..., 1]]
    else:
        channels = [s[..., 0], s[..., 1], s[..., 2], s[..., 3]]
    shade = sum(channels) / len(channels) / 65535.0
    p = 1.0 - shade
    return np.where(p > occ, 1, np.where(p < free, 0, -1))


def _classes(grid) -> np.ndarray:  # type: ignore[no-untyped-def]
    occupied = grid.occupied()[::-1]
    free = grid.free()[::-1]
    return np.where(occupied, 1, np.where(free, 0, -1))


def _opaque_samples(levels: np.ndarray, colour_type: int) -> np.ndarray:
    samples = np.repeat(levels[..., np.newaxis], _CHANNELS[colour_type], axis=-1)
    if colour_type in (_GREY_ALPHA, _RGBA):
        samples[..., -1] = 65535
    return samples


@pytest.mark.parametrize("colour_type", [_RGB, _GREY_ALPHA, _RGBA])
@pytest.mark.parametrize("sub_filter", [False, True])
def test_trinary_classes_use_all_16_bits(
    tmp_path: Path, colour_type: int, sub_filter: bool
) -> None:
    # 16-bit levels whose high byte alone (v >> 8, what Pillow kept) is classed
    # differently by Nav2, near free_thresh or occupied_thresh, plus random ones.
    every = np.arange(0, 65536, 5, dtype=np.uint16)
    exact = _nav2_trinary(_opaque_samples(every, colour_type), colour_type, 0.65, 0.196)
    high = _opaque_samples((every >> 8) * 257, colour_type)
    straddling = every[exact != _nav2_trinary(high, colour_type, 0.65, 0.196)]
    assert straddling.size > 0
    rng = np.random.default_rng(7)
    picks = np.concatenate((rng.choice(straddling, 12), rng.integers(0, 65536, 12)))
    samples = _opaque_samples(picks.astype(np.uint16).reshape(4, 6), colour_type)
    path = _write(tmp_path, _png16(samples, colour_type, sub_filter=sub_filter), "m.png", "trinary")
    expected = _nav2_trinary(samples, colour_type, 0.65, 0.196)
    np.testing.assert_array_equal(_classes(read_map(path)), expected)


def test_scale_mode_alpha_below_full_is_unknown(tmp_path: Path) -> None:
    # Nav2 scale mode: a pixel whose alpha is not the full 65535 is unknown; the
    # high byte of 65534 is 255, which read as opaque.
    samples = np.zeros((1, 3, 4), dtype=np.uint16)
    samples[..., :3] = 30000  # p = 1 - 30000 / 65535 = 0.54, between the thresholds
    samples[0, :, 3] = [65535, 65534, 65280]
    grid = read_map(_write(tmp_path, _png16(samples, _RGBA), "m.png", "scale"))
    p = 1.0 / (1.0 + np.exp(-grid.logodds[0].astype(np.float64)))
    # The opaque pixel keeps its own p; the others are unknown, p = 0.5.
    np.testing.assert_allclose(p, [1.0 - 30000 / 65535, 0.5, 0.5], atol=1e-6)


def test_rgb_with_16bit_transparent_colour(tmp_path: Path) -> None:
    samples = np.array([[[1000, 2000, 3000], [0x1234, 0x5678, 0x9ABC]]], dtype=np.uint16)
    png = _png16(samples, _RGB)
    trns = _chunk(b"tRNS", struct.pack(">HHH", 0x1234, 0x5678, 0x9ABC))
    png = png[:33] + trns + png[33:]  # after IHDR (8 + 25 bytes)
    grid = read_map(_write(tmp_path, png, "m.png", "scale"))
    assert grid.unknown()[0].tolist() == [False, True]


def test_16bit_colour_tiff_is_refused_naming_the_file(tmp_path: Path) -> None:
    samples = np.full((2, 2, 3), 52700, dtype=np.uint16)
    path = _write(tmp_path, _tiff16_rgb(samples), "deep.tif", "trinary")
    with pytest.raises(ValueError, match=r"deep\.tif.*16 bits per colour channel"):
        read_map(path)
