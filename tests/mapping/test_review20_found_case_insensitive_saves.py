"""Saving ``MAP.yaml`` then ``map.yaml`` in the other mode leaves no orphan image.

Review 20, FOUND item 5. On a case-insensitive file system (macOS, Windows)
``map.yaml`` is the file ``MAP.yaml``, whose YAML names ``MAP.pgm``. A save of
``map.yaml`` in scale mode writes ``map.png`` and must remove the previous
image, ``MAP.pgm``; it left it, because (a) the YAML's ``image`` was compared
with ``map.pgm`` as text and (b) the folder's listing shows the YAML as
``MAP.yaml``, taken for another YAML naming that image. The orphan then made a
later trinary save of ``MAP.yaml`` fail ("already exists and is not the
image of the map").

Linux has no case-insensitive folder here (no casefold mount), so a hard link
stands in for the second spelling of one directory entry: ``map.yaml`` and
``map.pgm`` are links to ``MAP.yaml`` and ``MAP.pgm`` (``os.path.samefile`` says
they are the same file, as it does for two spellings on macOS or Windows).
The choice of the image to remove (``_superseded_image``) is checked on that;
the removal itself (an ``unlink`` of one spelling removes the one entry there)
cannot be shown with links.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, read_map, write_map

GRID = OccupancyGrid.from_occupancy(np.array([[True, False], [False, False]]), resolution=0.5)


def _saved_upper_case(folder: Path, mode: str = "trinary") -> tuple[Path, Path]:
    """``MAP.yaml`` saved in ``mode``, and its image."""
    upper = folder / "MAP.yaml"
    image = write_map(GRID, upper, mode=mode)
    return upper, image


def _second_spelling(folder: Path, upper: Path, image: Path) -> Path:
    """``map.yaml`` and the lower-case image: the same files under another spelling."""
    lower = folder / "map.yaml"
    os.link(upper, lower)
    os.link(image, folder / image.name.lower())
    return lower


@pytest.mark.parametrize(("first", "then"), [("trinary", "scale"), ("scale", "trinary")])
def test_the_other_spelling_s_image_is_the_one_to_remove(
    tmp_path: Path, first: str, then: str
) -> None:
    pytest.importorskip("PIL")
    upper, image = _saved_upper_case(tmp_path, first)
    lower = _second_spelling(tmp_path, upper, image)
    new_image = lower.with_suffix(".png" if then == "scale" else ".pgm")
    chosen = _map_files._superseded_image(lower, new_image)
    assert chosen is not None
    assert os.path.samefile(chosen.path, image)
    assert chosen.path.name == image.name.lower()  # the spelling of the save, map.<fmt>


def test_no_removal_when_the_names_differ_beyond_case(tmp_path: Path) -> None:
    upper, image = _saved_upper_case(tmp_path)
    lower = tmp_path / "map.yaml"
    os.link(upper, lower)
    os.link(image, tmp_path / "other.pgm")  # the same file, but not a spelling of map.pgm
    text = upper.read_text().replace("image: MAP.pgm", "image: other.pgm")
    upper.write_text(text)  # both spellings of the YAML now name other.pgm
    (tmp_path / "map.pgm").hardlink_to(image)
    assert _map_files._superseded_image(lower, tmp_path / "map.png") is None


def test_another_yaml_naming_the_image_still_keeps_it(tmp_path: Path) -> None:
    upper, image = _saved_upper_case(tmp_path)
    lower = _second_spelling(tmp_path, upper, image)
    (tmp_path / "copy.yaml").write_text(upper.read_text())  # another map, the same image
    assert _map_files._superseded_image(lower, tmp_path / "map.png") is None


def test_same_spelling_saves_are_unchanged(tmp_path: Path) -> None:
    pytest.importorskip("PIL")
    path = tmp_path / "map.yaml"
    write_map(GRID, path, mode="trinary")
    write_map(GRID, path, mode="scale")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.png", "map.yaml"]
    write_map(GRID, path, mode="trinary")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]
    np.testing.assert_array_equal(read_map(path).occupied(), GRID.occupied())


def test_the_spelling_check() -> None:
    same = _map_files._same_spelling
    assert same("MAP.pgm", "map.pgm") and same("map.pgm", "map.pgm")
    assert same("Cafe\u0301.PGM", "caf\u00e9.pgm")  # macOS: composed and decomposed
    assert not same("other.pgm", "map.pgm")
    assert not same("sub/map.pgm", "map.pgm")
    assert not same("map.pgm.bak", "map.pgm")


def test_a_hard_linked_spelling_keeps_the_image_it_still_names(tmp_path: Path) -> None:
    # A case-sensitive folder where Map.yaml is a hard link to map.yaml: after the
    # save, Map.yaml is still the old YAML naming map.pgm, which must stay.
    pytest.importorskip("PIL")
    path = tmp_path / "map.yaml"
    write_map(GRID, path, mode="trinary")
    os.link(path, tmp_path / "Map.yaml")
    write_map(GRID, path, mode="scale")
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "Map.yaml", "map.pgm", "map.png", "map.yaml"
    ]  # fmt: skip
    np.testing.assert_array_equal(read_map(tmp_path / "Map.yaml").occupied(), GRID.occupied())
    np.testing.assert_array_equal(read_map(path).occupied(), GRID.occupied())
