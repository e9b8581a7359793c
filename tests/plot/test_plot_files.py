"""save_figure and animate_trace: pictures written atomically, nothing else created."""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.plot import animate_trace, plot_grid, save_figure
from navkit.sim import (
    Lidar,
    Metrics,
    MovingObstacle,
    Robot,
    Scene,
    Simulation,
    Trace,
    World,
)

pytest.importorskip("matplotlib")


def _axes():  # type: ignore[no-untyped-def]
    occupied = np.zeros((10, 10), dtype=bool)
    occupied[7:, 7:] = True
    return plot_grid(OccupancyGrid.from_occupancy(occupied, resolution=0.1))


# ------------------------------------------------------------------ save_figure
def test_save_figure_writes_one_png_of_the_asked_size(tmp_path: Path) -> None:
    ax = _axes()
    out = save_figure(ax, tmp_path / "map.png", dpi=50)
    assert out == tmp_path / "map.png"
    assert [p.name for p in tmp_path.iterdir()] == ["map.png"]
    with Image.open(out) as image:
        assert image.format == "PNG" and image.size == (320, 240)  # 6.4 × 4.8 in at 50 dpi
        pixels = np.asarray(image.convert("L"))
    assert pixels.min() < 30 and pixels.max() > 240  # black cells and white ones: not blank
    save_figure(ax.figure, str(tmp_path / "figure.PNG"))  # a Figure, a str, upper case
    assert sorted(p.name for p in tmp_path.iterdir()) == ["figure.PNG", "map.png"]


def test_save_figure_replaces_a_file_and_a_failure_keeps_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "map.png"
    target.write_bytes(b"old")
    ax = _axes()
    save_figure(ax, target, dpi=20)
    assert target.read_bytes()[:4] == b"\x89PNG"
    good = target.read_bytes()

    def broken(*args: object, **kwargs: object) -> None:
        Path(args[0]).write_bytes(b"partial")  # type: ignore[arg-type]
        raise OSError("disk full")

    monkeypatch.setattr(ax.figure, "savefig", broken)
    with pytest.raises(OSError, match="disk full"):
        save_figure(ax, target)
    assert target.read_bytes() == good
    assert [p.name for p in tmp_path.iterdir()] == ["map.png"]  # no temporary file left


@pytest.mark.parametrize(
    ("what", "path", "kwargs", "error", "match"),
    [
        ("axes", "map.jpg", {}, ValueError, r"\.png"),
        ("axes", "", {}, ValueError, "path"),
        ("axes", "missing/map.png", {}, FileNotFoundError, "missing"),
        ("axes", b"map.png", {}, TypeError, "path"),
        ("axes", "map.png", {"dpi": 0}, ValueError, "dpi"),
        ("axes", "map.png", {"dpi": math.inf}, ValueError, "dpi"),
        ("axes", "map.png", {"dpi": "100"}, TypeError, "dpi"),
        ("array", "map.png", {}, TypeError, "fig_or_ax"),
    ],
)
def test_save_figure_refuses_bad_arguments(
    tmp_path: Path, what: str, path: object, kwargs: dict, error: type, match: str
) -> None:
    target = (tmp_path / path) if isinstance(path, str) and path else path
    subject = _axes() if what == "axes" else np.zeros((2, 2))
    with pytest.raises(error, match=match):
        save_figure(subject, target, **kwargs)  # type: ignore[arg-type]
    assert list(tmp_path.iterdir()) == []


def test_save_figure_refuses_a_folder(tmp_path: Path) -> None:
    (tmp_path / "x.png").mkdir()
    with pytest.raises(ValueError, match="folder"):
        save_figure(_axes(), tmp_path / "x.png")


# ---------------------------------------------------------------- animate_trace
def _scene(record_scans: bool = True) -> Scene:
    world = World([box(0.0, 0.0, 4.0, 2.0).exterior],
                  moving=[MovingObstacle.constant_velocity(0.1, start_xy=(3.5, 0.3),
                                                           velocity_xy=(0.0, 0.4))])  # fmt: skip
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,
                  lidar=Lidar(n_beams=36, range_max=5.0, rate=10.0, noise=None))  # fmt: skip
    trace = Simulation(world, robot, lambda obs: Twist2D(0.5, 0.0, 0.0), start=(0.5, 1.0, 0.0),
                       duration=3.0, record_scans=record_scans).run()  # fmt: skip
    return Scene("corridor", world=world, paths=(("plan", np.array([[0.5, 1.0], [3.5, 1.0]])),),
                 traces=(("run", trace),))  # fmt: skip


def _frames(path: Path) -> list[np.ndarray]:
    with Image.open(path) as gif:
        assert gif.format == "GIF"
        out = []
        for k in range(gif.n_frames):
            gif.seek(k)
            out.append(np.asarray(gif.convert("RGB"), dtype=np.int16))
    return out


