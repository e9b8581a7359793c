"""Map-file reading rules that no test pinned down (mutation testing, review 10).

* ``pixel_occupancy`` in ``scale`` mode: like ``trinary``, a pixel below
  ``free_thresh`` is free (p = 0) and one above ``occupied_thresh`` occupied
  (p = 1); only the in-between ones keep ``p`` (map_server's scale mode).
* ``read_image`` returns grey levels 0..255 also for 32-bit integer images, whose
  values can lie outside the 16-bit range they are scaled from.
* A 16-bit colour PNG is decoded twice; a file that is another image the second
  time is refused ("the file changed while it was read"), never mixed.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping.io._map_files import MapMetadata, pixel_occupancy, read_image


def test_scale_mode_reads_free_pixels_as_zero_and_occupied_as_one() -> None:
    meta = MapMetadata(Path("m.png"), 0.05, (0.0, 0.0, 0.0), False, 0.65, 0.196, "scale")
    grey = np.array([[0.0, 60.0, 128.0, 180.0, 230.0, 254.0, 255.0]])
    prob, unknown = pixel_occupancy(grey.copy(), None, meta)
    want = []
    for v in grey[0]:
        p = 1.0 - v / 255.0
        want.append(1.0 if p > 0.65 else 0.0 if p < 0.196 else p)
    np.testing.assert_allclose(prob[0], want, rtol=0, atol=1e-15)
    assert prob[0, 4] == 0.0 and prob[0, 5] == 0.0  # p = 0.098 and 0.004: free
    assert not unknown.any()


def test_a_32_bit_image_is_clipped_to_grey_levels_0_to_255(tmp_path: Path) -> None:
    image_module = pytest.importorskip("PIL.Image")
    values = np.array([[-1000, 0, 32768, 65535, 100000]], dtype=np.int32)
    path = tmp_path / "deep.tif"
    image_module.fromarray(values).save(path)
    grey, alpha = read_image(path)
    # Scaled from 0..65535 (the values exceed 255), then clipped to 0..255.
    want = np.clip(values * (255.0 / 65535.0), 0.0, 255.0)
    np.testing.assert_allclose(grey, want, rtol=1e-12)
    assert grey.min() >= 0.0 and grey.max() <= 255.0
    assert alpha is None


def _png16_rgb(samples: np.ndarray) -> bytes:
    """A PNG with 16-bit RGB samples (rows, cols, 3), written without Pillow."""
    rows, cols, _ = samples.shape

    def chunk(kind: bytes, data: bytes) -> bytes:
        crc = struct.pack(">I", zlib.crc32(kind + data))
        return struct.pack(">I", len(data)) + kind + data + crc

    raw = b"".join(b"\x00" + row.astype(">u2").tobytes() for row in samples)
    header = struct.pack(">IIBBBBB", cols, rows, 16, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw))
            + chunk(b"IEND", b""))  # fmt: skip


def test_a_16_bit_png_that_is_another_image_when_read_again_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    image_module = pytest.importorskip("PIL.Image")
    path = tmp_path / "map.png"
    other = tmp_path / "other.png"
    path.write_bytes(_png16_rgb(np.full((2, 3, 3), 40000, dtype=np.uint16)))
    other.write_bytes(_png16_rgb(np.full((3, 2, 3), 1000, dtype=np.uint16)))
    grey, _ = read_image(path)  # read whole, as written
    np.testing.assert_allclose(grey, np.full((2, 3), 40000 / 257.0))
    real_open = image_module.open
    calls = []

    def swapping_open(fp: Any, *args: Any, **kwargs: Any) -> Any:
        # The second decode of the same file finds the other image (a swap mid-read).
        calls.append(fp)
        return real_open(other if len(calls) == 2 else fp, *args, **kwargs)

    monkeypatch.setattr(image_module, "open", swapping_open)
    with pytest.raises(ValueError, match="changed while it was read"):
        read_image(path)
    assert len(calls) == 2
