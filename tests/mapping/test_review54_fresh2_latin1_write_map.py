"""write_map's messages naming a map in a folder whose name is not UTF-8 (review 54, FRESH2).

ffd685d made read_map's messages show a Latin-1 folder's bytes escaped
(``str(exc).encode("utf-8")`` raised UnicodeEncodeError in a strict UTF-8 log
handler). write_map (``OccupancyGrid.save``) names the same folder in its own
ValueErrors and still keeps the surrogates: a YAML path that is a directory,
and an image beside the map that another file already holds. Fixed by the
lead: write_map's body runs inside ffd685d's ``_printable_errors()``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

pytestmark = pytest.mark.skipif(
    sys.platform == "win32" or sys.getfilesystemencoding().lower() != "utf-8",
    reason="a folder name of Latin-1 bytes as a POSIX file system with UTF-8 names holds it",
)


def _folder(tmp_path: Path) -> bytes:
    folder = os.fsencode(tmp_path) + b"/Karte B\xfcro"  # Latin-1 ü: not UTF-8
    try:
        os.mkdir(folder)
    except OSError as error:  # a file system that refuses such names
        pytest.skip(f"cannot make a folder of Latin-1 bytes: {error}")
    return folder


def _grid() -> OccupancyGrid:
    return OccupancyGrid.from_occupancy(np.eye(2, dtype=bool), resolution=0.1)


def _message(path: bytes) -> str:
    with pytest.raises(ValueError) as info:
        write_map(_grid(), os.fsdecode(path))
    return str(info.value)


def test_a_good_save_in_such_a_folder_works(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    write_map(_grid(), os.fsdecode(folder + b"/map.yaml"))
    assert sorted(os.listdir(folder)) == [b"map.pgm", b"map.yaml"]


@pytest.mark.parametrize("case", ["yaml_is_a_directory", "image_held_by_another_file"])
def test_refusals_name_the_folder_escaped(tmp_path: Path, case: str) -> None:
    folder = _folder(tmp_path)
    if case == "yaml_is_a_directory":
        os.mkdir(folder + b"/d.yaml")
        path = folder + b"/d.yaml"
    else:
        with open(folder + b"/x.pgm", "wb") as file:
            file.write(b"not this map's image")
        path = folder + b"/x.yaml"
    message = _message(path)
    assert "Karte B\\udcfcro" in message
    message.encode("utf-8")  # what a strict UTF-8 log handler does
