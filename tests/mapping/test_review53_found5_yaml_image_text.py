"""Review 53 (FOUND5): read_map reads an image name as its text, as map_server's yaml-cpp does.

map_server (ROS 1 and nav2_map_server) reads ``image`` with yaml-cpp's
``as<std::string>()``, a scalar's text whatever it looks like. PyYAML resolves
plain scalars by YAML 1.1, so ``image: yes`` (``on``, ``No``), ``1.50``,
``2001-12-14`` or ``15`` became True, 1.5, a date or 15, and ``read_map``
refused them: "image must be a file name, got True". They name those files now
(649d386 kept ``017``-like YAML 1.1 numbers as text already). A null
(``image:``, ``~``, ``null``) stays refused: yaml-cpp up to 0.6 refuses it too.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_WALL = np.zeros((6, 9), dtype=bool)
_WALL[1:5, 4] = True
GRID = OccupancyGrid.from_occupancy(_WALL, resolution=0.1, origin=(0.5, -1.0, 0.0))


def _map_naming(folder: Path, written: str, file_name: str) -> Path:
    """A map YAML whose ``image:`` line is ``written``, its image saved as ``file_name``."""
    yaml_path = folder / "map.yaml"
    pgm = GRID.save(yaml_path)
    pgm.rename(folder / file_name)
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(text.replace(f"image: {pgm.name}", f"image: {written}"), "utf-8")
    return yaml_path


@pytest.mark.parametrize(
    "name",
    [
        "yes", "No", "on", "OFF", "true", "y",  # YAML 1.1 booleans (y: PyYAML keeps it)
        "1.50", "15", "-3", "1e3", "0.5e1", ".inf", ".NaN",  # numbers
        "2001-12-14", "2001-12-14 21:59:43.10 -5",  # timestamps
        "017", "0x1F", "1_000", "1:20",  # YAML 1.1-only numbers (649d386)
    ],
)  # fmt: skip
def test_an_image_named_like_a_value_is_that_file(tmp_path: Path, name: str) -> None:
    yaml_path = _map_naming(tmp_path, name, name)
    grid = read_map(yaml_path)  # the only image beside the YAML is the file `name`
    assert np.array_equal(grid.occupied(), GRID.occupied())
    assert grid.origin == GRID.origin


@pytest.mark.parametrize(
    ("written", "file_name"),
    [("'yes'", "yes"), ('"1.50"', "1.50"), ("!!str on", "on"), ("!!int 15", "15")],
)
def test_quoted_and_tagged_names_are_their_text(
    tmp_path: Path, written: str, file_name: str
) -> None:
    yaml_path = _map_naming(tmp_path, written, file_name)
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())


def test_a_merged_image_is_read_as_text(tmp_path: Path) -> None:
    yaml_path = _map_naming(tmp_path, "on", "on")
    text = yaml_path.read_text(encoding="utf-8").replace("image: on\n", "")
    yaml_path.write_text("base: &b {image: 2001-12-14}\n<<: *b\nimage: on\n" + text, "utf-8")
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    yaml_path.write_text("base: &b {image: 1.50}\n<<: *b\n" + text, "utf-8")
    (tmp_path / "on").rename(tmp_path / "1.50")
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())


def test_the_missing_file_is_named_by_its_text(tmp_path: Path) -> None:
    yaml_path = _map_naming(tmp_path, "yes", "other.pgm")
    with pytest.raises(FileNotFoundError, match=r"map image .*yes does not exist"):
        read_map(yaml_path)


@pytest.mark.parametrize("written", ["", "~", "null", "[a.pgm]", "{a: b}"])
def test_no_name_stays_refused(tmp_path: Path, written: str) -> None:
    yaml_path = _map_naming(tmp_path, written, "map.pgm")
    with pytest.raises(ValueError, match=r"map\.yaml: image must be a file name, got "):
        read_map(yaml_path)
