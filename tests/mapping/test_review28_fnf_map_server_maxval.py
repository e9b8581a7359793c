"""PGMs of an odd ``maxval`` read as Nav2's map_server reads them (review 28, FNF item 2).

Nav2's map_server (Humble to Iron) reads images with GraphicsMagick's Magick++ at
16 bits a sample. A PGM of at least ``maxval`` pixels becomes a colormap image whose
entry ``i`` is ``i * (65535 // maxval)`` (an integer division), and
``Image::pixelColor`` reads that entry; a smaller PGM keeps its samples rounded to
16 bits. navkit scaled every sample exactly (``v * 255 / maxval``), so in ``raw``
mode 163 of the 1001 levels of a maxval-1000 map read one percent off. The pinned
values below are GraphicsMagick 1.3.40's (Debian 12, ``libgraphicsmagick++-q16-12``):
``pixelColor(x, 0).redQuantum()`` and Nav2's ``std::round(shade * 255)``, printed
by a ten-line Magick++ program for each file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import pixel_occupancy, read_image, read_map_yaml, read_pgm


def _pgm(folder: Path, levels: list[int] | np.ndarray, maxval: int, kind: str) -> Path:
    """A one-row PGM: P5 (1 byte a sample below maxval 256, else 2) or P2."""
    levels = np.asarray(levels)
    head = f"{kind}\n{levels.size} 1\n{maxval}\n".encode()
    if kind == "P5":
        body = levels.astype(np.uint8 if maxval < 256 else ">u2").tobytes()
    else:
        body = (" ".join(str(int(v)) for v in levels) + "\n").encode()
    path = folder / "m.pgm"
    path.write_bytes(head + body)
    return path


def _yaml(folder: Path, mode: str) -> Path:
    path = folder / "m.yaml"
    path.write_text(
        "image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
        f"occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: {mode}\n"
    )
    return path


def _raw_percent(folder: Path) -> np.ndarray:
    """map_server's raw-mode values of the one-row map (-1: unknown), as read_map reads them."""
    meta = read_map_yaml(_yaml(folder, "raw"))
    grey, alpha = read_image(meta.image)
    value, unknown = pixel_occupancy(grey, alpha, meta)
    out: np.ndarray = np.where(unknown, -1.0, np.round(value * 100.0))[0]
    return out


# (maxval, sample, GraphicsMagick's quantum, Nav2's raw percentage, navkit's before)
_COLORMAP_CASES = [
    (1000, 53, 3445, 13, 14),
    (1000, 81, 5265, 20, 21),
    (200, 20, 6540, 25, 26),
    (200, 75, 24525, 95, 96),
    (100, 10, 6550, 25, 26),
]


@pytest.mark.parametrize("kind", ["P5", "P2"])
@pytest.mark.parametrize(("maxval", "sample", "quantum", "nav2", "before"), _COLORMAP_CASES)
def test_a_pgm_of_maxval_pixels_or_more_reads_through_the_colormap(
    tmp_path: Path, kind: str, maxval: int, sample: int, quantum: int, nav2: int, before: int
) -> None:
    levels = np.arange(maxval + 1)  # maxval + 1 pixels: GraphicsMagick's colormap image
    _pgm(tmp_path, levels, maxval, kind)
    grey, alpha = read_image(tmp_path / "m.pgm")
    assert alpha is None
    assert grey[0, sample] * 65535.0 / 255.0 == pytest.approx(quantum, abs=1e-6)
    assert read_pgm(tmp_path / "m.pgm")[0, sample] == sample * 255.0 / maxval  # exact, as before
    assert round(sample * 255 / maxval) == before != nav2
    assert _raw_percent(tmp_path)[sample] == nav2
    # Every level as GraphicsMagick's colormap gives it.
    want = np.round(levels * (65535 // maxval) / 65535.0 * 255.0)
    assert np.array_equal(_raw_percent(tmp_path), np.where(want > 100, -1.0, want))


@pytest.mark.parametrize(
    ("maxval", "kind", "quanta"),
    [
        # 6 pixels, fewer than maxval: the samples rounded to 16 bits. P5's one-byte
        # samples are widened first (257 v), then scaled: 100 of 200 lands on 32767.
        (200, "P5", [0, 328, 12779, 16384, 32767, 33095]),
        (200, "P2", [0, 328, 12779, 16384, 32768, 33095]),
        (1000, "P5", [0, 66, 2556, 3277, 6554, 32833]),
        (1000, "P2", [0, 66, 2556, 3277, 6554, 32833]),
    ],
)
def test_a_smaller_pgm_reads_its_samples_rounded_to_16_bits(
    tmp_path: Path, maxval: int, kind: str, quanta: list[int]
) -> None:
    _pgm(tmp_path, [0, 1, 39, 50, 100, maxval // 2 + 1], maxval, kind)
    grey, _ = read_image(tmp_path / "m.pgm")
    np.testing.assert_allclose(grey[0] * 65535.0 / 255.0, quanta, rtol=0, atol=1e-6)


@pytest.mark.parametrize("maxval", [255, 65535])
def test_maxval_255_and_65535_read_as_before(tmp_path: Path, maxval: int) -> None:
    levels = np.linspace(0, maxval, 300).astype(np.int64)
    _pgm(tmp_path, levels, maxval, "P5")
    grey, _ = read_image(tmp_path / "m.pgm")
    assert grey.tobytes() == read_pgm(tmp_path / "m.pgm").tobytes()


def test_trinary_and_scale_read_the_same_levels(tmp_path: Path) -> None:
    # Sample 1000 of 1000 is white exactly, but 65 * 1000 of 65535 in the colormap:
    # p = 1 - 65000 / 65535 = 0.0082, free either way; sample 500 sits between the
    # thresholds, where scale mode keeps p itself.
    _pgm(tmp_path, np.arange(1001), 1000, "P5")
    grid = read_map(_yaml(tmp_path, "scale"))
    p = 1.0 / (1.0 + np.exp(-np.asarray(grid.logodds, dtype=np.float64)[0]))
    assert p[500] == pytest.approx(1.0 - 500 * 65 / 65535.0, abs=1e-6)
    assert p[500] != pytest.approx(1.0 - 500 / 1000.0, abs=1e-4)
