"""Rasterising shapely obstacles into occupancy grids."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import BoolArray, FloatArray, IntArray
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


_MAGNITUDE = np.int64(0x7FFF_FFFF_FFFF_FFFF)

# The rounding of bounds written as decimals, relative to their size (half an ulp
# is at most 2**-53), with a factor 4 to spare (sample_field's _FLOAT_SLACK).
_BOUND_SLACK = 2.0**-51


def _float_key(x: FloatArray) -> IntArray:
    """int64 keys in the order of the floats ``x`` (adjacent floats, adjacent keys)."""
    bits = x.view(np.int64)
    out: IntArray = bits ^ ((bits >> 63) & _MAGNITUDE)
    return out


def _key_float(key: IntArray) -> FloatArray:
    """The floats of :func:`_float_key`'s keys (the map is its own inverse)."""
    out: FloatArray = (key ^ ((key >> 63) & _MAGNITUDE)).view(np.float64)
    return out


def _edges(origin: float, res: float, n: int) -> tuple[FloatArray, FloatArray]:
    """Lower and upper world coordinates of the ``n + 1`` cell edges along one axis.

    Cell ``k``'s closed extent is ``[low[k], high[k + 1]]``: it holds both
    ``origin + k * res`` .. ``origin + (k + 1) * res`` (the cell in exact
    arithmetic, as rounded) and every float that
    :meth:`OccupancyGrid.world_to_cell` puts in cell ``k``, so that every point
    of an obstacle lies in an occupied cell. Edge ``k`` of the latter is the
    smallest float ``x`` whose grid coordinate ``(x - origin) * (1 / res)``
    (its arithmetic on an axis-aligned grid) is at least ``k``; the rounded
    ``origin + k * res`` can lie beyond it: 0.3 is in cell 3 of a 0.1 m grid
    (0.3 * 10 = 3), whose extent then started at 0.30000000000000004.
    """
    inv_res = 1.0 / res
    k = np.arange(n + 1, dtype=np.float64)
    guess = origin + k * res
    # A bracket [lo, hi] with f(lo) < k <= f(hi): rounding moves the edge by a
    # few ulps of the coordinates' size (widened until it holds, as a safeguard).
    width = 16.0 * np.spacing(np.maximum(abs(origin), np.abs(guess)))
    lo = guess - width
    hi = guess + width
    while (wide := (lo - origin) * inv_res >= k).any():
        width[wide] *= 2.0
        lo[wide] = guess[wide] - width[wide]
    while (wide := (hi - origin) * inv_res < k).any():
        width[wide] *= 2.0
        hi[wide] = guess[wide] + width[wide]
    # Bisection on the floats themselves (their ordered bit patterns): at most
    # 64 halvings, however many floats the bracket holds (near 0, very many).
    lo_key = _float_key(lo)
    hi_key = _float_key(hi)
    while (unsettled := hi_key - lo_key > 1).any():
        mid = (lo_key >> 1) + (hi_key >> 1) + (lo_key & hi_key & 1)  # no overflow
        up = (_key_float(mid) - origin) * inv_res >= k
        hi_key = np.where(unsettled & up, mid, hi_key)
        lo_key = np.where(unsettled & ~up, mid, lo_key)
    exact = _key_float(hi_key)
    return np.minimum(exact, guess), np.maximum(exact, guess)


