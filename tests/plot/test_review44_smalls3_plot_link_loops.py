"""``save_figure`` and ``animate_trace`` name a ``path`` that is a loop of links (review 44).

``path.exists()`` says False for ``out.png -> out.png``: the picture was drawn
and written to a temporary file, and only then did the save fail with
``OSError`` ("Too many levels of symbolic links"). Both now refuse it up
front, naming the argument, as they refuse a folder or a device.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.plot import animate_trace, plot_grid, save_figure
from navkit.sim import Robot, Simulation, World

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def test_save_figure_names_a_looped_path(tmp_path: Path) -> None:
    ax = plot_grid(OccupancyGrid.from_occupancy(np.eye(4, dtype=bool), resolution=0.1))
    loop = tmp_path / "out.png"
    loop.symlink_to("out.png")
    with pytest.raises(ValueError, match=rf"^path '{loop}' is a loop of symbolic links$"):
        save_figure(ax, loop)
    assert [(p.name, os.readlink(p)) for p in tmp_path.iterdir()] == [("out.png", "out.png")]
    # A folder that is such a loop is a missing folder, as before.
    with pytest.raises(FileNotFoundError, match="does not exist"):
        save_figure(ax, loop / "x.png")


def test_animate_trace_names_a_looped_path(tmp_path: Path) -> None:
    loop = tmp_path / "out.gif"
    loop.symlink_to("other.gif")
    (tmp_path / "other.gif").symlink_to("out.gif")
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    trace = Simulation(World(), robot, lambda obs: Twist2D(0.2, 0.0, 0.0), start=(0.0, 0.0, 0.0),
                       duration=0.2).run()  # fmt: skip
    with pytest.raises(ValueError, match=rf"^path '{loop}' is a loop of symbolic links$"):
        animate_trace(trace, loop, max_frames=2, dpi=20)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.gif", "out.gif"]
