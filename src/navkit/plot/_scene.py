"""A scenario's scene: map, world, plans, driven traces and markers in one picture."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool
from navkit.mapping import OccupancyGrid
from navkit.plot._figure import as_coords, axes_for, finish_axes, keep_directions
from navkit.plot._grid import draw_grid
from navkit.plot._lines import draw_trace, trace_xy
from navkit.sim import Scene, Trace, World

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.path import Path as MplPath

__all__ = ["CheckedScene", "check_scene", "draw_scene", "draw_world", "plot_scene"]

#: Markers of the labelled point sets, in turn.
_MARKERS = ("*", "D", "^", "v", "P", "X", "h")
_WALL_COLOUR = "0.15"
_MOVING_COLOUR = "tab:red"
#: Smallest margin around a scene, relative to its coordinates (and in m near 0).
_MIN_MARGIN = 1e-12


@frozen_setattr
@dataclass(frozen=True, slots=True)
class CheckedScene:
    """A Scene's contents, checked and converted to world arrays."""

    title: str
    grid: OccupancyGrid | None
    world: World | None
    paths: tuple[tuple[str, FloatArray], ...]
    traces: tuple[tuple[str, Trace, FloatArray, FloatArray], ...]
    points: tuple[tuple[str, FloatArray], ...]


