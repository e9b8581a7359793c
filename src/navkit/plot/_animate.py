"""A GIF of a run: the robot's footprint moving over the scene, its scans and plan."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit.geometry import Pose2D, as_pose
from navkit.plot._figure import (
    COORD_LIMIT,
    array_like,
    as_coords,
    bounded_float,
    bounded_int,
    new_figure,
)
from navkit.plot._files import check_size, output_path, written_atomically
from navkit.plot._lines import trace_xy
from navkit.plot._scene import CheckedScene, check_scene, draw_scene
from navkit.sim import Scene, Trace

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["animate_trace"]

#: Points of a circular footprint's outline.
_CIRCLE_POINTS = 48
#: Most pixels of all frames together (a GIF's frames are held until written).
MAX_FRAME_PIXELS = 1 << 28
_SCAN_COLOUR = "magenta"


def _footprint(value: Any) -> FloatArray:
    """Outline ``(V, 2)`` in the robot frame of a radius or a polygon's vertices."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError("footprint must be a radius (m) or (V, 2) polygon vertices, got bool")
    if isinstance(value, (int, float, np.integer, np.floating)) or (
        issubclass(type(value), np.ndarray) and value.ndim == 0
    ):
        radius = bounded_float(value, "footprint", 1e-6, 1e6)
        a = np.linspace(0.0, 2.0 * math.pi, _CIRCLE_POINTS, endpoint=False)
        return np.column_stack((radius * np.cos(a), radius * np.sin(a)))
    if isinstance(value, (str, bytes)) or not array_like(value):
        raise TypeError(
            f"footprint must be a radius (m) or (V, 2) polygon vertices, got {type(value).__name__}"
        )
    verts = as_coords(value, "footprint")
    if len(verts) < 3 or np.abs(verts).max() > 1e6:
        raise ValueError("footprint polygon needs at least 3 vertices within ±1e6 m")
    return verts


def _source(value: Any) -> CheckedScene:
    if isinstance(value, Scene):
        scene = check_scene(value, "source")
        if not scene.traces:
            raise ValueError("source: the scene has no traces to animate")
        return scene
    if isinstance(value, Trace):
        true_xy, est_xy = trace_xy(value, "source")
        return CheckedScene("", None, None, (), (("", value, true_xy, est_xy),), ())
    raise TypeError(f"source must be a navkit.sim.Scene or Trace, got {type(value).__name__}")


def _index_at(times: FloatArray, t: float) -> int:
    """The last row at or before ``t`` (the first before the run starts)."""
    return max(int(np.searchsorted(times, t, side="right")) - 1, 0)