def _fill(
    geom: shapely.Geometry,
    occ: BoolArray,
    xs: tuple[FloatArray, FloatArray],
    ys: tuple[FloatArray, FloatArray],
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

    # The block's square encloses its cells' squares (the edges are monotone).
    block = shapely.box(xs[0][c0], ys[0][r0], xs[1][c1], ys[1][r1])
    if not shapely.intersects(geom, block):
        return
    if (r1 - r0) * (c1 - c0) <= _LEAF_CELLS:
        rr, cc = np.mgrid[r0:r1, c0:c1]
        r = rr.ravel()
        c = cc.ravel()
        boxes = shapely.box(xs[0][c], ys[0][r], xs[1][c + 1], ys[1][r + 1])
        occ[r0:r1, c0:c1] |= shapely.intersects(geom, boxes).reshape(rr.shape)
        return
    if shapely.covers(geom, block):
        occ[r0:r1, c0:c1] = True
        return
    if r1 - r0 >= c1 - c0:
        mid = (r0 + r1) // 2
        _fill(geom, occ, xs, ys, r0, mid, c0, c1)
        _fill(geom, occ, xs, ys, mid, r1, c0, c1)
    else:
        mid = (c0 + c1) // 2
        _fill(geom, occ, xs, ys, r0, r1, c0, mid)
        _fill(geom, occ, xs, ys, r0, r1, mid, c1)


def _extent(low: float, high: float, res: float, what: str) -> float:
    """The extent of ``[low, high]`` to count cells in: ``high - low``, or less by rounding.

    Bounds written as decimals are each rounded by up to half a float spacing,
    2**-53 of their size: at a UTM northing of 5.1e6 m the difference of two
    written to the millimetre can exceed a whole number of cells by 1.9e-8 cells
    at 0.05 m, beyond the 1e-9 cells :func:`grid_shape` forgives, and gained a
    row past the area asked for (41 % of such bounds; review 54, FARWORLD).
    An extent within ``2**-51 (|low| + |high|)`` of fewer cells is counted as
    that many, as ``sample_field`` counts its window: the grid may then end that
    little short of ``high`` (4.6e-9 m at a northing of 5.4e6 m), within the
    rounding of the bounds themselves.
    """
    full = high - low
    less = full - _BOUND_SLACK * (abs(low) + abs(high))
    if not less > 0.0:
        return full
    try:
        n_full = grid_shape(width=full, height=res, resolution=res, what=what)[1]
        n_less = grid_shape(width=less, height=res, resolution=res, what=what)[1]
    except ValueError:  # too many cells in one row: the caller's check says how many
        return full
    return less if n_less < n_full else full


def _window(low: float, high: float, origin: float, res: float, size: int) -> tuple[int, int]:
    """Cells ``[i0, i1)`` whose closed extent along one axis meets ``[low, high]``.

    Computed on clipped floats, so that geometries at ±1e300 never overflow;
    one cell wider on each side than exact arithmetic needs (cells reach a
    little beyond their edges as rounded, see :func:`_edges`), as every cell of
    the window is tested anyway.
    """
    lo = min(max((low - origin) / res, -3.0), size + 3.0)
    hi = min(max((high - origin) / res, -3.0), size + 3.0)
    return max(0, math.ceil(lo) - 2), min(size, math.floor(hi) + 2)


def _own_parts(geom: shapely.Geometry) -> list[shapely.Geometry]:
    """Copies of ``geom`` to prepare and test: itself, or its parts where that is invalid.

    Copies, because preparing the caller's geometry (and undoing it) raced in
    threads rasterising one shared geometry: one thread freed the prepared
    index another was using (a segmentation fault, as GEOS's prepared
    geometries are not thread-safe). ``force_2d`` copies in one GEOS call
    (100 µs for 16,000 vertices); the heights it drops are ignored by GEOS's
    predicates anyway.

    Parts, because GEOS's predicates are undefined on invalid geometries and
    its prepared ones read a multi-part geometry's area by the parity of its
    boundaries: a MultiPolygon of two overlapping squares, invalid only because
    its parts overlap, left their overlap free, and a part nested in another
    was a hole. The cells touching its parts are the cells touching their
    union. A single polygon whose ring crosses itself (a bow-tie) is kept:
    read by the same parity, its cells are those of ``shapely.make_valid``'s
    repair (240 random ones checked).
    """
    import shapely

    # The type first: a single part is kept whatever its validity, and GEOS's
    # validity check of a degenerate ring grows faster than quadratically (a
    # zero-area zigzag of 200,000 vertices took 2.5 s of 2.9).
    if not (
        geom.geom_type.startswith("Multi") or geom.geom_type == "GeometryCollection"
    ) or shapely.is_valid(geom):
        return [shapely.force_2d(geom)]
    parts: list[shapely.Geometry] = []
    for part in shapely.get_parts(geom):
        parts.extend(_own_parts(part))
    return parts


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
    Each square also holds every float that :meth:`OccupancyGrid.world_to_cell`
    rounds into its cell, so every point of an obstacle inside the grid lies
    in an occupied cell (an edge at x = 0.3 m on a 0.1 m grid occupies the
    cells on both sides, 2 and 3, as an edge at 0.2 m does).
    Large obstacles are tested block by block, so the time grows with their
    outlines rather than their areas.

    Parameters
    ----------
    geometries : shapely geometry or iterable of them
        Obstacles in world coordinates (m), with finite coordinates. A
        multi-part geometry is the union of its parts, also where shapely
        calls it invalid (a ``MultiPolygon`` of overlapping walls). They are
        neither modified nor prepared (copies are), so threads may share them.
    bounds : array_like (xmin, ymin, xmax, ymax)
        Area to cover, m, within ±1e9 m; the grid is axis-aligned with its
        origin at ``(xmin, ymin)`` and is rounded up to whole cells, at most
        ``OccupancyGrid.MAX_CELLS`` (``2**28``) of them. An extent within
        ``2**-51 (|min| + |max|)`` of whole cells (the rounding of bounds
        written as decimals: 4.6e-9 m at a UTM northing of 5.4e6 m) is that
        many cells, as in :func:`~navkit.planning.sample_field`: bounds given
        to the millimetre at UTM coordinates, ``n`` cells apart, give ``n``.
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
    xmin, ymin, xmax, ymax = given = tuple(float(v) for v in b)
    # The values as given (an array's repr rounds them: 1e9 + 1e-7 would print as 1e9).
    if not float(np.abs(b).max()) <= COORDINATE_LIMIT:
        raise ValueError(f"bounds must lie within ±1e9 m, got {given}")
    if xmax <= xmin or ymax <= ymin:
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax) with max > min, got {given}")
    res = resolution_float(resolution)
    geoms = _geometry_list(geometries)
    for i, g in enumerate(geoms):
        if not isinstance(g, shapely.Geometry):
            raise TypeError(f"geometries[{i}] must be a shapely geometry, got {type(g).__name__}")
        # Every x, y checked, not the bounds: GEOS leaves NaN out of a geometry's
        # bounds, so a LineString through (1, NaN) has finite ones.
        if not g.is_empty and not np.isfinite(shapely.get_coordinates(g)).all():
            # shapely 2.0 warns (numpy's "invalid value encountered in bounds") for a
            # geometry with NaN coordinates, on top of the error raised here.
            with np.errstate(invalid="ignore"):
                shown = g.bounds
            raise ValueError(
                f"geometries[{i}] has non-finite coordinates (NaN or ±inf; bounds {shown})"
            )
    parts = [part for g in geoms if not g.is_empty for part in _own_parts(g)]
    what = f"bounds {given} at resolution {res:g} m"
    rows, cols = grid_shape(
        width=_extent(xmin, xmax, res, what),
        height=_extent(ymin, ymax, res, what),
        resolution=res,
        what=what,
    )
    occ = np.zeros((rows, cols), dtype=np.bool_)
    # The bisection near a coordinate 0 visits subnormal floats, whose products
    # underflow as they should: not an error under a caller's np.seterr(under=...).
    with np.errstate(under="ignore"):
        xs = _edges(xmin, res, cols)
        ys = _edges(ymin, res, rows)
    for g in parts:
        if g.is_empty:
            continue
        gx0, gy0, gx1, gy1 = g.bounds
        # Candidate window: every cell whose closed square meets the bounding box.
        c0, c1 = _window(gx0, gx1, xmin, res, cols)
        r0, r1 = _window(gy0, gy1, ymin, res, rows)
        if c0 >= c1 or r0 >= r1:
            continue
        shapely.prepare(g)  # a copy of the caller's (see _own_parts)
        try:
            _fill(g, occ, xs, ys, r0, r1, c0, c1)
        finally:
            shapely.destroy_prepared(g)  # its index freed now, not at the end
    return OccupancyGrid.from_occupancy(occ, resolution=res, origin=Pose2D(xmin, ymin, 0.0))