def check_scene(scene: Any, name: str = "scene") -> CheckedScene:
    """A Scene's contents as world arrays that can be drawn (within ±1e9 m).

    A :class:`~navkit.sim.Scene` checks its parts when it is made; only the
    drawing range (and the traces' poses) is checked here.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"{name} must be a navkit.sim.Scene, got {type(scene).__name__}")
    paths = tuple(
        (label, as_coords(path, f"{name}.paths[{k}]"))
        for k, (label, path) in enumerate(scene.paths)
    )
    traces = tuple(
        (label, trace, *trace_xy(trace, f"{name}.traces[{k}]"))
        for k, (label, trace) in enumerate(scene.traces)
    )
    points = tuple(
        (label, as_coords(pts, f"{name}.points[{k}]"))
        for k, (label, pts) in enumerate(scene.points)
    )
    return CheckedScene(scene.title, scene.grid, scene.world, paths, traces, points)


def plot_scene(scene: Scene, *, ax: Axes | None = None, legend: bool = True) -> Axes:
    """Draw a scenario's scene: map, world, planned paths, driven traces, markers.

    Layers from the bottom: the grid (``scene.grid``, else the world's own
    map) in ROS map orientation; the world's solid polygons and circles
    (filled), walls and edges (lines), circular walls (``Circle(...,
    solid=False)``: outlines) and moving obstacles (where they are at t = 0,
    dashed, with their routes dotted); the planned paths; the traces (true
    poses solid, estimates dashed, start circle, end square, collisions as
    red crosses); the labelled points; the title and a legend.

    The view is the scene with a margin (of the map, its known cells only),
    at equal scales. On axes that already hold something (artists, or limits
    set with ``set_xlim``/``set_ylim``) the view is widened to hold what they
    showed, along each axis where they hold data or had limits set (after an
    ``axhline`` only, or ``set_xlim`` only, the other axis is the scene's),
    and their title is replaced only by a non-empty scene title.

    Parameters
    ----------
    scene : navkit.sim.Scene
        What to draw (``ScenarioResult.scene``).
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted.
    legend : bool, default True
        Add a legend of the labelled items.

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``scene`` is not a Scene, or holds something of the wrong type.
    ValueError
        Coordinates that are not finite or lie beyond ±1e9 m, a trace
        without rows.

    Examples
    --------
    >>> import numpy as np
    >>> from shapely.geometry import box
    >>> from navkit.sim import Circle, Scene, World
    >>> scene = Scene("a room", world=World([box(0, 0, 4, 3).exterior, Circle((2, 1.5), 0.3)]),
    ...               paths=(("plan", np.array([[0.5, 0.5], [3.5, 2.5]])),),
    ...               points=(("goal", np.array([[3.5, 2.5]])),))
    >>> ax = plot_scene(scene)
    >>> legend = ax.get_legend()
    >>> assert legend is not None  # an entry per labelled path and point set
    >>> ax.get_title(), [t.get_text() for t in legend.get_texts()]
    ('a room', ['plan', 'goal'])
    """
    checked = check_scene(scene)
    show_legend = as_bool(legend, "legend")
    axes = axes_for(ax)
    draw_scene(axes, checked, traces=True)
    labels = axes.get_legend_handles_labels()[1] if show_legend else []
    if len(labels) > 6:
        # A long legend would hide the scene: put it beside the axes, and let the
        # layout make room for it.
        axes.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="x-small")
        from matplotlib.figure import Figure

        figure = axes.get_figure()
        if isinstance(figure, Figure) and ax is None:  # only a figure made here is resized
            width, height = figure.get_size_inches()
            figure.set_size_inches(width * 1.6, height)
            figure.set_layout_engine("constrained")
    elif labels:
        axes.legend(loc="best", fontsize="small")
    return axes


def draw_scene(ax: Axes, scene: CheckedScene, *, traces: bool) -> list[Any]:
    """Draw a checked scene (its traces too when ``traces``); returns the moving obstacles.

    An axis the caller inverted stays inverted.
    """
    with keep_directions(ax):
        return _draw_scene(ax, scene, traces=traces)


def _draw_scene(ax: Axes, scene: CheckedScene, *, traces: bool) -> list[Any]:
    # What the caller's axes showed before, axis by axis: limits they set, or their own
    # artists' data along that axis (an axhline has none along x: the default [0, 1]
    # there showed nothing, and widening to it squeezed a distant scene to a sliver).
    has_data = not ax.ignore_existing_data_limits
    shown_x = _shown(ax.get_xlim(), ax.get_autoscalex_on(), has_data, ax.dataLim.intervalx)
    shown_y = _shown(ax.get_ylim(), ax.get_autoscaley_on(), has_data, ax.dataLim.intervaly)
    grid = scene.grid
    if grid is None and scene.world is not None:
        grid = scene.world.grid
    if grid is not None:
        draw_grid(ax, grid)
    moving = draw_world(ax, scene.world) if scene.world is not None else []
    for label, points in scene.paths:
        ax.plot(points[:, 0], points[:, 1], "-", label=label or None, linewidth=1.5, zorder=3,
                marker="." if len(points) == 1 else None)  # fmt: skip
    if traces:
        for label, trace, true_xy, est_xy in scene.traces:
            draw_trace(ax, trace, true_xy, est_xy, label=label or None, color=None,
                       estimate=True)  # fmt: skip
    for k, (label, points) in enumerate(scene.points):
        ax.plot(points[:, 0], points[:, 1], linestyle="none", marker=_MARKERS[k % len(_MARKERS)],
                markersize=10, markeredgecolor="black", label=label or None, zorder=7)  # fmt: skip
    if scene.title:
        ax.set_title(scene.title)
    finish_axes(ax)
    limits = scene_limits(scene, grid)
    if limits is not None:
        # Widened to the earlier view: cropping to the scene would hide what was there.
        x0, y0, x1, y1 = limits
        if shown_x is not None:
            x0, x1 = min(x0, shown_x[0]), max(x1, shown_x[1])
        if shown_y is not None:
            y0, y1 = min(y0, shown_y[0]), max(y1, shown_y[1])
        limits = (x0, y0, x1, y1)
    if limits is not None:
        # Fixed limits: the axes box takes the map's proportions.
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlim(limits[0], limits[2])
        ax.set_ylim(limits[1], limits[3])
    return moving


def _shown(view: Any, auto: bool, has_data: bool, data: Any) -> tuple[float, float] | None:
    """The caller's view along one axis, ``(low, high)``, if it showed something there.

    Something: limits set by the caller (autoscaling off), or data of their
    artists along this axis.
    """
    if not auto or (has_data and bool(np.all(np.isfinite(data)))):
        low, high = (float(v) for v in view)
        return (min(low, high), max(low, high))
    return None


def _known_corners(grid: OccupancyGrid) -> FloatArray:
    """World corners of the smallest block of cells holding every known cell (else all)."""
    known = ~grid.unknown()
    rows = np.flatnonzero(known.any(axis=1))
    cols = np.flatnonzero(known.any(axis=0))
    if rows.size:
        r0, r1, c0, c1 = rows[0], rows[-1], cols[0], cols[-1]
    else:
        r0, r1, c0, c1 = 0, grid.shape[0] - 1, 0, grid.shape[1] - 1
    cells = [[r0 - 0.5, c0 - 0.5], [r0 - 0.5, c1 + 0.5], [r1 + 0.5, c0 - 0.5], [r1 + 0.5, c1 + 0.5]]
    return grid.cell_to_world(np.array(cells, dtype=np.float64))


def scene_limits(
    scene: CheckedScene, grid: OccupancyGrid | None
) -> tuple[float, float, float, float] | None:
    """``(xmin, ymin, xmax, ymax)`` of what a scene shows, with a margin.

    The margin is 5 % of the larger side, and at least 0.25 m (0.25 m around
    a single point) or the larger side itself when that is smaller, but never
    less than 1e-12 of the largest coordinate's magnitude nor 1e-12 m (a
    narrower window would not be drawn at that scale).

    The map counts by its known part only (a map_server map is mostly unknown
    space around the building); walls, circles, moving obstacles' routes,
    paths, traces and points count whole.
    """
    parts: list[FloatArray] = []
    if grid is not None:
        parts.append(_known_corners(grid))
    world = scene.world
    if world is not None:
        parts.append(np.asarray(world.segments).reshape(-1, 2))
        c = np.asarray(world.circles)
        parts += [c[:, :2] - c[:, 2:], c[:, :2] + c[:, 2:]]
        parts += [np.asarray(ob.path_xy) for ob in world.moving]
    parts += [points for _, points in scene.paths]
    parts += [points for _, points in scene.points]
    for _, _, true_xy, est_xy in scene.traces:
        parts += [true_xy, est_xy[np.isfinite(est_xy).all(axis=1)]]
    if not parts:
        return None
    xy = np.concatenate([np.reshape(part, (-1, 2)) for part in parts])
    if not xy.size:
        return None
    lo = xy.min(axis=0)
    hi = xy.max(axis=0)
    span = float(np.max(hi - lo))
    # At least 0.25 m around a point or a small scene, but not more than the scene's
    # own size: a map of micrometre cells would otherwise be a speck in the picture.
    # Nor less than 1e-12 of the coordinates (and 1e-12 m): matplotlib widens a
    # window narrower than 1e-15 of its coordinates to ±5 % of them (a scene
    # 1e-10 m wide at x = 1e6 m drawn 100 km wide), and one at the origin
    # narrower than about 1e-287 m to ±0.05 m.
    floor = _MIN_MARGIN * max(1.0, float(np.max(np.abs(np.concatenate((lo, hi))))))
    margin = max(0.05 * span, min(0.25, max(span, floor))) if span > 0.0 else 0.25
    return (float(lo[0]) - margin, float(lo[1]) - margin,
            float(hi[0]) + margin, float(hi[1]) + margin)  # fmt: skip


def _polygon_path(poly: Any) -> MplPath:
    """A shapely polygon's outline with its holes, as a path whose holes are not filled.

    matplotlib fills by the nonzero winding rule: the holes must turn the other
    way round from the exterior, which shapely's ``orient`` guarantees.
    """
    from matplotlib.path import Path as MplPath
    from shapely.geometry.polygon import orient

    oriented = orient(poly, sign=1.0)  # exterior counter-clockwise, holes clockwise
    rings = (oriented.exterior, *oriented.interiors)
    return MplPath.make_compound_path(
        *(MplPath(np.asarray(ring.coords, dtype=np.float64), closed=True) for ring in rings)
    )


def draw_world(ax: Axes, world: World, *, t: float = 0.0) -> list[Any]:
    """Draw a world's static edges and circles; returns the moving obstacles' patches.

    Solid polygons (their holes left clear) and solid circles are filled; walls
    (lines, rings, a circular room) are outlines only.

    Moving obstacles are drawn where they are at ``t`` (dashed outlines), their
    routes dotted; the returned patches are what an animation moves.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Circle as CirclePatch
    from matplotlib.patches import PathPatch
    from matplotlib.patches import Polygon as PolygonPatch

    segs = as_coords(world.segments, "world.segments", ncols=4)
    if len(segs):
        ax.add_collection(LineCollection(list(segs.reshape(-1, 2, 2)), colors=_WALL_COLOUR,
                                         linewidths=1.5, zorder=2))  # fmt: skip
        ax.update_datalim(segs.reshape(-1, 2))
    solids = world.solids
    if solids is not None:
        for poly in getattr(solids, "geoms", [solids]):
            if poly.geom_type == "Polygon" and not poly.is_empty:
                ax.add_patch(PathPatch(_polygon_path(poly), fill=True, facecolor=_WALL_COLOUR,
                                       alpha=0.25, linewidth=0, zorder=1))  # fmt: skip
    solid_rows = {tuple(row) for row in np.asarray(world.solid_circles).tolist()}
    circles = as_coords(world.circles, "world.circles", ncols=3)
    for cx, cy, r in circles:
        filled = (float(cx), float(cy), float(r)) in solid_rows
        ax.add_patch(CirclePatch((cx, cy), r, fill=filled, facecolor=_WALL_COLOUR,
                                 edgecolor=_WALL_COLOUR, linewidth=1.5,
                                 alpha=0.6 if filled else 1.0, zorder=2))  # fmt: skip
        ax.update_datalim([[cx - r, cy - r], [cx + r, cy + r]])
    patches: list[Any] = []
    for k, ob in enumerate(world.moving):
        route = as_coords(ob.path_xy, f"world.moving[{k}].path_xy")
        if len(route) > 1:
            ax.plot(route[:, 0], route[:, 1], ":", color=_MOVING_COLOUR, linewidth=1.0, zorder=2)
        outline = np.asarray(ob.geometry_at(t).exterior.coords, dtype=np.float64)
        patch = PolygonPatch(
            outline,
            closed=True,
            fill=True,
            facecolor=_MOVING_COLOUR,
            alpha=0.35,
            edgecolor=_MOVING_COLOUR,
            linestyle="--",
            zorder=3,
        )
        ax.add_patch(patch)
        ax.update_datalim(outline)
        patches.append(patch)
    ax.autoscale_view()
    return patches
