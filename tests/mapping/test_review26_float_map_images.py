"""A map image of 32-bit floats is refused, naming the file (review 26).

Pillow opens a floating-point TIFF in mode "F" and converts it to 8 bits by
clipping: a map of occupancy probabilities in [0, 1] read as black, every cell
occupied, without a word (found by the coverage review). map_server does not
read such images; navkit now refuses them with a ValueError naming the file.
"""

from __future__ import annotations

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


@pytest.mark.parametrize("values", [(0.0, 1.0), (0.0, 255.0)], ids=["unit", "bytes"])
def test_a_floating_point_image_is_refused_naming_the_file(
    tmp_path: Path, values: tuple[float, float]
) -> None:
    low, high = values
    picture = np.full((4, 6), high, dtype=np.float32)
    picture[1:3, 2:4] = low
    Image.fromarray(picture, mode="F").save(tmp_path / "float.tif")
    with Image.open(tmp_path / "float.tif") as check:
        assert check.mode == "F"  # the case under test, as Pillow opens it
    yaml = tmp_path / "float.yaml"
    yaml.write_text(_YAML.format(image="float.tif"), encoding="utf-8")
    with pytest.raises(ValueError, match=r"float\.tif: a 32-bit floating-point image"):
        read_map(yaml)


def test_an_8_bit_twin_of_the_same_map_reads(tmp_path: Path) -> None:
    # The message's advice works: the same picture as 8-bit grey is the map drawn.
    picture = np.full((4, 6), 255, dtype=np.uint8)
    picture[1:3, 2:4] = 0
    Image.fromarray(picture).save(tmp_path / "grey.png")
    yaml = tmp_path / "grey.yaml"
    yaml.write_text(_YAML.format(image="grey.png"), encoding="utf-8")
    occupied = read_map(yaml).occupied()
    # Row 0 of the grid is the image's bottom row (map_server's convention).
    np.testing.assert_array_equal(occupied, (picture == 0)[::-1])
