"""A potential field sampled on a regular grid of cell centres (e.g. for plots)."""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from decimal import ROUND_CEILING, ROUND_HALF_EVEN, Decimal
from typing import TYPE_CHECKING, Literal, overload

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.float32 import intended_resolution, narrow_float_dtype
from navkit._shared.frozen import frozen_setattr, reduce_record
from navkit._shared.grid_coords import CELL_LIMIT, as_pairs, inside, one_or_many
from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit._shared.validation import as_bool, as_float_array, positive_float
from navkit.planning.reactive._limits import (
    COORDINATE_LIMIT,
    MAX_SAMPLES,
    RESOLUTION_MAX,
    RESOLUTION_MIN,
    check_coordinates,
)
from navkit.planning.reactive._potential_field import (
    PotentialField,
    _frozen,
    _restore,
)

__all__ = ["SampledField", "sample_field"]

# Continuous cell coordinates beyond this are refused (their world points and
# int64 cells stay exact and finite).
_CELL_LIMIT = float(2**53)
# Bytes sample_field holds per cell: the potential and force it returns (the
# points and the fields' temporaries are a block's, _BLOCK_CELLS at a time).
_BYTES_PER_SAMPLE = 24
# Cells evaluated at a time: 256 KiB of points, whose temporaries (a Khatib
# field's grow with points × obstacles) stay in cache; the per-block calls cost
# under 1 % of the fields' work (a 500 × 1000 window: 0.29 → 0.21 s with 40
# Khatib obstacles, 0.14 → 0.06 s for a blended + conic attraction).
_BLOCK_CELLS = 2**14
# Relative rounding allowed in a centre axis' spacing: 8 float64 epsilons (the
# rounding of lo + (k + ½)·resolution is at most about 3).
_AXIS_ULPS = 8.0 * float(np.finfo(np.float64).eps)
# The coarsest rounding (an ulp of the largest coordinate), as a share of a cell, of
# axes given as float32 (or float16) that are let through as evenly spaced.
_NARROW_CELL_SHARE = 0.01
# Relative error of a float against the decimal it was written as (half an ulp is
# at most 2**-53), with a factor 4 to spare.
_FLOAT_SLACK = Decimal(2.0**-51)


def _resolution(value: object) -> float:
    res = positive_float(value, "resolution")
    if not RESOLUTION_MIN <= res <= RESOLUTION_MAX:
        raise ValueError(
            f"resolution must lie in [{RESOLUTION_MIN:g}, {RESOLUTION_MAX:g}] m, got {res}"
        )
    return res


def _check_potential(potential: FloatArray) -> None:
    if np.isnan(potential).any() or (potential == -np.inf).any():
        raise ValueError("potential must not contain NaN or -inf (+inf is allowed)")


