"""Hostile outputs (session 34): a save into a missing folder names that folder.

``grid.save("maps/new/office.yaml")`` with no ``maps/new`` raised
``FileNotFoundError: [Errno 2] No such file or directory:
'maps/new/.office.16589322.tmp.pgm'``, naming a temporary file the caller never
heard of. It now names the folder (``no such folder: 'maps/new'``), and nothing
is created.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.files import atomic_paths
from navkit.mapping import OccupancyGrid


def test_a_missing_folder_is_named(tmp_path: Path) -> None:
    (tmp_path / "a-file").write_text("not a folder")
    target = tmp_path / "missing" / "m.yaml"
    with pytest.raises(FileNotFoundError) as caught, atomic_paths([target]):
        pytest.fail("the block must not run")  # pragma: no cover
    assert caught.value.errno == errno.ENOENT
    assert caught.value.filename == os.fspath(tmp_path / "missing")
    assert ".tmp" not in str(caught.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file"]


@pytest.mark.parametrize("below", [(), ("sub",), ("sub", "deeper")])
def test_a_file_where_a_folder_should_be_is_named_as_no_folder(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    # Review 31: it was reported as a missing folder (ENOENT) where the system says
    # ENOTDIR, naming the folder below the file rather than the file itself.
    (tmp_path / "a-file").write_text("not a folder")
    target = tmp_path.joinpath("a-file", *below, "m.yaml")
    with pytest.raises(NotADirectoryError, match="not a folder") as caught, atomic_paths([target]):
        pytest.fail("the block must not run")  # pragma: no cover
    assert caught.value.errno == errno.ENOTDIR
    assert caught.value.filename == os.fspath(tmp_path / "a-file")
    assert ".tmp" not in str(caught.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file"]


def test_write_map_into_a_missing_folder_names_it(tmp_path: Path) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(2, dtype=bool), resolution=0.1)
    with pytest.raises(FileNotFoundError, match="no such folder") as caught:
        grid.save(tmp_path / "new" / "office.yaml")
    assert caught.value.filename == os.fspath(tmp_path / "new")
    assert list(tmp_path.iterdir()) == []
