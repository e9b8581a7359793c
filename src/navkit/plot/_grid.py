"""Occupancy grids drawn in ROS map orientation on world axes."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from navkit._shared.types import FloatArray
from navkit.mapping import OccupancyGrid
from navkit.plot._figure import (
    COORD_LIMIT,
    axes_for,
    bounded_float,
    finish_axes,
    keep_directions,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["FREE_GREY", "OCCUPIED_GREY", "UNKNOWN_GREY", "draw_grid", "plot_grid"]

#: Grey levels (0 black, 1 white) of free, unknown and occupied cells.
FREE_GREY = 1.0
UNKNOWN_GREY = 0.75
OCCUPIED_GREY = 0.0
#: Grids larger than this along an axis are shrunk (darkest cell of each block
#: kept, so one-cell walls survive) before matplotlib resamples them.
MAX_IMAGE_CELLS = 2048
#: Grid cells shrunk at a time (8 MiB of grey levels).
_BAND_CELLS = 1 << 20


def plot_grid(grid: OccupancyGrid, *, ax: Axes | None = None, alpha: float = 1.0) -> Axes:
    """Draw an occupancy grid on world axes, in ROS map orientation.

    Row 0 of the grid (the lowest y) is drawn at the bottom; the image covers
    the map's world extent (``origin`` to ``origin + (width, height)``, rotated
    by the origin's yaw). Free cells are white, unknown cells grey, occupied
    cells black (the grid's own thresholds); axes are in metres with equal
    scales.

    Parameters
    ----------
    grid : OccupancyGrid
        The map.
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted.
    alpha : float, default 1.0
        Opacity of the image, in [0, 1].

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``grid`` is not an OccupancyGrid (the message says how to make one of
        a boolean or probability array, a ``LocalGrid`` or a ``ScanMapper``),
        ``ax`` not an Axes.
    ValueError
        ``alpha`` outside [0, 1]; the map lies beyond ±1e9 m.
    ImportError
        matplotlib is not installed (``pip install 'navkit[plot]'``).

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.mapping import OccupancyGrid
    >>> occupied = np.zeros((4, 6), dtype=bool)
    >>> occupied[3, :] = True                         # the top row: highest y
    >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5, origin=(1.0, 2.0, 0.0))
    >>> ax = plot_grid(grid)
    >>> [float(v) for v in ax.images[0].get_extent()]   # x from 1 m, y from 2 m
    [1.0, 4.0, 2.0, 4.0]
    """
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(_not_a_grid(grid))
    opacity = bounded_float(alpha, "alpha", 0.0, 1.0)
    axes = axes_for(ax)
    draw_grid(axes, grid, alpha=opacity)
    finish_axes(axes)
    return axes


def _not_a_grid(value: Any) -> str:
    """What plot_grid takes, and how to make one of what was passed."""
    name = type(value).__name__
    text = f"grid must be a navkit.mapping.OccupancyGrid, got {name}"
    try:
        inner = getattr(value, "map", None)
    except Exception:  # a failing property of the caller's object: no hint, the TypeError stands
        inner = None
    if isinstance(inner, OccupancyGrid):
        return f"{text}: pass its map (grid=mapper.map)"
    if name == "LocalGrid":
        return (
            f"{text}: convert it, in the robot frame, with OccupancyGrid.from_occupancy("
            "g.occupied, resolution=g.resolution, origin=(-g.half_width - g.resolution / 2, "
            "-g.half_width - g.resolution / 2, 0.0))"
        )
    if isinstance(value, (np.ndarray, list, tuple)):
        return (
            f"{text}: make one of an array with OccupancyGrid.from_occupancy(occupied, "
            "resolution=...) (booleans) or OccupancyGrid.from_probabilities(p, "
            "resolution=...) (occupancy probabilities in [0, 1]); row 0 is the lowest y"
        )
    return text


def grid_shades(grid: OccupancyGrid) -> FloatArray:
    """Grey level of every cell (free white, unknown grey, occupied black), shrunk if huge.

    A grid larger than :data:`MAX_IMAGE_CELLS` along an axis is shrunk by a
    factor ``k`` (the darkest cell of each ``k x k`` block) a band of rows at a
    time: the peak is the views' two masks (1 byte a cell each), the image and
    a band of :data:`_BAND_CELLS` cells, where the whole grid's grey levels and
    their padded copy took 16 bytes a cell (4 GiB at ``OccupancyGrid.MAX_CELLS``).
    """
    free = grid.free()
    occupied = grid.occupied()
    rows, cols = grid.shape
    k = math.ceil(max(rows, cols) / MAX_IMAGE_CELLS)
    if k <= 1:
        shades = np.full(grid.shape, UNKNOWN_GREY)
        shades[free] = FREE_GREY
        shades[occupied] = OCCUPIED_GREY
        return shades
    # The padding keeps the cell size; the image covers the padded extent, and
    # draw_grid clips it to the map's.
    out_rows, out_cols = -(-rows // k), -(-cols // k)
    shades = np.empty((out_rows, out_cols))
    band = max(1, _BAND_CELLS // (k * k * out_cols))  # image rows per band
    for first in range(0, out_rows, band):
        n = min(band, out_rows - first)
        r0, r1 = first * k, min((first + n) * k, rows)
        block = np.full((n * k, out_cols * k), FREE_GREY)
        cells = block[: r1 - r0, :cols]
        cells.fill(UNKNOWN_GREY)
        cells[free[r0:r1]] = FREE_GREY
        cells[occupied[r0:r1]] = OCCUPIED_GREY
        shades[first : first + n] = block.reshape(n, k, out_cols, k).min(axis=(1, 3))
    return shades


def draw_grid(ax: Axes, grid: OccupancyGrid, *, alpha: float = 1.0, zorder: float = 0.0) -> None:
    """Draw ``grid`` on ``ax`` (checked arguments) and extend the data limits to it."""
    with keep_directions(ax):
        _draw_grid(ax, grid, alpha=alpha, zorder=zorder)


def _draw_grid(ax: Axes, grid: OccupancyGrid, *, alpha: float, zorder: float) -> None:
    from matplotlib.path import Path as MplPath
    from matplotlib.transforms import Affine2D

    o = grid.origin
    corners = o.transform_points([[0.0, 0.0], [grid.width, 0.0], [0.0, grid.height],
                                  [grid.width, grid.height]])  # fmt: skip
    if not np.all(np.abs(corners) <= COORD_LIMIT):
        raise ValueError(f"grid must lie within ±{COORD_LIMIT:g} m to be drawn")
    shades = grid_shades(grid)
    k = max(math.ceil(max(grid.shape) / MAX_IMAGE_CELLS), 1)
    width = shades.shape[1] * grid.resolution * k
    height = shades.shape[0] * grid.resolution * k
    image_kw: dict[str, Any] = {
        "cmap": "gray", "vmin": 0.0, "vmax": 1.0, "origin": "lower", "alpha": alpha,
        "interpolation": "antialiased", "zorder": zorder,
    }  # fmt: skip
    # imshow extends the data limits by its extent, which is not the map's when
    # the map is rotated (the extent is in the map frame) or padded to whole
    # blocks (grid_shades): undo that, the corners below are the real limits.
    limits = ax.dataLim.frozen()
    ignore = ax.ignore_existing_data_limits
    if o.theta == 0.0:
        image = ax.imshow(shades, extent=(o.x, o.x + width, o.y, o.y + height), **image_kw)
        map_to_data = Affine2D().translate(o.x, o.y)
    else:
        image = ax.imshow(shades, extent=(0.0, width, 0.0, height), **image_kw)
        map_to_data = Affine2D().rotate(o.theta).translate(o.x, o.y)
        image.set_transform(map_to_data + ax.transData)
    if shades.shape[0] * k != grid.shape[0] or shades.shape[1] * k != grid.shape[1]:
        # The padded blocks reach up to k - 1 cells past the map's edges: show the
        # map's own rectangle only (a Path, not a Rectangle, which matplotlib
        # would turn into the axis-aligned clip box, wrong for a rotated map).
        outline = MplPath([(0.0, 0.0), (grid.width, 0.0), (grid.width, grid.height),
                           (0.0, grid.height), (0.0, 0.0)], closed=True)  # fmt: skip
        image.set_clip_path(outline, map_to_data + ax.transData)
    ax.dataLim.set(limits)
    ax.ignore_existing_data_limits = ignore
    # No autoscale margins around the map itself, as around any image, in world axes.
    image.sticky_edges.x[:] = [float(corners[:, 0].min()), float(corners[:, 0].max())]
    image.sticky_edges.y[:] = [float(corners[:, 1].min()), float(corners[:, 1].max())]
    ax.update_datalim(corners)
    ax.autoscale_view()
