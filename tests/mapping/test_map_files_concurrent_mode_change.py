"""write_map's removal of the previous mode's image when another save of the
same map finishes between this save's decision and its removal."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, read_map, write_map

pytest.importorskip("PIL")  # scale mode writes PNG with Pillow


def grid(value: bool) -> OccupancyGrid:
    occupied = np.array([[value, False], [False, not value]])
    return OccupancyGrid.from_occupancy(occupied, resolution=0.5)


@pytest.mark.parametrize("first", ["trinary", "scale"])
def test_a_save_that_finished_meanwhile_keeps_its_image(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, first: str
) -> None:
    # Process A saves in the other mode while process B saves the map in the first
    # mode again: B renames its new image and YAML (naming that image) after A's
    # renames, before A removes "its" superseded image. Removing it then deleted
    # B's new image and left the map's YAML naming a missing file.
    other = {"trinary": "scale", "scale": "trinary"}[first]
    folder, elsewhere = tmp_path / "maps", tmp_path / "b"
    folder.mkdir()
    elsewhere.mkdir()
    yaml_path = folder / "map.yaml"
    write_map(grid(True), yaml_path, mode=first)
    b_image = write_map(grid(False), elsewhere / "map.yaml", mode=first)  # B's files
    replace_all = _map_files._replace_all
    interleaved: list[Path] = []

    def replace_then_b_renames(files: list[tuple[Path, bytes]]) -> None:
        replace_all(files)
        if not interleaved:  # B's renames, as its own _replace_all does them
            interleaved.append(b_image)
            os.replace(b_image, folder / b_image.name)
            os.replace(elsewhere / "map.yaml", yaml_path)

    monkeypatch.setattr(_map_files, "_replace_all", replace_then_b_renames)
    write_map(grid(True), yaml_path, mode=other)
    assert interleaved
    # The YAML is B's (renamed last); its image must still be there.
    again = read_map(yaml_path)
    assert np.array_equal(again.occupied(), grid(False).occupied())


def test_an_image_rewritten_in_place_meanwhile_is_kept(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Another tool rewrites map.pgm in place (same inode) and points the YAML back
    # at it after this save's renames: the YAML no longer names this save's image.
    yaml_path = tmp_path / "map.yaml"
    write_map(grid(True), yaml_path, mode="trinary")
    trinary_yaml = yaml_path.read_text()
    pgm = tmp_path / "map.pgm"
    replace_all = _map_files._replace_all

    def replace_then_rewrite(files: list[tuple[Path, bytes]]) -> None:
        replace_all(files)
        with pgm.open("r+b") as fh:  # in place: the inode stays
            fh.write(pgm.read_bytes())
        yaml_path.write_text(trinary_yaml)

    monkeypatch.setattr(_map_files, "_replace_all", replace_then_rewrite)
    write_map(grid(False), yaml_path, mode="scale")
    assert np.array_equal(read_map(yaml_path).occupied(), grid(True).occupied())
