"""Input guards of navkit.plot that tests/plot did not reach (review 32): each refuses by name."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.plot import animate_trace, plot_grid, plot_path, save_figure
from navkit.sim import Robot, Simulation, Trace, World

pytest.importorskip("matplotlib")


class _BytesPath:
    def __fspath__(self) -> bytes:
        return b"out.png"


def _trace() -> Trace:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    return Simulation(
        World(), robot, lambda obs: Twist2D(0.2, 0.0, 0.0), start=(0.0, 0.0, 0.0), duration=0.1
    ).run()


def test_a_path_like_naming_bytes_is_refused(tmp_path: Path) -> None:
    ax = plot_grid(OccupancyGrid.from_occupancy(np.zeros((4, 4), dtype=bool), resolution=0.1))
    with pytest.raises(TypeError, match="path must be a str or path-like, got bytes"):
        save_figure(ax, _BytesPath())  # type: ignore[arg-type]


def test_a_picture_over_the_pixel_limit_is_refused_unwritten(tmp_path: Path) -> None:
    ax = plot_grid(OccupancyGrid.from_occupancy(np.zeros((4, 4), dtype=bool), resolution=0.1))
    ax.figure.set_size_inches(20.0, 20.0)  # 12000 × 12000 pixels at 600 dpi > 2**26
    with pytest.raises(ValueError, match="would be"):
        save_figure(ax, tmp_path / "big.png", dpi=600)
    assert list(tmp_path.iterdir()) == []


def test_a_colour_of_another_type_is_refused_by_name() -> None:
    with pytest.raises(TypeError, match="color must be a matplotlib colour"):
        plot_path([[0.0, 0.0], [1.0, 1.0]], color=5)


def test_animate_refuses_a_bool_footprint_and_a_far_lidar_mount(tmp_path: Path) -> None:
    trace = _trace()
    with pytest.raises(TypeError, match="footprint must be a radius"):
        animate_trace(trace, tmp_path / "a.gif", footprint=True)
    with pytest.raises(ValueError, match="lidar_mount must lie within"):
        animate_trace(trace, tmp_path / "a.gif", lidar_mount=(2e6, 0.0, 0.0))
    assert list(tmp_path.iterdir()) == []
