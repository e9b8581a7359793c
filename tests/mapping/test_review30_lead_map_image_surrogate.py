"""A map YAML naming its image with a lone surrogate is a ValueError naming the YAML (review 30).

A YAML escape (``image: "\\ud800.pgm"``) makes a name no file system encoding
takes: ``stat`` raised a bare ``UnicodeEncodeError``, and ``navkit plan`` printed
"'utf-8' codec can't encode ..." without the file.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_YAML = (
    "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


@pytest.mark.parametrize("read", [read_map, OccupancyGrid.load])
def test_a_lone_surrogate_image_name_is_refused_naming_the_yaml(
    read: object, tmp_path: Path
) -> None:
    path = tmp_path / "m.yaml"
    path.write_text('image: "\\ud800.pgm"\n' + _YAML, encoding="utf-8")
    with pytest.raises(ValueError, match=re.escape(f"{path}: image must be a file name")):
        read(path)  # type: ignore[operator]


def test_an_undecodable_byte_name_still_reaches_the_file_system(tmp_path: Path) -> None:
    # "\udc80" is how Python spells the byte 0x80 of a file name (surrogateescape): a
    # name the file system can hold, so its absence is the usual "does not exist".
    path = tmp_path / "m.yaml"
    path.write_text('image: "\\udc80.pgm"\n' + _YAML, encoding="utf-8")
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read_map(path)
