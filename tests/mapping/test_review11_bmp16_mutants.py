"""A BMP with 16 bits per pixel (5-6-5 colour) is an 8-bit-per-channel-or-less image.

``read_image`` refuses only images with 16 bits per colour *channel*, which
Pillow would truncate; BMP's 16-bit pixels (raw mode ``BGR;16``, 5 bits of red,
6 of green, 5 of blue) hold less than 8 bits a channel and must be read
(mutation testing: a refusal pattern matching any ``;16`` raw mode refused them).
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import read_image

BLACK, WHITE, RED = 0x0000, 0xFFFF, 0xF800


def bmp565(pixels: np.ndarray) -> bytes:
    """A BITMAPINFOHEADER BMP, BI_BITFIELDS with the 5-6-5 masks, rows stored bottom-up."""
    height, width = pixels.shape
    stride = (2 * width + 3) // 4 * 4
    rows = b"".join(
        pixels[r].astype("<u2").tobytes().ljust(stride, b"\0") for r in range(height - 1, -1, -1)
    )
    masks = struct.pack("<III", 0xF800, 0x07E0, 0x001F)
    offset = 14 + 40 + len(masks)
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 16, 3, len(rows), 2835, 2835, 0, 0)
    return b"BM" + struct.pack("<IHHI", offset + len(rows), 0, 0, offset) + info + masks + rows


def test_a_565_bmp_is_read_with_its_channels_averaged(tmp_path: Path) -> None:
    path = tmp_path / "m.bmp"
    path.write_bytes(bmp565(np.array([[BLACK, WHITE, RED], [WHITE, WHITE, BLACK]])))
    grey, alpha = read_image(path)
    assert alpha is None
    # Full-scale channels are 255 at any bit depth; pure red averages to 255 / 3.
    np.testing.assert_array_equal(grey, [[0.0, 255.0, 85.0], [255.0, 255.0, 0.0]])


def test_a_565_bmp_map_loads_in_trinary_mode(tmp_path: Path) -> None:
    (tmp_path / "m.bmp").write_bytes(bmp565(np.array([[BLACK, WHITE], [WHITE, BLACK]])))
    yaml_path = tmp_path / "map.yaml"
    yaml_path.write_text(
        "image: m.bmp\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    grid = read_map(yaml_path)
    # The image's top row is the grid's last row; black is occupied, white free.
    assert grid.occupied()[::-1].tolist() == [[True, False], [False, True]]
    assert grid.free()[::-1].tolist() == [[False, True], [True, False]]