def _axis(value: ArrayLike, name: str, resolution: float) -> FloatArray:
    """A strictly increasing, evenly spaced 1-D axis of cell centres (read-only copy)."""
    arr = as_float_array(value, name, ndim=1, finite=False)
    if arr.shape[0] == 0:
        raise ValueError(f"{name} must hold at least one cell centre")
    check_coordinates(arr, name)
    # Centres computed as lo + (k + ½)·resolution are spaced by it up to the rounding
    # of each centre, a few ulps of the largest coordinate; otherwise the spacing must
    # match to 1e-9 of a cell at any offset (UTM coordinates reach 1e7 m), or
    # world_to_cell and cell_to_world drift from the sampled points.
    top = float(np.max(np.abs(arr)))
    tol = 1e-9 * resolution + _AXIS_ULPS * (resolution + top)
    if not np.any(np.abs(np.diff(arr) - resolution) > tol):
        return _frozen(arr)
    note = ""
    narrow = narrow_float_dtype(value)
    if narrow is not None:
        # Centres given as float32 (a ROS map's) each carry their own rounding, up to
        # half an ulp of the largest (steps 0.72 ulp off for 0.01 m from 0): they are
        # accepted as lying within 4 ulps of their dtype (and of the spacing's, over
        # the axis) of centres evenly spaced from the first, where the dtype holds
        # coordinates to 1 % of a cell. Coarser (float32 at 1e4 m holds 1e-3 m, a
        # tenth of a 0.01 m cell), the cells would drift from the sampled points:
        # refused, saying why (review 53).
        eps = float(np.finfo(narrow).eps)
        if eps * (resolution + top) <= _NARROW_CELL_SHARE * resolution:
            even = arr[0] + np.arange(arr.shape[0], dtype=np.float64) * resolution
            if np.all(np.abs(arr - even) <= 4.0 * eps * (top + arr.shape[0] * resolution)):
                return _frozen(arr)
        else:
            note = (
                f" (its {narrow} values hold coordinates near {top:g} m "
                f"only to {eps * top:.3g} m, too coarse for a cell of {resolution:g} m: "
                "pass float64 coordinates)"
            )
    raise ValueError(f"{name} must be evenly spaced by resolution = {resolution}{note}")


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class SampledField:
    """A field sampled on a regular grid of cell centres.

    ``potential[row, col]`` and ``force[row, col]`` are the values at the world
    point ``(x[col], y[row])``; rows run along y, columns along x. The grid
    coordinates follow :class:`navkit.mapping.OccupancyGrid`'s: cell ``(row,
    col)`` covers ``[row - ½, row + ½) × [col - ½, col + ½)`` in continuous
    ``(row, col)`` coordinates, whose integers sit at the cell centres.
    Usually built by :func:`sample_field`; all arrays are stored as read-only copies.

    Parameters
    ----------
    x : array_like, shape (W,)
        Cell-centre x coordinates (m), increasing by ``resolution``, within
        ``±1e9``. Float32 (or float16) axes, as a ROS map's, are spaced by it
        up to their own rounding (within 4 ulps of their dtype of evenly
        spaced centres) where an ulp is at most 1 % of a cell; coarser ones
        are refused (the message says to pass float64).
    y : array_like, shape (H,)
        Cell-centre y coordinates (m), increasing by ``resolution``, within
        ``±1e9``.
    potential : array_like, shape (H, W)
        Potential at each cell centre: finite or ``+inf`` (a Khatib
        obstacle); no NaN, no ``-inf``.
    force : array_like, shape (H, W, 2)
        Force ``(Fx, Fy)`` at each cell centre, finite.
    resolution : float
        Cell side in metres, in ``[1e-6, 1e6]``.

    Raises
    ------
    ValueError
        Shapes that do not match, axes not evenly spaced or beyond ±1e9 m,
        NaN, infinite forces, ``resolution`` out of range.
    TypeError
        Non-numeric arrays or ``resolution``.

    Examples
    --------
    >>> sampled = SampledField([0.5, 1.5], [0.5], [[1.0, 2.0]], np.zeros((1, 2, 2)),
    ...                        resolution=1.0)
    >>> sampled.world_to_cell([1.9, 0.2])
    array([0, 1])
    >>> sampled.cell_to_world([0, 1])
    array([1.5, 0.5])
    """

    x: FloatArray
    y: FloatArray
    potential: FloatArray
    force: FloatArray
    _: KW_ONLY
    resolution: float

    __reduce__ = reduce_record
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            x: ArrayLike,
            y: ArrayLike,
            potential: ArrayLike,
            force: ArrayLike,
            *,
            resolution: float,
        ) -> None: ...

    def __post_init__(self) -> None:
        res = _resolution(self.resolution)
        xs = _axis(self.x, "x", res)
        ys = _axis(self.y, "y", res)
        shape = (ys.shape[0], xs.shape[0])
        potential = as_float_array(self.potential, "potential", shape=shape, finite=False)
        _check_potential(potential)
        force = as_float_array(self.force, "force", shape=(*shape, 2))
        object.__setattr__(self, "resolution", res)
        object.__setattr__(self, "x", xs)
        object.__setattr__(self, "y", ys)
        object.__setattr__(self, "potential", _frozen(potential))
        object.__setattr__(self, "force", _frozen(force))

    @classmethod
    def _owned(
        cls,
        x: FloatArray,
        y: FloatArray,
        potential: FloatArray,
        force: FloatArray,
        resolution: float,
    ) -> SampledField:
        """A record taking :func:`sample_field`'s own arrays, frozen in place, not copied.

        The constructor's copies would double the results' memory at its peak.
        The checks on the values stay: a user's field may return NaN.
        """
        _check_potential(potential)
        if not np.isfinite(force).all():
            # The constructor's message (as_float_array's).
            raise ValueError("force must contain only finite values")
        sampled = object.__new__(cls)
        for name, arr in (("x", x), ("y", y), ("potential", potential), ("force", force)):
            arr.setflags(write=False)
            object.__setattr__(sampled, name, arr)
        object.__setattr__(sampled, "resolution", resolution)
        return sampled

    @property
    def shape(self) -> tuple[int, int]:
        """``(H, W)``: rows along y, columns along x."""
        return int(self.y.shape[0]), int(self.x.shape[0])

    @overload
    def world_to_cell(
        self, points_xy: ArrayLike, *, continuous: Literal[False] = False
    ) -> IntArray: ...

    @overload
    def world_to_cell(self, points_xy: ArrayLike, *, continuous: Literal[True]) -> FloatArray: ...

    @overload
    def world_to_cell(self, points_xy: ArrayLike, *, continuous: bool) -> IntArray | FloatArray: ...

    def world_to_cell(
        self, points_xy: ArrayLike, *, continuous: bool = False
    ) -> IntArray | FloatArray:
        """Cells ``(row, col)`` of world points ``(x, y)``.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            World points in metres, ``|x|, |y| <= 1e9``.
        continuous : bool, default False
            Return float continuous coordinates (integers at cell centres)
            instead of the int64 cell containing each point.

        Returns
        -------
        ndarray, shape (N, 2) or (2,)
            ``(row, col)`` per point, the shape of the input. Cells are not
            clipped: points outside the window give indices outside
            ``[0, H) × [0, W)``. A point on a cell edge is in the upper cell
            (up to rounding), and the window's lower corner ``(xlim[0],
            ylim[0])`` of :func:`sample_field` is in cell ``(0, 0)`` exactly.

        Raises
        ------
        TypeError
            Non-numeric ``points_xy``; a ``continuous`` that is not a bool.
        ValueError
            ``points_xy`` of another shape or with NaN or inf.

        Examples
        --------
        >>> from navkit.planning import ConicAttraction
        >>> sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0),
        ...                        ylim=(0.0, 1.0), resolution=0.5)
        >>> sampled.world_to_cell([[0.3, 0.9], [-1.0, 0.0]])
        array([[1, 2],
               [0, 0]])
        >>> sampled.world_to_cell([0.3, 0.9], continuous=True)
        array([1.3, 2.1])
        """
        pts, single = as_pairs(points_xy, "points_xy")
        check_coordinates(pts, "points_xy")
        res = self.resolution
        out: IntArray | FloatArray
        if as_bool(continuous, "continuous"):
            out = np.empty_like(pts)
            out[:, 0] = (pts[:, 1] - self.y[0]) / res
            out[:, 1] = (pts[:, 0] - self.x[0]) / res
            return one_or_many(out, single)
        # Cells counted from the window's lower edge, half a cell below the first
        # centre, which sample_field placed at x[0] = xlim[0] + res / 2 (rounded).
        # Adding the half cell to the point, as there, brings the window's own
        # corner exactly onto x[0], in cell 0; rounding (p - x[0]) / res half up
        # put it at -0.5 ± a rounding error, most often in cell -1. Boundaries
        # elsewhere are those of round half up, up to rounding.
        half = 0.5 * res
        edge = np.empty_like(pts)
        edge[:, 0] = (pts[:, 1] + half - self.y[0]) / res
        edge[:, 1] = (pts[:, 0] + half - self.x[0]) / res
        out = np.clip(np.floor(edge), -CELL_LIMIT, CELL_LIMIT).astype(np.int64)
        return one_or_many(out, single)

    def cell_to_world(self, cells: ArrayLike) -> FloatArray:
        """World points ``(x, y)`` of cells ``(row, col)``; continuous cells are accepted.

        Parameters
        ----------
        cells : array_like, shape (N, 2) or (2,)
            Integer cells (their centres are returned) or float continuous
            coordinates (integers at cell centres), within ``±2**53``.

        Returns
        -------
        ndarray, shape (N, 2) or (2,)
            ``(x, y)`` in metres, the shape of the input.

        Raises
        ------
        TypeError
            Non-numeric ``cells``.
        ValueError
            ``cells`` of another shape, with NaN or inf, or beyond ``±2**53``.

        Examples
        --------
        >>> from navkit.planning import ConicAttraction
        >>> sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0),
        ...                        ylim=(0.0, 1.0), resolution=0.5)
        >>> sampled.cell_to_world([1, 2])
        array([0.25, 0.75])
        >>> sampled.cell_to_world([[0.0, -0.5]])     # a cell corner: the window's corner
        array([[-1.  ,  0.25]])
        """
        arr, single = as_pairs(cells, "cells")
        if arr.size and not float(np.abs(arr).max()) <= _CELL_LIMIT:
            raise ValueError(f"cells must lie within ±2**53, got {float(np.abs(arr).max()):g}")
        out = np.empty_like(arr)
        out[:, 0] = self.x[0] + arr[:, 1] * self.resolution
        out[:, 1] = self.y[0] + arr[:, 0] * self.resolution
        return one_or_many(out, single)

    def contains(self, points_xy: ArrayLike) -> BoolArray:
        """Whether each world point ``(x, y)`` falls in a cell of the window.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            World points, m.

        Returns
        -------
        ndarray of bool, shape (N,), or 0-d for one point given as shape (2,)
            True where the point's cell (:meth:`world_to_cell`) is inside the
            sampled window.

        Raises
        ------
        TypeError, ValueError
            ``points_xy`` not finite real pairs.

        Examples
        --------
        >>> from navkit.planning import ConicAttraction
        >>> sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0),
        ...                        ylim=(0.0, 1.0), resolution=0.5)
        >>> sampled.contains([[0.3, 0.9], [0.3, 1.1]])
        array([ True, False])
        >>> bool(sampled.contains([-1.0, 0.0]))
        True
        """
        pts, single = as_pairs(points_xy, "points_xy")
        return one_or_many(inside(self.world_to_cell(pts), self.shape), single)