def animate_trace(
    source: Scene | Trace,
    path: str | os.PathLike[str],
    *,
    fps: int = 10,
    max_frames: int = 60,
    footprint: float | ArrayLike = 0.2,
    lidar_mount: Pose2D | ArrayLike = (0.0, 0.0, 0.0),
    dpi: float = 80.0,
) -> Path:
    """Write a GIF of a run: the robot moving over the map, its scans, the plan.

    Over the scene's background (map, world, planned paths, markers), each
    trace's robot is drawn as its footprint with a heading line, the path driven
    so far behind it, and the latest recorded scan's end points (when the run
    kept them: ``Simulation(..., record_scans=True)``); moving obstacles move.
    Frames are spaced evenly in simulated time, at most ``max_frames`` of them,
    so a long run still writes in a few seconds. The GIF is written with Pillow
    (each frame in its own 256 colours) to a temporary file in the same folder,
    which then replaces ``path``.

    Parameters
    ----------
    source : navkit.sim.Scene or Trace
        A scene with at least one trace (every trace is animated, on one clock)
        or a bare trace.
    path : str or path-like
        The ``.gif`` file to write, in an existing folder; replaced if it exists.
    fps : int, default 10
        Frames per second of the GIF, in [1, 50]. GIF delays are whole
        hundredths of a second: each frame lasts the nearest one to
        ``1 / fps`` (30 plays at 33 frames per second, 35 at 33, 15 at 14.3).
    max_frames : int, default 60
        Most frames, in [1, 1000]; all frames together may hold at most 2**28
        pixels (GIF frames are held until written): at ``dpi`` 300, 97 frames.
    footprint : float or array_like (V, 2), default 0.2
        The robot's radius (m) or polygon vertices in its own frame.
    lidar_mount : Pose2D or array_like [x, y, theta], default (0, 0, 0)
        Pose of the LiDAR on the robot (as ``Lidar(mount=...)``), to place scans.
    dpi : float, default 80
        Resolution of the frames, dots per inch, in [10, 300] (the figure is
        6.4 × 4.8 in).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    TypeError
        ``source`` is neither a Scene nor a Trace, a bad option type.
    ValueError
        A scene without traces, a trace without rows, a path not ending in
        ``.gif`` or naming a loop of symbolic links or something else that is
        not a regular file, an option out
        of range, frames of more than 2**28 pixels in all (the frames drawn,
        ``max_frames`` or the longest trace's rows if fewer, × the frame's
        pixels at ``dpi``), coordinates beyond ±1e9 m.
    FileNotFoundError
        The folder of ``path`` does not exist, or is (or lies below) a loop of
        symbolic links: ``"path: folder {folder} does not exist"``, the loop
        named after it. Nothing is drawn or written.
    NotADirectoryError
        A file stands where a folder of ``path`` should be:
        ``"path: {file} is a file, not a folder"``. Nothing is drawn or written.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from navkit.geometry import Twist2D
    >>> from navkit.kinematics import DiffDrive
    >>> from navkit.sim import Robot, Simulation, World
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    >>> trace = Simulation(World(), robot, lambda obs: Twist2D(0.5, 0.0, 0.3),
    ...                    start=(0.0, 0.0, 0.0), duration=1.0).run()
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     gif = animate_trace(trace, Path(folder) / "run.gif", max_frames=3, dpi=30)
    ...     print(gif.name, gif.read_bytes()[:6])
    run.gif b'GIF89a'
    """
    scene = _source(source)
    rate = bounded_int(fps, "fps", 1, 50)
    frames_most = bounded_int(max_frames, "max_frames", 1, 1000)
    outline = _footprint(footprint)
    mount = as_pose(lidar_mount, "lidar_mount")
    if abs(mount.x) > 1e6 or abs(mount.y) > 1e6:
        raise ValueError("lidar_mount must lie within ±1e6 m of the robot")
    resolution = bounded_float(dpi, "dpi", 10.0, 300.0)
    target = output_path(path, "path", ".gif")

    # No layout engine (it would lay the figure out again for every frame).
    fig = new_figure(layout=None)
    fig.set_dpi(resolution)
    check_size(fig, resolution)
    ax = fig.add_subplot()
    moving_patches = draw_scene(ax, scene, traces=False)
    moving = scene.world.moving if scene.world is not None else ()
    # Robots take the colours after the paths' (as plot_scene gives the traces).
    first = len(scene.paths)
    robots = [_Robot(ax, trace, true_xy, est_xy, outline, f"C{(first + k) % 10}")
              for k, (_, trace, true_xy, est_xy) in enumerate(scene.traces)]  # fmt: skip
    t0 = min(float(r.trace.times[0]) for r in robots)
    t1 = max(float(r.trace.times[-1]) for r in robots)
    n = min(frames_most, max(len(r.trace) for r in robots))
    width, height = (round(float(v) * resolution) for v in fig.get_size_inches())
    if n * width * height > MAX_FRAME_PIXELS:
        raise ValueError(
            f"{n} frames of {width} × {height} pixels exceed {MAX_FRAME_PIXELS} pixels in "
            "all: use a smaller max_frames or dpi"
        )
    clock = np.linspace(t0, t1, n) if n > 1 else np.array([t1])
    # Fixed limits (the whole run, the robot's body included): frames must not jump.
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    for r in robots:
        lo = r.true_xy.min(axis=0) - r.radius
        hi = r.true_xy.max(axis=0) + r.radius
        x0, x1 = min(x0, lo[0]), max(x1, hi[0])
        y0, y1 = min(y0, lo[1]), max(y1, hi[1])
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    caption = ax.set_title(_caption(scene.title, t0))
    # Fixed margins (tight_layout would cost more than drawing every frame).
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.11, top=0.92)

    # Blitting: the scene is drawn once; each frame redraws only what moves.
    dynamic: list[Any] = [caption, *moving_patches]
    for r in robots:
        dynamic += r.artists
    dynamic.sort(key=lambda artist: float(artist.get_zorder()))
    for artist in dynamic:
        artist.set_animated(True)
    canvas: Any = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    frames = []
    for t in clock:
        for r in robots:
            r.show(float(t), mount)
        for ob, patch in zip(moving, moving_patches, strict=True):
            patch.set_xy(np.asarray(ob.geometry_at(float(t)).exterior.coords))
        caption.set_text(_caption(scene.title, float(t)))
        canvas.restore_region(background)
        for artist in dynamic:
            fig.draw_artist(artist)
        frames.append(_frame(canvas))
    with written_atomically(target) as temporary:
        frames[0].save(temporary, format="GIF", save_all=True, append_images=frames[1:],
                       duration=_frame_delay_ms(rate), loop=0)  # fmt: skip
    return target


