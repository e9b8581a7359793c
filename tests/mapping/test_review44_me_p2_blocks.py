"""An ASCII (P2) PGM raster is read a block of text at a time (review 44).

MEMCAP measured 62 bytes a pixel reading a P2 map (a list of every token and one
of every int: 15.6 GiB at the 2**28-pixel limit) where ``read_map`` documents
about 16.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.mapping.io._map_files as map_files
from memory_peak import peak_bytes

_SPACES = [b" ", b"\t", b"\n", b"\r", b"\x0b", b"\x0c", b"  \n", b"\r\n"]


def _raster(values: list[int], gaps: list[bytes]) -> bytes:
    return b"".join(str(v).encode() + gaps[i % len(gaps)] for i, v in enumerate(values))


def test_a_p2_map_peaks_at_its_text_and_a_few_bytes_a_pixel(tmp_path: Path) -> None:
    rng = np.random.default_rng(44)
    values = rng.integers(0, 256, size=600 * 500).tolist()
    path = tmp_path / "big.pgm"
    path.write_bytes(b"P2\n600 500\n255\n" + _raster(values, [b" ", b"\n"]))
    peak, grey = peak_bytes(lambda: map_files.read_pgm(path))
    assert grey.shape == (500, 600)
    assert np.array_equal(grey, np.array(values, dtype=np.float64).reshape(500, 600))
    # The text (about 3.6 bytes a pixel), the int32 values, the float64 levels and
    # a block's tokens: 62 bytes a pixel before.
    per_pixel = peak / grey.size
    assert per_pixel < 20, f"{per_pixel:.1f} bytes a pixel"


@settings(max_examples=150, deadline=None)
@given(
    values=st.lists(st.integers(0, 65535), min_size=1, max_size=60),
    gaps=st.lists(st.sampled_from(_SPACES), min_size=1, max_size=4),
    block=st.integers(1, 16),
    trailing=st.sampled_from([b"", b"\n", b" 7 8 junk", b"\n\n"]),
)
def test_values_across_block_boundaries_are_read_whole(
    values: list[int], gaps: list[bytes], block: int, trailing: bytes
) -> None:
    # Tiny blocks put a boundary inside values, inside runs of whitespace and at
    # their ends; the values read are the file's, whatever follows them.
    raster = _raster(values, gaps) + trailing
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(map_files, "_P2_BLOCK_BYTES", block)
        pixels = map_files._p2_pixels(raster, len(values), Path("x.pgm"), 65535)
    assert pixels.tolist() == values


@pytest.mark.parametrize("block", [1, 3, 1 << 20])
def test_a_short_raster_is_truncated_whatever_the_blocks(block: int) -> None:
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(map_files, "_P2_BLOCK_BYTES", block)
        with pytest.raises(ValueError, match="PGM raster truncated: 3 of 4 values"):
            map_files._p2_pixels(b"1 22 333 ", 4, Path("x.pgm"), 65535)
        with pytest.raises(ValueError, match=r"holds b'2x', not a non-negative"):
            map_files._p2_pixels(b"1 2x 3 4", 4, Path("x.pgm"), 65535)
