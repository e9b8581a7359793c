"""Re-saving a map in the other mode (navkit.mapping.io.write_map): the previous
mode's image is removed only when it provably belongs to the replaced map."""

from __future__ import annotations

import errno
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

pytest.importorskip("PIL")  # scale mode writes PNG with Pillow

IMAGE = {"trinary": "map.pgm", "scale": "map.png"}
OTHER = {"trinary": "scale", "scale": "trinary"}


def grid(value: bool) -> OccupancyGrid:
    occupied = np.array([[value, False, False], [False, False, not value]])
    unknown = np.array([[False, True, False], [False, False, False]])
    return OccupancyGrid.from_occupancy(occupied, resolution=0.25, unknown=unknown)


def names(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.parametrize("first", ["trinary", "scale"])
def test_mode_change_replaces_the_maps_own_image(tmp_path: Path, first: str) -> None:
    # The issue: trinary, then scale to the same YAML left map.pgm behind, and a
    # later trinary save refused to overwrite that orphan.
    second = OTHER[first]
    yaml_path = tmp_path / "map.yaml"
    write_map(grid(True), yaml_path, mode=first)
    write_map(grid(False), yaml_path, mode=second)
    assert names(tmp_path) == sorted(["map.yaml", IMAGE[second]])
    again = read_map(yaml_path)
    assert np.array_equal(again.occupied(), grid(False).occupied())
    assert np.array_equal(again.unknown(), grid(False).unknown())
    # ... and back: no refusal, the other image removed again.
    write_map(grid(True), yaml_path, mode=first)
    assert names(tmp_path) == sorted(["map.yaml", IMAGE[first]])
    assert np.array_equal(read_map(yaml_path).occupied(), grid(True).occupied())


def test_an_image_another_yaml_names_is_kept(tmp_path: Path) -> None:
    write_map(grid(True), tmp_path / "map.yaml")
    copy = (tmp_path / "map.yaml").read_text()
    (tmp_path / "copy.yaml").write_text(copy)  # a second map sharing map.pgm
    pgm = (tmp_path / "map.pgm").read_bytes()
    write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    assert (tmp_path / "map.pgm").read_bytes() == pgm
    assert np.array_equal(read_map(tmp_path / "copy.yaml").occupied(), grid(True).occupied())


def test_an_image_the_yaml_does_not_name_is_kept(tmp_path: Path) -> None:
    # map.yaml names floor.pgm: map.pgm is someone else's file, never removed,
    # and floor.pgm (not the name a save gives) is left alone too.
    write_map(grid(True), tmp_path / "floor.yaml")
    (tmp_path / "floor.yaml").rename(tmp_path / "map.yaml")
    (tmp_path / "map.pgm").write_bytes(b"unrelated")
    write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    assert (tmp_path / "map.pgm").read_bytes() == b"unrelated"
    assert (tmp_path / "floor.pgm").exists()


def test_an_image_with_a_mismatched_mode_is_kept(tmp_path: Path) -> None:
    # A hand-edited YAML: mode raw with map.pgm is not what a save writes.
    write_map(grid(True), tmp_path / "map.yaml")
    text = (tmp_path / "map.yaml").read_text().replace("mode: trinary", "mode: raw")
    (tmp_path / "map.yaml").write_text(text)
    write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    assert (tmp_path / "map.pgm").exists()


@pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need privileges")
def test_a_symlinked_image_is_kept(tmp_path: Path) -> None:
    write_map(grid(True), tmp_path / "map.yaml")
    (tmp_path / "map.pgm").rename(tmp_path / "real.pgm")
    (tmp_path / "map.pgm").symlink_to(tmp_path / "real.pgm")
    write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    assert (tmp_path / "map.pgm").is_symlink()
    assert (tmp_path / "real.pgm").exists()


def test_failed_mode_change_keeps_the_old_image(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write_map(grid(True), tmp_path / "map.yaml")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def full(*args: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "replace", full)
    with pytest.raises(OSError, match="No space left"):
        write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    monkeypatch.undo()
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_failed_removal_warns_and_keeps_the_new_map(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write_map(grid(True), tmp_path / "map.yaml")
    real_unlink = Path.unlink

    def refuse(self: Path, missing_ok: bool = False) -> None:
        if self.name == "map.pgm":
            raise PermissionError(errno.EACCES, "Permission denied")
        real_unlink(self, missing_ok=missing_ok)

    monkeypatch.setattr(Path, "unlink", refuse)
    with pytest.warns(RuntimeWarning, match="could not be removed"):
        write_map(grid(False), tmp_path / "map.yaml", mode="scale")
    monkeypatch.undo()
    assert np.array_equal(read_map(tmp_path / "map.yaml").occupied(), grid(False).occupied())
