"""Reading a map whose image goes away while it is being checked.

A save of the map in the other mode (PGM ↔ PNG, another thread or process)
removes the former image. The reader checked "exists", then "is a regular
file": an image removed between the two was reported as ``ValueError`` "is not
a regular file", a misleading message (and the wrong type) for a file that is
simply gone. The checks are now one ``stat``: a missing image is always
``FileNotFoundError``, and a directory or FIFO is still a ``ValueError``.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, read_map, write_map

GRID = OccupancyGrid.from_occupancy(np.eye(4, 6, dtype=bool), resolution=0.5)


def test_an_image_removed_after_the_first_look_reads_as_missing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    yaml_path = tmp_path / "map.yaml"
    write_map(GRID, yaml_path, mode="trinary")
    image = tmp_path / "map.pgm"
    real_stat = Path.stat

    def stat_then_gone(self: Path, *args: object, **kwargs: object) -> os.stat_result:
        # Path.exists and Path.is_file stat too: whatever looks first, the image
        # is there then, and a save in the other mode removes it right after.
        result = real_stat(self, *args, **kwargs)  # type: ignore[arg-type]
        if self == image:
            image.unlink(missing_ok=True)
        return result

    monkeypatch.setattr(Path, "stat", stat_then_gone)
    with pytest.raises(FileNotFoundError):
        read_map(yaml_path)


def test_the_checks_still_tell_what_is_wrong(tmp_path: Path) -> None:
    yaml_path = tmp_path / "map.yaml"
    write_map(GRID, yaml_path, mode="trinary")
    image = tmp_path / "map.pgm"
    assert read_map(yaml_path).shape == GRID.shape
    image.unlink()
    with pytest.raises(FileNotFoundError, match="does not exist"):
        _map_files.read_map_yaml(yaml_path)
    image.mkdir()
    with pytest.raises(ValueError, match="is a directory"):
        _map_files.read_map_yaml(yaml_path)
    image.rmdir()
    if hasattr(os, "mkfifo"):  # not on Windows
        os.mkfifo(image)
        with pytest.raises(ValueError, match="not a regular file"):
            _map_files.read_map_yaml(yaml_path)
        image.unlink()
    image.symlink_to(tmp_path / "nowhere.pgm")  # a dangling link: missing, as before
    with pytest.raises(FileNotFoundError, match="does not exist"):
        _map_files.read_map_yaml(yaml_path)
    image.unlink()
    image.symlink_to(image)  # a loop: missing, as Path.exists said
    with pytest.raises(FileNotFoundError, match="does not exist"):
        _map_files.read_map_yaml(yaml_path)


def test_the_yaml_naming_itself_is_still_refused(tmp_path: Path) -> None:
    yaml_path = tmp_path / "self.yaml"
    yaml_path.write_text(
        "image: self.yaml\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    with pytest.raises(ValueError, match="names the YAML file itself"):
        _map_files.read_map_yaml(yaml_path)