def _frame_delay_ms(fps: int) -> int:
    """The GIF delay of a frame at ``fps``: the nearest whole hundredth of a second, ms.

    GIF stores delays in hundredths, and Pillow truncates milliseconds to them:
    ``round(1000 / 35)`` = 29 ms would be written as 2/100 s, 50 frames per second
    instead of 33. At least 2/100 s (browsers slow shorter delays down to 1/10 s).
    """
    return 10 * max(round(100.0 / fps), 2)


def _frame(canvas: Any) -> Any:
    """The canvas as a palette image (what a GIF frame holds).

    Each frame gets its own 256 colours (what it shows changes: paths grow,
    scans appear, bodies pass over the map). By fast octree: the median cut of
    ``convert("P", palette=ADAPTIVE)`` took ten times as long (a third of a
    whole ``navkit run --animate``) and, weighing colours by their pixels,
    merged a thin path's or a marker's colour into a neighbour's, 40 levels
    off; the octree keeps each colour a plot shows within a few levels.
    """
    from PIL import Image

    rgba = np.asarray(canvas.buffer_rgba())
    return Image.fromarray(np.ascontiguousarray(rgba[..., :3])).quantize(
        256, method=Image.Quantize.FASTOCTREE
    )


def _caption(title: str, t: float) -> str:
    return f"{title}   t = {t:.1f} s" if title else f"t = {t:.1f} s"


class _Robot:
    """The artists of one animated trace and how to move them."""

    def __init__(
        self,
        ax: Axes,
        trace: Trace,
        true_xy: FloatArray,
        est_xy: FloatArray,
        outline: FloatArray,
        colour: str,
    ) -> None:
        from matplotlib.patches import Polygon as PolygonPatch

        self.trace = trace
        self.true_xy = true_xy
        self.outline = outline
        self.body = PolygonPatch(outline, closed=True, facecolor=colour, alpha=0.45,
                                 edgecolor="black", linewidth=1.0, zorder=8)  # fmt: skip
        ax.add_patch(self.body)
        (self.heading,) = ax.plot([], [], "-", color="black", linewidth=1.2, zorder=9)
        (self.driven,) = ax.plot([], [], "-", color=colour, linewidth=1.5, zorder=7)
        (self.estimated,) = ax.plot([], [], "--", color=colour, linewidth=1.2, zorder=7)
        self.est_xy = est_xy
        self.scan = ax.scatter(np.empty(0), np.empty(0), s=5, color=_SCAN_COLOUR, zorder=6)
        self.artists: list[Any] = [self.body, self.heading, self.driven, self.estimated, self.scan]
        self.scan_times = np.array([s.stamp for s in trace.scans], dtype=np.float64)
        self.reach = float(np.abs(outline).max())
        # The farthest the body reaches from the robot's position in any heading (a
        # square's corner turned by 45° lies beyond its largest coordinate).
        self.radius = float(np.hypot(outline[:, 0], outline[:, 1]).max())

    def show(self, t: float, mount: Pose2D) -> None:
        i = _index_at(self.trace.times, t)
        x, y, theta = (float(v) for v in self.trace.poses[i])
        c, s = math.cos(theta), math.sin(theta)
        rot = np.array([[c, s], [-s, c]])
        # A heading below 1e-290 rad times an outline's rounding-noise coordinate
        # (1e-17) underflows to 0, as under NumPy's defaults, whatever np.seterr says.
        with np.errstate(under="ignore"):
            self.body.set_xy(self.outline @ rot + (x, y))
        self.heading.set_data([x, x + self.reach * c], [y, y + self.reach * s])
        self.driven.set_data(self.true_xy[: i + 1, 0], self.true_xy[: i + 1, 1])
        self.estimated.set_data(self.est_xy[: i + 1, 0], self.est_xy[: i + 1, 1])
        points = np.empty((0, 2))
        if self.scan_times.size:
            j = int(np.searchsorted(self.scan_times, t, side="right")) - 1
            if j >= 0:
                reading = self.trace.scans[j]
                at = self.trace.poses[_index_at(self.trace.times, reading.stamp)]
                sensor = Pose2D(float(at[0]), float(at[1]), float(at[2])).compose(mount)
                if abs(sensor.x) <= COORD_LIMIT and abs(sensor.y) <= COORD_LIMIT:
                    points = reading.scan.to_points(sensor)
                    points = points[np.all(np.abs(points) <= COORD_LIMIT, axis=1)]
        self.scan.set_offsets(points)
