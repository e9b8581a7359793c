"""``write_map`` refuses a YAML or image path that is a loop of symbolic links (review 44).

Before, the save wrote both temporary files and then failed with ``OSError``
("Too many levels of symbolic links") from the mode lookup of the atomic
write; it is now a ``ValueError`` naming the file, raised before anything is
written (see ``tests/shared/test_review44_smalls3_link_loops.py``).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def _tree(folder: Path) -> dict[str, str]:
    return {
        p.name: f"-> {os.readlink(p)}" if p.is_symlink() else p.read_bytes().hex()
        for p in folder.iterdir()
    }


@pytest.mark.parametrize(("mode", "looped"), [("trinary", "m.yaml"), ("trinary", "m.pgm"),
                                              ("scale", "m.png")])  # fmt: skip
def test_a_looped_map_file_is_refused_and_nothing_is_written(
    tmp_path: Path, mode: str, looped: str
) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)
    (tmp_path / looped).symlink_to(f"other{Path(looped).suffix}")
    (tmp_path / f"other{Path(looped).suffix}").symlink_to(looped)
    before = _tree(tmp_path)
    with pytest.raises(ValueError, match=rf"^{tmp_path / looped} is a loop of symbolic links"):
        write_map(grid, tmp_path / "m.yaml", mode=mode)
    with pytest.raises(ValueError, match=rf"^{tmp_path / looped} is a loop of symbolic links"):
        grid.save(tmp_path / "m.yaml", mode=mode)
    assert _tree(tmp_path) == before