def _limits(value: ArrayLike, name: str) -> tuple[float, float]:
    arr = as_float_array(value, name, shape=(2,))
    lo, hi = float(arr[0]), float(arr[1])
    if not hi > lo:
        raise ValueError(f"{name} must be (min, max) with max > min, got {(lo, hi)}")
    return lo, hi


def _count(lo: float, hi: float, resolution: float, cell: float) -> Decimal:
    """Cells of ``resolution`` covering ``[lo, hi]``, exactly (no overflow before the size
    check), counted in cells of ``cell`` (the decimal a float32 resolution stands for)
    unless the window is a whole number of the resolution's own cells."""
    low, high, res = Decimal(lo), Decimal(hi), Decimal(resolution)
    n = (high - low) / res
    # A window that is an exact multiple in decimal (12 m at 0.01 m) may exceed it once
    # lo, hi and resolution are floats, by up to 2**-53 of |lo| + |hi| and of the width,
    # in cells: 1e-8 cells for (1e6 + 0.2, 1e6 + 0.3) at 0.01 m. The slack keeps it
    # from gaining a cell.
    slack = Decimal("1e-9") + _FLOAT_SLACK * ((abs(low) + abs(high)) / res + n)
    whole = n.to_integral_value(rounding=ROUND_HALF_EVEN)
    if cell != resolution and abs(n - whole) > slack:
        # Not whole cells of the float32 itself (n times float32 0.05 is a little more
        # than n times 0.05, and gained a cell counted in the decimal; review 54).
        res = Decimal(cell)
        n = (high - low) / res
        slack = Decimal("1e-9") + _FLOAT_SLACK * ((abs(low) + abs(high)) / res + n)
    return max(Decimal(1), (n - slack).to_integral_value(rounding=ROUND_CEILING))


