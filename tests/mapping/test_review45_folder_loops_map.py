"""``write_map`` into a folder that is a loop of symbolic links: a missing folder (review 45).

Before, ``write_map(grid, "a/m.yaml")`` with ``a -> b``, ``b -> a`` raised
``OSError`` (``ELOOP``) where a missing folder gives ``FileNotFoundError`` ("no
such folder") and the other writers gave "does not exist": it is now the
missing folder's error, naming the folder and the loop, with nothing written.
See ``tests/shared/test_review45_folder_loops.py``.
"""

from __future__ import annotations

import errno
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")

_GRID = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)


@pytest.mark.parametrize("mode", ["trinary", "scale"])
@pytest.mark.parametrize("below", [(), ("b",)])
def test_a_looped_folder_is_a_missing_folder_and_nothing_is_written(
    tmp_path: Path, mode: str, below: tuple[str, ...]
) -> None:
    (tmp_path / "a").symlink_to("b")
    (tmp_path / "b").symlink_to("a")
    folder = tmp_path.joinpath("a", *below)
    before = _tree(tmp_path)
    for save in (lambda p: write_map(_GRID, p, mode=mode), lambda p: _GRID.save(p, mode=mode)):
        with pytest.raises(FileNotFoundError) as caught:
            save(folder / "m.yaml")
        assert caught.value.errno == errno.ENOENT
        assert (
            caught.value.strerror
            == f"no such folder ({tmp_path / 'a'} is a loop of symbolic links)"
        )
        assert caught.value.filename == str(folder)
        assert _tree(tmp_path) == before


def test_a_looped_yaml_path_is_refused_as_a_loop(tmp_path: Path) -> None:
    # Unchanged (review 44): the file, not its folder, is the loop.
    (tmp_path / "m.yaml").symlink_to("m.yaml")
    before = _tree(tmp_path)
    with pytest.raises(ValueError, match=rf"^{tmp_path / 'm.yaml'} is a loop of symbolic links"):
        write_map(_GRID, tmp_path / "m.yaml")
    assert _tree(tmp_path) == before


def test_a_folder_given_through_a_link_is_written_into(tmp_path: Path) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to("real")
    image = write_map(_GRID, tmp_path / "link" / "m.yaml")
    assert image == tmp_path / "link" / "m.pgm"
    assert sorted(_tree(tmp_path)) == ["link", "real", "real/m.pgm", "real/m.yaml"]
    assert np.array_equal(read_map(tmp_path / "link" / "m.yaml").occupied(), _GRID.occupied())
