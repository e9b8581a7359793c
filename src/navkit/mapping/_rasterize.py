"""Rasterising shapely obstacles into occupancy grids."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import BoolArray
from navkit._shared.validation import as_float_array
from navkit.geometry import Pose2D
from navkit.mapping._grid import OccupancyGrid
from navkit.mapping._limits import COORDINATE_LIMIT, grid_shape, resolution_float

if TYPE_CHECKING:
    import shapely

__all__ = ["rasterize_polygons"]

# Blocks of at most this many cells are tested cell by cell (one vectorised
# shapely call); larger blocks are first tested whole and split in two.
_LEAF_CELLS = 4096


def _block_box(
    xmin: float, ymin: float, res: float, r0: int, r1: int, c0: int, c1: int
) -> shapely.Geometry:
    """The union of the closed squares of cells [r0, r1) × [c0, c1), computed with
    the very same float operations as each cell's square (so it encloses them)."""
    import shapely

    return shapely.box(
        xmin + c0 * res,
        ymin + r0 * res,
        (xmin + (c1 - 1) * res) + res,
        (ymin + (r1 - 1) * res) + res,
    )


def _fill(
    geom: shapely.Geometry,
    occ: BoolArray,
    xmin: float,
    ymin: float,
    res: float,
    r0: int,
    r1: int,
    c0: int,
    c1: int,
) -> None:
    """Mark the cells of the block [r0, r1) × [c0, c1) whose closed square meets ``geom``.

    A block that ``geom`` misses holds no such cell; a block it covers holds
    only such cells: each is decided with one test, so the work grows with the
    obstacle's outline, not its area, and memory stays bounded by the leaf size.
    """
    import shapely

    block = _block_box(xmin, ymin, res, r0, r1, c0, c1)
    if not shapely.intersects(geom, block):
        return
    if (r1 - r0) * (c1 - c0) <= _LEAF_CELLS:
        rr, cc = np.mgrid[r0:r1, c0:c1]
        x0 = xmin + cc.ravel() * res
        y0 = ymin + rr.ravel() * res
        boxes = shapely.box(x0, y0, x0 + res, y0 + res)
        occ[r0:r1, c0:c1] |= shapely.intersects(geom, boxes).reshape(rr.shape)
        return
    if shapely.covers(geom, block):
        occ[r0:r1, c0:c1] = True
        return
    if r1 - r0 >= c1 - c0:
        mid = (r0 + r1) // 2
        _fill(geom, occ, xmin, ymin, res, r0, mid, c0, c1)
        _fill(geom, occ, xmin, ymin, res, mid, r1, c0, c1)
    else:
        mid = (c0 + c1) // 2
        _fill(geom, occ, xmin, ymin, res, r0, r1, c0, mid)
        _fill(geom, occ, xmin, ymin, res, r0, r1, mid, c1)


def _window(low: float, high: float, origin: float, res: float, size: int) -> tuple[int, int]:
    """Cells ``[i0, i1)`` whose closed extent along one axis meets ``[low, high]``.

    Computed on clipped floats, so that geometries at ±1e300 never overflow.
    """
    lo = min(max((low - origin) / res, -2.0), size + 2.0)
    hi = min(max((high - origin) / res, -2.0), size + 2.0)
    return max(0, math.ceil(lo) - 1), min(size, math.floor(hi) + 1)


def _geometry_list(geometries: Any) -> list[Any]:
    import shapely

    if isinstance(geometries, shapely.Geometry):
        return [geometries]
    if isinstance(geometries, (str, bytes, Mapping)) or not isinstance(geometries, Iterable):
        raise TypeError(
            "geometries must be a shapely geometry or an iterable of them, got "
            f"{type(geometries).__name__}"
        )
    return list(geometries)


def rasterize_polygons(geometries: Any, *, bounds: ArrayLike, resolution: float) -> OccupancyGrid:
    """Occupancy grid of shapely obstacles: a cell is occupied when it intersects one.

    The test is conservative: a cell whose closed square touches an obstacle
    (even along an edge or at a corner) is occupied; every other cell is free.
    Large obstacles are tested block by block, so the time grows with their
    outlines rather than their areas.

    Parameters
    ----------
    geometries : shapely geometry or iterable of them
        Obstacles in world coordinates (m), with finite coordinates. They are
        not modified (shapely's preparation is undone afterwards).
    bounds : array_like (xmin, ymin, xmax, ymax)
        Area to cover, m, within ±1e9 m; the grid is axis-aligned with its
        origin at ``(xmin, ymin)`` and is rounded up to whole cells, at most
        ``OccupancyGrid.MAX_CELLS`` (``2**28``) of them.
    resolution : float
        Cell size, m, in [1e-6, 1e6].

    Returns
    -------
    OccupancyGrid
        Axis-aligned grid with origin ``(xmin, ymin, 0)``, every cell occupied
        (touching an obstacle) or free.

    Raises
    ------
    TypeError
        An item of ``geometries`` is not a shapely geometry; ``bounds`` is not
        numeric.
    ValueError
        Bad ``bounds`` or ``resolution``, a geometry with non-finite
        coordinates, or a grid of more than ``2**28`` cells (the message says
        how many it would need; nothing is allocated).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> grid = rasterize_polygons(box(1.2, 0.2, 1.8, 0.8), bounds=(0, 0, 3, 1), resolution=0.5)
    >>> grid.occupied().astype(int)
    array([[0, 0, 1, 1, 0, 0],
           [0, 0, 1, 1, 0, 0]])
    """
    import shapely

    b = as_float_array(bounds, "bounds", shape=(4,))
    xmin, ymin, xmax, ymax = (float(v) for v in b)
    if not float(np.abs(b).max()) <= COORDINATE_LIMIT:
        raise ValueError(f"bounds must lie within ±1e9 m, got {b}")
    if xmax <= xmin or ymax <= ymin:
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax) with max > min, got {b}")
    res = resolution_float(resolution)
    geoms = _geometry_list(geometries)
    for i, g in enumerate(geoms):
        if not isinstance(g, shapely.Geometry):
            raise TypeError(f"geometries[{i}] must be a shapely geometry, got {type(g).__name__}")
        # Every x, y checked, not the bounds: GEOS leaves NaN out of a geometry's
        # bounds, so a LineString through (1, NaN) has finite ones.
        if not g.is_empty and not np.isfinite(shapely.get_coordinates(g)).all():
            raise ValueError(
                f"geometries[{i}] has non-finite coordinates (NaN or ±inf; bounds {g.bounds})"
            )
    rows, cols = grid_shape(
        width=xmax - xmin,
        height=ymax - ymin,
        resolution=res,
        what=f"bounds {tuple(float(v) for v in b)} at resolution {res:g} m",
    )
    occ = np.zeros((rows, cols), dtype=np.bool_)
    for g in geoms:
        if g.is_empty:
            continue
        gx0, gy0, gx1, gy1 = g.bounds
        # Candidate window: every cell whose closed square meets the bounding box.
        c0, c1 = _window(gx0, gx1, xmin, res, cols)
        r0, r1 = _window(gy0, gy1, ymin, res, rows)
        if c0 >= c1 or r0 >= r1:
            continue
        prepared_here = not shapely.is_prepared(g)
        shapely.prepare(g)
        try:
            _fill(g, occ, xmin, ymin, res, r0, r1, c0, c1)
        finally:
            if prepared_here:
                shapely.destroy_prepared(g)
    return OccupancyGrid.from_occupancy(occ, resolution=res, origin=Pose2D(xmin, ymin, 0.0))