def _centres(lo: float, n: int, resolution: float, name: str) -> FloatArray:
    out: FloatArray = lo + (np.arange(n, dtype=np.float64) + 0.5) * resolution
    if not abs(float(out[-1])) <= COORDINATE_LIMIT:
        raise ValueError(
            f"{name}: the last cell centre, {float(out[-1]):g} m, lies beyond "
            f"±{COORDINATE_LIMIT:g} m (a smaller resolution or window fits)"
        )
    return out


def sample_field(
    field: PotentialField,
    *,
    xlim: ArrayLike,
    ylim: ArrayLike,
    resolution: float,
) -> SampledField:
    """Evaluate a field's potential and force on a grid (e.g. for plots).

    The window ``[xlim[0], xlim[1]] × [ylim[0], ylim[1]]`` is divided into square
    cells of side ``resolution``; values are taken at cell centres, so
    ``xlim=(0, 12), resolution=0.01`` gives 1200 columns. Cells start at the
    window's lower corner ``(xlim[0], ylim[0])``; an extent that is not a whole
    number of cells gets one more, which reaches past the upper limit
    (``xlim=(0, 1), resolution=0.3``: 4 columns, centres 0.15 to 1.05). A
    float32 ``resolution`` (a ROS map's) counts cells of the decimal it stands
    for: ``xlim=(0, 12)`` at ``float(np.float32(0.01))`` gives 1200 columns too,
    spaced by the float32.

    Parameters
    ----------
    field : PotentialField
        Any navkit field, including composites.
    xlim, ylim : array_like, shape (2,)
        ``(min, max)`` extents in metres, ``max > min``, within ``±1e9``.
    resolution : float
        Cell side in metres, in ``[1e-6, 1e6]``. The window may hold at most
        ``2**26`` (8192 × 8192) cells.

    Returns
    -------
    SampledField
        Coordinates, ``potential`` (H, W) and ``force`` (H, W, 2) indexed ``[row, col]``.

    Raises
    ------
    ValueError
        Limits out of range or not increasing; more than ``2**26`` cells (the
        message says how many the window would need and their memory);
        ``resolution`` out of range.
    TypeError
        ``field`` is not a PotentialField; non-numeric limits or resolution.

    Examples
    --------
    >>> from navkit.planning import ConicAttraction
    >>> sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0),
    ...                        ylim=(0.0, 1.0), resolution=0.5)
    >>> sampled.potential.shape, sampled.force.shape
    ((2, 4), (2, 4, 2))
    >>> sampled.x
    array([-0.75, -0.25,  0.25,  0.75])
    """
    if not isinstance(field, PotentialField):
        raise TypeError(f"field must be a PotentialField, got {type(field).__name__}")
    res = positive_float(resolution, "resolution")
    x0, x1 = _limits(xlim, "xlim")
    y0, y1 = _limits(ylim, "ylim")
    # Counted in cells of the decimal a float32 resolution stands for (10 m at a ROS
    # message's 0.01 m are 1000 cells, not 1001; review 53), a window of whole cells
    # of the float32 itself in those (review 54); centres are spaced by res.
    cell = intended_resolution(res)
    nx = _count(x0, x1, res, cell)
    ny = _count(y0, y1, res, cell)
    if not nx * ny <= MAX_SAMPLES:
        raise ValueError(
            f"sample_field would need {_num(ny)} × {_num(nx)} = {_num(nx * ny)} cells "
            f"({_bytes_text(nx * ny * _BYTES_PER_SAMPLE)}) at resolution {res:g} m; the "
            f"maximum is 2**26 = {MAX_SAMPLES} cells (8192 × 8192)"
        )
    check_coordinates(np.array([x0, x1]), "xlim")
    check_coordinates(np.array([y0, y1]), "ylim")
    res = _resolution(res)
    xs = _centres(x0, int(nx), res, "xlim")
    ys = _centres(y0, int(ny), res, "ylim")
    shape = (ys.size, xs.size)
    potential = np.empty(shape)
    force = np.empty((*shape, 2))
    flat_potential = potential.reshape(-1)
    flat_force = force.reshape((-1, 2))
    # The points row by row, x fastest (a meshgrid's order), a block of cells at a
    # time: the whole grid of points and the fields' temporaries (a Khatib field's
    # one per obstacle) held 128 bytes a cell beside the results, 8 GiB at 2**26 cells.
    cells = shape[0] * shape[1]
    block = min(cells, _BLOCK_CELLS)
    pts = np.empty((block, 2))
    index = np.arange(block, dtype=np.int64)
    # An underflow to 0 (a squared offset of 1e-200 m from a goal) is no error, nor
    # a warning under a caller's np.seterr(under="warn"): NumPy's default answer. One
    # np.errstate per call (about 2 µs, 1 % of the smallest grid's 0.2 ms), where the
    # field methods, called once per control step, redo the work under "raise" only.
    with np.errstate(under="ignore"):
        for start in range(0, cells, block):
            n = min(block, cells - start)
            rows, cols = np.divmod(index[:n] + start, shape[1])
            part = pts[:n]
            part[:, 0] = xs[cols]
            part[:, 1] = ys[rows]
            flat_potential[start : start + n] = field._potential(part).reshape(n)
            flat_force[start : start + n] = field._force(part).reshape((n, 2))
    return SampledField._owned(xs, ys, potential, force, res)


def _bytes_text(n: Decimal) -> str:
    units = ("B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB", "ZiB", "YiB")
    k = 0
    while n >= 1024 and k < len(units) - 1:
        n /= 1024
        k += 1
    return f"{_num(n)} {units[k]}"


def _num(n: Decimal) -> str:
    """``n`` to 3 significant digits, as a float prints it when it fits one."""
    return f"{float(n):.3g}" if n < Decimal("1e300") else f"{n:.2e}"
