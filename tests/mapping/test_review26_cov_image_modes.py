"""Map images in modes the default suite never read (coverage review, session 30).

A bilevel image (Pillow mode "1": 1-bit PNG, PBM, BMP) and colour spaces other
than RGB (CMYK and CIELAB TIFF) are converted before their channels are
averaged; the map they give is the map of the same picture saved as 8-bit grey.
A PGM of another kind (P6, colour) is refused, naming the file and its magic.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

pytest.importorskip("PIL")
from PIL import Image

_YAML = (
    "image: {image}\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)
# Black (occupied) and white (free) only: exact in every mode.
_PICTURE = np.kron(
    np.array([[0, 255, 255], [255, 0, 255]], dtype=np.uint8), np.ones((8, 8), np.uint8)
)


def _map(folder: Path, name: str, image: Image.Image) -> Path:
    image.save(folder / name)
    yaml = folder / f"{name}.yaml"
    yaml.write_text(_YAML.format(image=name), encoding="utf-8")
    return yaml


@pytest.mark.parametrize(
    ("name", "mode"),
    [
        ("bits.png", "1"),
        ("bits.pbm", "1"),
        ("bits.bmp", "1"),
        ("colour.tif", "CMYK"),
        ("lab.tif", "LAB"),
    ],
)
def test_a_bilevel_or_other_colour_space_image_reads_as_its_grey_twin(
    tmp_path: Path, name: str, mode: str
) -> None:
    grey = read_map(_map(tmp_path, "grey.png", Image.fromarray(_PICTURE)))
    source = Image.fromarray(_PICTURE)
    converted = source.convert(mode if mode == "1" else "RGB").convert(mode)
    with Image.open(tmp_path / "grey.png") as check:
        assert check.mode == "L"
    yaml = _map(tmp_path, name, converted)
    with Image.open(tmp_path / name) as check:
        assert check.mode == mode  # the mode under test, as Pillow opens it
    grid = read_map(yaml)
    np.testing.assert_array_equal(grid.occupied(), grey.occupied())
    np.testing.assert_array_equal(grid.free(), grey.free())
    assert grid.occupied().sum() == 2 * 64 and not grid.unknown().any()


def test_a_colour_pgm_is_refused_naming_its_magic(tmp_path: Path) -> None:
    image = tmp_path / "map.pgm"
    image.write_bytes(b"P6\n2 2\n255\n" + bytes(12))
    yaml = tmp_path / "map.yaml"
    yaml.write_text(_YAML.format(image="map.pgm"), encoding="utf-8")
    message = f"map image {image}: not a PGM image (magic b'P6', expected P5 or P2)"
    with pytest.raises(ValueError, match=re.escape(message) + "$"):
        read_map(yaml)
