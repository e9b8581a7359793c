"""Mutation-testing gaps of 16-bit grey + alpha PNG maps (review 10).

A 16-bit grey + alpha PNG is decoded by Pillow to 8 bits and its other bytes
are read by a second decode; a mutant that dropped the grey's low byte, or
swapped the alpha's two bytes, passed the earlier tests (their grey levels
straddled thresholds only by the high byte, their alpha was always opaque).
Expected values follow Nav2's map_server (GraphicsMagick): the grey in red,
green and blue, ``shade = mean(channels) / 65535`` (alpha included in trinary
mode), ``p = 1 - shade``; scale mode keeps ``p`` of opaque in-between pixels.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

pytest.importorskip("PIL")

OCC, FREE = 0.65, 0.196


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def grey_alpha_png(grey: np.ndarray, alpha: np.ndarray) -> bytes:
    """A PNG of colour type 4 (grey + alpha), 16 bits a sample, filter 0."""
    rows, cols = grey.shape
    samples = np.stack((grey, alpha), axis=-1).astype(">u2")
    raw = b"".join(b"\x00" + row.tobytes() for row in samples)
    header = struct.pack(">IIBBBBB", cols, rows, 16, 4, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw))
            + _chunk(b"IEND", b""))


def write(folder: Path, grey: np.ndarray, alpha: np.ndarray, mode: str) -> Path:
    (folder / "m.png").write_bytes(grey_alpha_png(grey, alpha))
    yaml_path = folder / "m.yaml"
    yaml_path.write_text(
        "image: m.png\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
        f"occupied_thresh: {OCC}\nfree_thresh: {FREE}\nmode: {mode}\n"
    )
    return yaml_path


def low_byte_levels(threshold: float) -> np.ndarray:
    """16-bit greys of opaque trinary pixels whose class at ``threshold``
    (p = 1 - (3 v + 65535) / (4 * 65535)) flips when the low byte is dropped (v & 0xFF00)."""
    v = np.arange(65536, dtype=np.int64)
    p_full = 1.0 - (3.0 * v + 65535.0) / 4.0 / 65535.0
    p_high = 1.0 - (3.0 * (v & 0xFF00) + 65535.0) / 4.0 / 65535.0
    flips = v[(p_full > threshold) != (p_high > threshold)]
    assert flips.size > 0
    out: np.ndarray = flips
    return out


def test_trinary_grey_uses_its_low_byte_and_alpha_both_bytes(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    grey = np.concatenate((
        rng.choice(low_byte_levels(OCC), 6), rng.choice(low_byte_levels(FREE), 6),
        rng.integers(0, 65536, 12),
    )).astype(np.uint16).reshape(4, 6)
    alpha = rng.integers(0, 65536, grey.shape).astype(np.uint16)
    alpha[:2] = 65535  # the flipping levels (rows 0 and 1) opaque
    alpha[2, :3] = 0x00FF  # byte orders told apart: 0x00FF vs 0xFF00
    alpha[2, 3:] = 0xFF00
    grid = read_map(write(tmp_path, grey, alpha, "trinary"))
    shade = (3.0 * grey + alpha) / 4.0 / 65535.0
    p = 1.0 - shade
    expected = np.where(p > OCC, 1, np.where(p < FREE, 0, -1))
    got = np.where(grid.occupied()[::-1], 1, np.where(grid.free()[::-1], 0, -1))
    np.testing.assert_array_equal(got, expected)


def test_scale_mode_keeps_the_full_depth_grey_of_opaque_pixels(tmp_path: Path) -> None:
    # Mid-band greys differing only in the low byte; the last pixel not opaque.
    grey = np.array([[0x8000, 0x80FF, 0x7F01, 0x8000]], dtype=np.uint16)
    alpha = np.array([[65535, 65535, 65535, 65534]], dtype=np.uint16)
    grid = read_map(write(tmp_path, grey, alpha, "scale"))
    p = 1.0 / (1.0 + np.exp(-grid.logodds[0].astype(np.float64)))
    expected = 1.0 - grey[0] / 65535.0
    expected[3] = 0.5
    np.testing.assert_allclose(p, expected, rtol=0, atol=2e-6)
