"""``map_image_path``: the image a map's YAML names, as read_map finds it (review 54, FOUND8).

``navkit plan`` refused a ``--plot`` or ``--json`` naming the map's image by
reading the YAML with a PyYAML loader of its own, apart from read_map's: it
could not read UTF-32, Latin-1 bytes or tabs (read_map can) and refused any
existing output for them. ``navkit.mapping.io`` had no public way to ask for
the image; ``map_image_path`` is read_map's own reading.
"""

from __future__ import annotations

import codecs
import os
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import map_image_path, read_map

GRID = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)


def _saved(folder: Path) -> tuple[Path, Path]:
    yaml_path = folder / "map.yaml"
    return yaml_path, GRID.save(yaml_path)


def _same(a: Path, b: Path) -> bool:
    return os.path.samefile(a, b)


def test_the_image_of_a_saved_map(tmp_path: Path) -> None:
    yaml_path, image = _saved(tmp_path)
    assert map_image_path(yaml_path) == image
    assert map_image_path(str(yaml_path)) == image


@pytest.mark.parametrize(
    "edit",
    [
        lambda t: codecs.BOM_UTF32_LE + t.decode().encode("utf-32-le"),
        lambda t: b"# Karte B\xfcro\n" + t,
        lambda t: t.replace(b"negate", b"\t\nnegate").replace(b"resolution: ", b"resolution:\t"),
    ],
    ids=["utf-32", "latin-1-comment", "tabs"],
)
def test_yamls_pyyaml_refuses(tmp_path: Path, edit: object) -> None:
    yaml_path, image = _saved(tmp_path)
    assert callable(edit)
    yaml_path.write_bytes(edit(yaml_path.read_bytes()))
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    assert _same(map_image_path(yaml_path), image)


def test_a_number_like_name_and_a_windows_name(tmp_path: Path) -> None:
    yaml_path, image = _saved(tmp_path)
    text = yaml_path.read_text(encoding="utf-8")
    (tmp_path / "017").write_bytes(image.read_bytes())  # image: 017 is the file 017
    yaml_path.write_text(text.replace(f"image: {image.name}", "image: 017"), encoding="utf-8")
    assert _same(map_image_path(yaml_path), tmp_path / "017")
    (tmp_path / "maps").mkdir()
    image.rename(tmp_path / "maps" / image.name)
    yaml_path.write_text(
        text.replace(f"image: {image.name}", f"image: maps\\{image.name}"), encoding="utf-8"
    )
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    assert _same(map_image_path(yaml_path), tmp_path / "maps" / image.name)


def test_refusals_are_read_maps(tmp_path: Path) -> None:
    yaml_path, image = _saved(tmp_path)
    image.unlink()
    with pytest.raises(FileNotFoundError, match="does not exist"):
        map_image_path(yaml_path)
    yaml_path.write_text("resolution: 0.1\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"map\.yaml: missing required key\(s\) image"):
        map_image_path(yaml_path)
    with pytest.raises(TypeError, match="path"):
        map_image_path(3.0)  # type: ignore[arg-type]
