"""``save_figure`` and ``animate_trace`` name a folder that is a loop of symbolic links (review 45).

Before, a ``path`` in such a folder (``a -> b``, ``b -> a``, ``a/out.png``) gave
"path: the folder 'a' does not exist", as for a missing folder, while
``write_map`` raised ``OSError`` (``ELOOP``) and the command line called the file
a loop. Every writer now says the folder does not exist and which folder of
the path is the loop, before drawing anything. See
``tests/shared/test_review45_folder_loops.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.plot import animate_trace, plot_grid, save_figure
from navkit.sim import Robot, Simulation, Trace, World

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def _trace() -> Trace:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    return Simulation(World(), robot, lambda obs: Twist2D(0.2, 0.0, 0.0), start=(0.0, 0.0, 0.0),
                      duration=0.2).run()  # fmt: skip


def _writers() -> dict[str, tuple[Any, str]]:
    ax = plot_grid(OccupancyGrid.from_occupancy(np.eye(4, dtype=bool), resolution=0.1))
    trace = _trace()
    return {
        "save_figure": (lambda path: save_figure(ax, path), ".png"),
        "animate_trace": (lambda path: animate_trace(trace, path, max_frames=2, dpi=20), ".gif"),
    }


@pytest.mark.parametrize("writer", ["save_figure", "animate_trace"])
@pytest.mark.parametrize("below", [(), ("b",)])
def test_a_looped_folder_is_named_with_its_loop(
    tmp_path: Path, writer: str, below: tuple[str, ...]
) -> None:
    write, suffix = _writers()[writer]
    loop = tmp_path / "a"
    loop.symlink_to("b")
    (tmp_path / "b").symlink_to("a")
    folder = loop.joinpath(*below)
    before = _tree(tmp_path)
    expected = f"path: folder {folder} does not exist ({loop} is a loop of symbolic links)"
    with pytest.raises(FileNotFoundError) as caught:
        write(folder / f"out{suffix}")
    assert str(caught.value) == expected
    assert _tree(tmp_path) == before


@pytest.mark.parametrize("writer", ["save_figure", "animate_trace"])
def test_a_missing_folder_says_so_in_the_same_words(tmp_path: Path, writer: str) -> None:
    write, suffix = _writers()[writer]
    with pytest.raises(FileNotFoundError) as caught:
        write(tmp_path / "missing" / f"out{suffix}")
    assert str(caught.value) == f"path: folder {tmp_path / 'missing'} does not exist"
    assert _tree(tmp_path) == {}


@pytest.mark.parametrize("writer", ["save_figure", "animate_trace"])
def test_a_looped_file_and_a_linked_folder(tmp_path: Path, writer: str) -> None:
    write, suffix = _writers()[writer]
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to("real")
    looped = tmp_path / "link" / f"loop{suffix}"
    looped.symlink_to(looped.name)
    # The file, not its folder, is the loop: refused as before (review 44).
    with pytest.raises(ValueError, match=rf"^path '{looped}' is a loop of symbolic links$"):
        write(looped)
    written = write(tmp_path / "link" / f"out{suffix}")
    assert written == tmp_path / "link" / f"out{suffix}"
    tree = _tree(tmp_path)
    assert sorted(tree) == ["link", "real", f"real/loop{suffix}", f"real/out{suffix}"]
    assert tree[f"real/out{suffix}"]  # written, not empty
