"""Paths, driven traces and laser scans on world axes."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool
from navkit.geometry import Pose2D, as_pose
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import Path2D
from navkit.plot._figure import (
    COORD_LIMIT,
    array_like,
    as_color,
    as_coords,
    as_label,
    axes_for,
    finish_axes,
)
from navkit.sim import Trace

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["path_points", "plot_path", "plot_scan", "plot_trace", "trace_xy"]


def path_points(path: Any, grid: Any, name: str = "path") -> FloatArray:
    """World points ``(n, 2)`` of a Path2D or an ``(n, 2)`` array (checked)."""
    if grid is not None and not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid or None, got {type(grid).__name__}")
    if isinstance(path, Path2D):
        if path.frame == "grid":
            if grid is None:
                raise ValueError(
                    f"{name} is in the 'grid' frame: give grid= (the OccupancyGrid it was "
                    "planned on) to draw it in world coordinates"
                )
            if np.abs(path.points).max() > 2.0**62:
                raise ValueError(f"{name} lies beyond ±2**62 cells")
            points = grid.cell_to_world(path.points)
        else:
            points = path.points
        return as_coords(points, name)
    if isinstance(path, (str, bytes)) or not array_like(path):
        raise TypeError(f"{name} must be a Path2D or an (n, 2) array, got {type(path).__name__}")
    points = as_coords(path, name)
    if points.shape[0] == 0:
        raise ValueError(f"{name} must hold at least one point, got shape (0, 2)")
    return points


def plot_path(
    path: Path2D | ArrayLike,
    *,
    ax: Axes | None = None,
    grid: OccupancyGrid | None = None,
    label: str | None = None,
    color: Any = None,
) -> Axes:
    """Draw a path as a polyline on world axes.

    Parameters
    ----------
    path : Path2D or array_like, shape (n, 2)
        A planner's path (a ``"grid"`` frame one needs ``grid``) or world
        points ``(x, y)`` in metres, within ±1e9 m.
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted.
    grid : OccupancyGrid, optional
        The map a ``"grid"`` frame path was planned on.
    label : str, optional
        Legend entry.
    color : matplotlib colour, optional
        Line colour (default: the axes' next colour).

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``path`` is neither a Path2D nor numbers, a wrong type of option.
    ValueError
        No points, non-finite points or beyond ±1e9 m, a ``"grid"`` path
        without ``grid``, an unknown colour.

    Examples
    --------
    >>> import numpy as np
    >>> ax = plot_path(np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 0.5]]), label="plan")
    >>> np.asarray(ax.lines[0].get_xydata()).tolist()  # asarray: matplotlib types it array_like
    [[0.0, 0.0], [1.0, 0.5], [2.0, 0.5]]
    """
    points = path_points(path, grid)
    text = as_label(label, "label")
    colour = as_color(color, "color")
    axes = axes_for(ax)
    axes.plot(points[:, 0], points[:, 1], "-", marker="." if len(points) == 1 else None,
              color=colour, label=text, linewidth=1.5, zorder=3)  # fmt: skip
    finish_axes(axes)
    return axes


def trace_xy(trace: Any, name: str = "trace") -> tuple[FloatArray, FloatArray]:
    """``(true xy (T, 2), estimated xy (T, 2) with NaN rows)`` of a checked Trace (T >= 1)."""
    if not isinstance(trace, Trace):
        raise TypeError(f"{name} must be a navkit.sim.Trace, got {type(trace).__name__}")
    if len(trace) == 0:
        # Nothing to draw, and no start or end to mark (a Simulation records at least one row).
        raise ValueError(f"{name} has no poses to draw (a trace of 0 rows)")
    true_xy = as_coords(trace.poses[:, :2], f"{name}.poses")
    est_xy = as_coords(trace.estimates[:, :2], f"{name}.estimates", nan_ok=True)
    return true_xy, est_xy


def plot_trace(
    trace: Trace,
    *,
    ax: Axes | None = None,
    label: str | None = None,
    color: Any = None,
    estimate: bool = True,
) -> Axes:
    """Draw a simulated run: true poses solid, the estimator's dashed, start and end marked.

    The start is a circle, the end a square; collisions are red crosses at
    the true position where they happened.

    Parameters
    ----------
    trace : navkit.sim.Trace
        The run.
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted.
    label : str, optional
        Legend entry of the true path (the estimate gets ``"<label> (estimate)"``).
    color : matplotlib colour, optional
        Colour of both lines (default: the axes' next colour).
    estimate : bool, default True
        Draw the estimated poses (when the run had an estimator).

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``trace`` is not a Trace, a wrong type of option.
    ValueError
        A trace without rows, poses beyond ±1e9 m, an unknown colour.

    Examples
    --------
    >>> from navkit.geometry import Twist2D
    >>> from navkit.kinematics import DiffDrive
    >>> from navkit.sim import Robot, Simulation, World
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    >>> trace = Simulation(World(), robot, lambda obs: Twist2D(0.5, 0.0, 0.0),
    ...                    start=(0.0, 0.0, 0.0), duration=1.0).run()
    >>> ax = plot_trace(trace, label="run")
    >>> [line.get_label() for line in ax.lines][:1]
    ['run']
    """
    true_xy, est_xy = trace_xy(trace)
    text = as_label(label, "label")
    colour = as_color(color, "color")
    show_estimate = as_bool(estimate, "estimate")
    axes = axes_for(ax)
    draw_trace(axes, trace, true_xy, est_xy, label=text, color=colour, estimate=show_estimate)
    finish_axes(axes)
    return axes


def draw_trace(
    ax: Axes,
    trace: Trace,
    true_xy: FloatArray,
    est_xy: FloatArray,
    *,
    label: str | None,
    color: Any,
    estimate: bool,
    alpha: float = 1.0,
) -> None:
    """Draw a checked trace (see :func:`plot_trace`)."""
    (line,) = ax.plot(true_xy[:, 0], true_xy[:, 1], "-", color=color, label=label,
                      linewidth=1.5, alpha=alpha, zorder=4)  # fmt: skip
    colour = line.get_color()
    if estimate and np.isfinite(est_xy).all(axis=1).any():
        est_label = None if label is None else f"{label} (estimate)"
        ax.plot(est_xy[:, 0], est_xy[:, 1], "--", color=colour, label=est_label,
                linewidth=1.2, alpha=alpha, zorder=4)  # fmt: skip
    ax.plot(true_xy[0, 0], true_xy[0, 1], "o", color=colour, markersize=6, alpha=alpha, zorder=5)
    ax.plot(true_xy[-1, 0], true_xy[-1, 1], "s", color=colour, markersize=6, alpha=alpha,
            zorder=5)  # fmt: skip
    hits = [e.t for e in trace.events if e.kind == "collision"]
    if hits:
        x = np.interp(hits, trace.times, true_xy[:, 0])
        y = np.interp(hits, trace.times, true_xy[:, 1])
        ax.plot(x, y, "x", color="red", markersize=9, markeredgewidth=2, zorder=6)


def scan_pose(pose: Any) -> Pose2D:
    """The sensor pose of :func:`plot_scan`, within ±1e9 m."""
    p = as_pose(pose, "pose")
    if abs(p.x) > COORD_LIMIT or abs(p.y) > COORD_LIMIT:
        raise ValueError(f"pose must lie within ±{COORD_LIMIT:g} m to be drawn")
    return p


def plot_scan(
    scan: LaserScan,
    pose: Pose2D | ArrayLike,
    *,
    ax: Axes | None = None,
    rays: bool = False,
    color: Any = None,
    label: str | None = None,
) -> Axes:
    """Draw a laser scan's end points (and optionally its beams) from a sensor pose.

    Only valid returns are drawn (``scan.valid_mask()``: finite and within
    ``[range_min, range_max)``); the sensor is a small triangle pointing along
    its heading.

    Parameters
    ----------
    scan : LaserScan
        The scan, in the sensor frame.
    pose : Pose2D or array_like [x, y, theta]
        World pose of the sensor, within ±1e9 m.
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted.
    rays : bool, default False
        Also draw each valid beam from the sensor to its end point.
    color : matplotlib colour, optional
        Colour of points and beams (default: the axes' next colour).
    label : str, optional
        Legend entry of the points.

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``scan`` is not a LaserScan, a bad pose or option type.
    ValueError
        A pose or end points beyond ±1e9 m, an unknown colour.

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from navkit.mapping import LaserScan
    >>> scan = LaserScan([1.0, 2.0, math.inf], angle_min=0.0, angle_increment=math.pi / 2,
    ...                  range_min=0.1, range_max=5.0)
    >>> ax = plot_scan(scan, (1.0, 1.0, 0.0), rays=True)
    >>> np.asarray(ax.collections[0].get_offsets()).round(6).tolist()
    [[2.0, 1.0], [1.0, 3.0]]
    """
    if not isinstance(scan, LaserScan):
        raise TypeError(f"scan must be a LaserScan, got {type(scan).__name__}")
    p = scan_pose(pose)
    show_rays = as_bool(rays, "rays")
    colour = as_color(color, "color")
    text = as_label(label, "label")
    points = as_coords(scan.to_points(p), "scan end points")
    axes = axes_for(ax)
    draw_scan(axes, p, points, rays=show_rays, color=colour, label=text)
    finish_axes(axes)
    return axes


def draw_scan(
    ax: Axes, pose: Pose2D, points: FloatArray, *, rays: bool, color: Any, label: str | None
) -> None:
    """Draw checked scan end points from ``pose`` (see :func:`plot_scan`)."""
    from matplotlib.collections import LineCollection

    dots = ax.scatter(points[:, 0], points[:, 1], s=6, color=color, label=label, zorder=5)
    colour = dots.get_facecolor()
    if rays and len(points):
        origin = np.broadcast_to([pose.x, pose.y], points.shape)
        beams = np.stack((origin, points), axis=1)
        ax.add_collection(LineCollection(list(beams), colors=colour, linewidths=0.5,
                                         alpha=0.35, zorder=4))  # fmt: skip
    ax.plot(pose.x, pose.y, marker=(3, 0, np.degrees(pose.theta) - 90.0), color="black",
            markersize=7, linestyle="none", zorder=6)  # fmt: skip
    ax.update_datalim([[pose.x, pose.y]])
    ax.autoscale_view()
