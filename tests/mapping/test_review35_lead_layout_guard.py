"""world_to_cell's C fast path stands aside where its struct reading is not known good.

``navkit._shared.array_objects`` reads NumPy's array structs by offset and calls
``PyArray_Empty`` by its index in NumPy's C-API table, which NumPy fixes for a
major version only: under any NumPy but 2 (or a layout that does not check out)
the fast entry must refuse every object, so the general way answers, with the
same cells.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from navkit.mapping import OccupancyGrid

_CODE = """
import numba  # noqa: F401  (numba itself refuses a NumPy 3: loaded before the change)
import numpy as np
np.__version__ = {version!r}
from navkit.mapping import OccupancyGrid
from navkit._shared import array_objects as _array_objects
from navkit.mapping._new_cells_kernel import new_cells_entry
points = np.array([[0.7, 0.2], [-1.3, 2.6], [0.05, -0.05]])
print(_array_objects.LAYOUT_OK)
print(new_cells_entry()(points, 0.5, -0.25, 0.3, 0.1) is None)
grid = OccupancyGrid(np.zeros((4, 5)), resolution=0.1, origin=(0.5, -0.25, 0.3))
print(grid.world_to_cell(points).tolist())
"""


def _run(version: str, cache: Path) -> list[str]:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    done = subprocess.run(
        [sys.executable, "-c", _CODE.format(version=version)],
        check=True, capture_output=True, text=True, env=env,
    )  # fmt: skip
    return done.stdout.splitlines()


def test_the_fast_entry_refuses_everything_under_another_numpy_major(tmp_path: Path) -> None:
    points = np.array([[0.7, 0.2], [-1.3, 2.6], [0.05, -0.05]])
    grid = OccupancyGrid(np.zeros((4, 5)), resolution=0.1, origin=(0.5, -0.25, 0.3))
    expected = str(grid.world_to_cell(points).tolist())
    # Separate caches: the layout check is baked into the compiled code.
    assert _run("3.0.0", tmp_path / "three") == ["False", "True", expected]
    assert _run(np.__version__, tmp_path / "two") == ["True", "False", expected]
