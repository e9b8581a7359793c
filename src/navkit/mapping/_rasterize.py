"""Rasterising shapely obstacles into occupancy grids."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import shapely
from numpy.typing import ArrayLike

from navkit._shared.validation import as_float_array, positive_float
from navkit.geometry import Pose2D
from navkit.mapping._grid import OccupancyGrid

__all__ = ["rasterize_polygons"]


def rasterize_polygons(geometries: Any, *, bounds: ArrayLike, resolution: float) -> OccupancyGrid:
    """Occupancy grid of shapely obstacles: a cell is occupied when it intersects one.

    The test is conservative: a cell whose closed square touches an obstacle
    (even along an edge or at a corner) is occupied; every other cell is free.

    Parameters
    ----------
    geometries : shapely geometry or iterable of them
        Obstacles in world coordinates (m).
    bounds : array_like (xmin, ymin, xmax, ymax)
        Area to cover, m; the grid is axis-aligned with its origin at
        ``(xmin, ymin)`` and is rounded up to whole cells.
    resolution : float
        Cell size, m.

    Examples
    --------
    >>> from shapely.geometry import box
    >>> grid = rasterize_polygons(box(1.2, 0.2, 1.8, 0.8), bounds=(0, 0, 3, 1), resolution=0.5)
    >>> grid.occupied().astype(int)
    array([[0, 0, 1, 1, 0, 0],
           [0, 0, 1, 1, 0, 0]])
    """
    b = as_float_array(bounds, "bounds", shape=(4,))
    xmin, ymin, xmax, ymax = (float(v) for v in b)
    if xmax <= xmin or ymax <= ymin:
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax) with max > min, got {b}")
    res = positive_float(resolution, "resolution")
    geoms = [geometries] if isinstance(geometries, shapely.Geometry) else list(geometries)
    for i, g in enumerate(geoms):
        if not isinstance(g, shapely.Geometry):
            raise TypeError(f"geometries[{i}] must be a shapely geometry, got {type(g).__name__}")
    origin = Pose2D(xmin, ymin, 0.0)
    rows, cols = OccupancyGrid.empty(
        width=xmax - xmin, height=ymax - ymin, resolution=res, origin=origin
    ).shape
    occ = np.zeros((rows, cols), dtype=np.bool_)
    for g in geoms:
        if g.is_empty:
            continue
        gx0, gy0, gx1, gy1 = g.bounds
        # Candidate window: every cell whose closed square meets the bounding box.
        c0 = max(0, math.ceil((gx0 - xmin) / res) - 1)
        c1 = min(cols, math.floor((gx1 - xmin) / res) + 1)
        r0 = max(0, math.ceil((gy0 - ymin) / res) - 1)
        r1 = min(rows, math.floor((gy1 - ymin) / res) + 1)
        if c0 >= c1 or r0 >= r1:
            continue
        rr, cc = np.mgrid[r0:r1, c0:c1]
        x0 = xmin + cc.ravel() * res
        y0 = ymin + rr.ravel() * res
        boxes = shapely.box(x0, y0, x0 + res, y0 + res)
        shapely.prepare(g)
        hits = shapely.intersects(g, boxes).reshape(rr.shape)
        occ[r0:r1, c0:c1] |= hits
    return OccupancyGrid.from_occupancy(occ, resolution=res, origin=origin)