def test_animate_trace_writes_a_gif_of_the_robot_moving(tmp_path: Path) -> None:
    scene = _scene()
    out = animate_trace(scene, tmp_path / "run.gif", max_frames=8, dpi=40, fps=5)
    assert [p.name for p in tmp_path.iterdir()] == ["run.gif"]
    frames = _frames(out)
    assert len(frames) == 8 and frames[0].shape == (192, 256, 3)
    with Image.open(out) as gif:
        assert gif.info["duration"] == 200  # 5 frames per second
    # The robot moves: consecutive frames differ by more than the caption's digits.
    changed = [int((np.abs(b - a).sum(axis=2) > 60).sum()) for a, b in itertools.pairwise(frames)]
    assert all(c > 30 for c in changed)
    # Scan end points (magenta) are on the walls in the frames after the first scan.
    magenta = np.array([255, 0, 255])
    assert (np.abs(frames[-1] - magenta).sum(axis=2) < 60).sum() > 5


def test_a_bare_trace_and_a_polygon_footprint_animate_too(tmp_path: Path) -> None:
    trace = _tiny_trace()
    square = [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]]
    out = animate_trace(trace, tmp_path / "bare.gif", max_frames=1000, dpi=20, footprint=square)
    # One frame per row at most (fewer rows than max_frames); Pillow merges identical ones.
    assert 5 < len(_frames(out)) <= len(trace)


def test_the_view_holds_a_turned_polygon_footprint_whole(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import navkit.plot._animate as animate

    figures = []
    original = animate.new_figure

    def new_figure(**kwargs: Any) -> Any:  # keeps the animation's figure to look at
        figures.append(original(**kwargs))
        return figures[-1]

    monkeypatch.setattr(animate, "new_figure", new_figure)
    # A 2 m square robot driving along y = 1 turned by 45°: its corners reach
    # √2 m from its centre, beyond its largest coordinate (1 m).
    times = np.linspace(0.0, 2.0, 5)
    poses = np.column_stack((times, np.ones_like(times), np.full_like(times, math.pi / 4)))
    metrics = Metrics(False, "timeout", 2.0, *[math.nan] * 6, 0.1, 0, 2.0)
    trace = Trace(times, poses, poses.copy(), np.zeros_like(poses), (), (), metrics)
    square = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
    animate_trace(trace, tmp_path / "turned.gif", footprint=square, max_frames=2, dpi=20)
    (ax,) = figures[0].axes
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    reach = math.sqrt(2.0)
    assert x0 <= -reach + 1e-9 and x1 >= 2.0 + reach - 1e-9
    assert y0 <= 1.0 - reach + 1e-9 and y1 >= 1.0 + reach - 1e-9


@pytest.mark.parametrize(
    ("source", "path", "kwargs", "error", "match"),
    [
        ("scene", "run.png", {}, ValueError, r"\.gif"),
        ("empty", "run.gif", {}, ValueError, "no traces"),
        ("array", "run.gif", {}, TypeError, "source"),
        ("scene", "run.gif", {"fps": 0}, ValueError, "fps"),
        ("scene", "run.gif", {"max_frames": 2.5}, TypeError, "max_frames"),
        ("scene", "run.gif", {"footprint": -0.1}, ValueError, "footprint"),
        ("scene", "run.gif", {"footprint": [[0, 0], [1, 0]]}, ValueError, "footprint"),
        ("scene", "run.gif", {"lidar_mount": (0.0, 0.0)}, ValueError, "lidar_mount"),
        ("scene", "run.gif", {"dpi": 1000}, ValueError, "dpi"),
        ("scene", "no/run.gif", {}, FileNotFoundError, "no"),
    ],
)
def test_animate_trace_refuses_bad_arguments(
    tmp_path: Path, source: str, path: str, kwargs: dict, error: type, match: str
) -> None:
    subject = {"scene": Scene("s", traces=(("t", _tiny_trace()),)), "empty": Scene("e"),
               "array": np.zeros((3, 3))}[source]  # fmt: skip
    with pytest.raises(error, match=match):
        animate_trace(subject, tmp_path / path, **kwargs)  # type: ignore[arg-type]
    assert list(tmp_path.iterdir()) == []


def _tiny_trace() -> Trace:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    return Simulation(World(), robot, lambda obs: Twist2D(0.2, 0.0, 0.0), start=(0.0, 0.0, 0.0),
                      duration=0.2).run()  # fmt: skip


def test_pictures_are_never_renamed_over_a_pipe(tmp_path: Path) -> None:
    # The atomic rename used to replace the pipe (or a device) itself with a file.
    import os
    import stat

    ax = _axes()
    for name in ("p.png", "a.gif"):
        fifo = tmp_path / name
        os.mkfifo(fifo)
        with pytest.raises(ValueError, match="not a regular file"):
            if name.endswith(".png"):
                save_figure(ax, fifo, dpi=20)
            else:
                animate_trace(_tiny_trace(), fifo, max_frames=2, dpi=20)
        assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.gif", "p.png"]
