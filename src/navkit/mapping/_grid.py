"""Log-odds occupancy grids in the ROS ``nav_msgs/OccupancyGrid`` convention."""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any, TypedDict

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array, as_points, finite_float, positive_float
from navkit.geometry import Pose2D, as_pose
from navkit.mapping import _mapfile
from navkit.mapping._inflation import (
    INSCRIBED_INFLATED_OBSTACLE,
    NO_INFORMATION,
    inflation_costs,
    obstacle_distance,
)
from navkit.mapping._kernels import integrate_beams, world_to_cell_kernel
from navkit.mapping._scan import LaserScan

__all__ = ["OccupancyGrid", "OccupancyGridFields"]


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


#: Probabilities are clipped to [_P_MIN, _P_MAX] before taking log-odds so that
#: certain cells (p = 0 or 1, as in map files) stay finite (about ±6.9).
_P_MIN = 1e-3
_P_MAX = 1.0 - 1e-3
#: OctoMap's sensor model (prob_hit 0.7, prob_miss 0.4, clamping 0.12 / 0.97).
DEFAULT_HIT = _logit(0.7)
DEFAULT_MISS = _logit(0.4)
DEFAULT_CLAMP = (_logit(0.12), _logit(0.97))
#: map_server's default thresholds.
DEFAULT_OCCUPIED_THRESH = 0.65
DEFAULT_FREE_THRESH = 0.196
_IDENTITY = Pose2D(0.0, 0.0, 0.0)
# Distances compared against radii get this slack (in cells) so that radii that
# are exact multiples of the resolution include the cells at that distance.
_CELL_EPS = 1e-9


class OccupancyGridFields(TypedDict):
    """Values for the fields of a ``nav_msgs/OccupancyGrid`` message."""

    width: int
    height: int
    resolution: float
    origin_position: tuple[float, float, float]
    origin_orientation: tuple[float, float, float, float]
    data: NDArray[np.int8]


def _threshold(value: float | None, default: float, name: str) -> float:
    if value is None:
        return default
    out = finite_float(value, name)
    if not 0.0 <= out <= 1.0:
        raise ValueError(f"{name} must lie in [0, 1], got {out}")
    return out


def _logit_bound(p: float) -> float:
    if p <= 0.0:
        return -math.inf
    if p >= 1.0:
        return math.inf
    return _logit(p)


def _bool_grid(value: ArrayLike, name: str) -> NDArray[np.bool_]:
    arr = np.asarray(value)
    if arr.dtype != np.bool_:
        raise TypeError(f"{name} must be a boolean array, got dtype {arr.dtype}")
    if arr.ndim != 2 or arr.shape[0] == 0 or arr.shape[1] == 0:
        raise ValueError(f"{name} must be a non-empty 2-D (rows, cols) array, got {arr.shape}")
    return arr


class OccupancyGrid:
    """A 2-D occupancy grid storing the log-odds of occupancy of every cell.

    Cells are indexed ``[row, col]``. As in ROS ``nav_msgs/OccupancyGrid``, cell
    ``(0, 0)`` is the one at the map origin, rows grow along the origin's y axis
    and columns along its x axis, so **row 0 is the lowest y** (an image file's
    top row is the last map row). Cell ``(row, col)`` covers
    ``[col, col + 1) × [row, row + 1)`` times ``resolution`` in the origin frame.

    Log-odds 0 (probability 0.5) means unknown. The views :meth:`occupied`,
    :meth:`free` and :meth:`unknown` classify cells with the thresholds of
    map_server: occupied when ``p > occupied_thresh``, free when
    ``p < free_thresh``, unknown in between.

    Parameters
    ----------
    logodds : array_like, shape (rows, cols)
        Log-odds of occupancy; copied to a new float32 array.
    resolution : float
        Cell size, m.
    origin : Pose2D or array_like [x, y, yaw], default Pose2D(0, 0, 0)
        World pose of the corner of cell (0, 0) (its lower-left corner); the yaw
        rotates the whole grid.
    occupied_thresh, free_thresh : float
        Default thresholds of the views, ``0 <= free_thresh < occupied_thresh <= 1``.

    Examples
    --------
    >>> grid = OccupancyGrid.empty(4.0, 2.0, 0.5)
    >>> grid.shape
    (4, 8)
    >>> grid.world_to_cell([[0.1, 1.9], [3.9, 0.2]])
    array([[3, 0],
           [0, 7]])
    >>> grid.cell_to_world([3, 0])
    array([[0.25, 1.75]])
    >>> bool(grid.unknown().all())
    True
    """

    __slots__ = ("_free_thresh", "_logodds", "_occupied_thresh", "_origin", "_resolution")

    def __init__(
        self,
        logodds: ArrayLike,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
        *,
        occupied_thresh: float = DEFAULT_OCCUPIED_THRESH,
        free_thresh: float = DEFAULT_FREE_THRESH,
    ) -> None:
        arr = as_float_array(logodds, "logodds", ndim=2)
        if arr.shape[0] == 0 or arr.shape[1] == 0:
            raise ValueError(f"logodds must not be empty, got shape {arr.shape}")
        self._logodds = np.array(arr, dtype=np.float32, order="C", copy=True)
        self._resolution = positive_float(resolution, "resolution")
        self._origin = as_pose(origin, "origin")
        occ = _threshold(occupied_thresh, DEFAULT_OCCUPIED_THRESH, "occupied_thresh")
        free = _threshold(free_thresh, DEFAULT_FREE_THRESH, "free_thresh")
        if free >= occ:
            raise ValueError(
                f"free_thresh ({free}) must be smaller than occupied_thresh ({occ})"
            )
        self._occupied_thresh = occ
        self._free_thresh = free

    # ------------------------------------------------------------------ basics
    @property
    def logodds(self) -> NDArray[np.float32]:
        """Read-only view of the log-odds, shape (rows, cols), float32."""
        view: NDArray[np.float32] = self._logodds.view()
        view.flags.writeable = False
        return view

    @property
    def resolution(self) -> float:
        """Cell size, m."""
        return self._resolution

    @property
    def origin(self) -> Pose2D:
        """World pose of the lower-left corner of cell (0, 0)."""
        return self._origin

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``."""
        rows, cols = self._logodds.shape
        return int(rows), int(cols)

    @property
    def occupied_thresh(self) -> float:
        """Default probability above which a cell is occupied."""
        return self._occupied_thresh

    @property
    def free_thresh(self) -> float:
        """Default probability below which a cell is free."""
        return self._free_thresh

    @property
    def width(self) -> float:
        """Extent along the origin's x axis, m (``cols * resolution``)."""
        return self.shape[1] * self._resolution

    @property
    def height(self) -> float:
        """Extent along the origin's y axis, m (``rows * resolution``)."""
        return self.shape[0] * self._resolution

    def __repr__(self) -> str:
        return (
            f"OccupancyGrid(shape={self.shape}, resolution={self._resolution}, "
            f"origin={self._origin!r})"
        )

    def copy(self) -> OccupancyGrid:
        """Independent copy (log-odds array included)."""
        return OccupancyGrid(
            self._logodds,
            self._resolution,
            self._origin,
            occupied_thresh=self._occupied_thresh,
            free_thresh=self._free_thresh,
        )

    # ------------------------------------------------------------ constructors
    @classmethod
    def empty(
        cls,
        width: float,
        height: float,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
    ) -> OccupancyGrid:
        """All-unknown grid covering ``width × height`` metres (rounded up to whole cells).

        Parameters
        ----------
        width, height : float
            Extent along the origin's x and y axes, m (> 0).
        resolution : float
            Cell size, m (> 0).
        origin : Pose2D or array_like [x, y, yaw], optional
            World pose of the lower-left corner.
        """
        w = positive_float(width, "width")
        h = positive_float(height, "height")
        res = positive_float(resolution, "resolution")
        cols = max(1, math.ceil(w / res - 1e-9))
        rows = max(1, math.ceil(h / res - 1e-9))
        return cls(np.zeros((rows, cols), dtype=np.float32), res, origin)

    @classmethod
    def from_probabilities(
        cls,
        probabilities: ArrayLike,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
    ) -> OccupancyGrid:
        """Grid from occupancy probabilities in [0, 1] (0.5 = unknown), shape (rows, cols).

        Probabilities are clipped to [0.001, 0.999] so that certain cells have
        finite log-odds (about ±6.9).
        """
        p = as_float_array(probabilities, "probabilities", ndim=2)
        if p.size and (p.min() < 0.0 or p.max() > 1.0):
            raise ValueError("probabilities must lie in [0, 1]")
        p = np.clip(p, _P_MIN, _P_MAX)
        return cls(np.log(p / (1.0 - p)), resolution, origin)

    @classmethod
    def from_occupancy(
        cls,
        occupied: ArrayLike,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
        *,
        unknown: ArrayLike | None = None,
    ) -> OccupancyGrid:
        """Grid from a boolean obstacle mask: True occupied, False free.

        Parameters
        ----------
        occupied : array_like of bool, shape (rows, cols)
            Obstacle cells, ``[row, col]`` with row 0 at the lowest y.
        resolution : float
            Cell size, m.
        origin : Pose2D or array_like [x, y, yaw], optional
            World pose of the lower-left corner.
        unknown : array_like of bool, shape (rows, cols), optional
            Cells to mark unknown instead (must not overlap ``occupied``).

        Examples
        --------
        >>> grid = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), 1.0)
        >>> grid.traversal_costs()
        array([[inf,  1.,  1.],
               [ 1., inf,  1.],
               [ 1.,  1., inf]])
        """
        occ = _bool_grid(occupied, "occupied")
        prob = np.where(occ, 1.0, 0.0)
        if unknown is not None:
            unk = _bool_grid(unknown, "unknown")
            if unk.shape != occ.shape:
                raise ValueError(
                    f"unknown must have the shape of occupied {occ.shape}, got {unk.shape}"
                )
            if (unk & occ).any():
                raise ValueError("unknown and occupied must not overlap")
            prob[unk] = 0.5
        return cls.from_probabilities(prob, resolution, origin)

    @classmethod
    def from_polygons(
        cls,
        geometries: Any,
        bounds: ArrayLike,
        resolution: float,
    ) -> OccupancyGrid:
        """Rasterise shapely obstacles: a cell is occupied when it intersects one.

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
        >>> grid = OccupancyGrid.from_polygons(box(1.2, 0.2, 1.8, 0.8), (0, 0, 3, 1), 0.5)
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
                raise TypeError(
                    f"geometries[{i}] must be a shapely geometry, got {type(g).__name__}"
                )
        grid = cls.empty(xmax - xmin, ymax - ymin, res, Pose2D(xmin, ymin, 0.0))
        rows, cols = grid.shape
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
        return cls.from_occupancy(occ, res, grid.origin)

    @classmethod
    def from_msg(cls, msg: Any) -> OccupancyGrid:
        """Grid from a ``nav_msgs/OccupancyGrid`` (or any look-alike with its field names).

        ``data`` is row-major int8 with row 0 at the origin: -1 is unknown and
        0..100 the occupancy probability in percent. The origin's quaternion is
        reduced to its yaw.
        """
        try:
            info = msg.info
            width = int(info.width)
            height = int(info.height)
            resolution = info.resolution
            pos = info.origin.position
            q = info.origin.orientation
            ox, oy = float(pos.x), float(pos.y)
            qx, qy, qz, qw = float(q.x), float(q.y), float(q.z), float(q.w)
            raw = msg.data
        except AttributeError as exc:
            raise TypeError(f"msg is not a nav_msgs/OccupancyGrid: {exc}") from None
        data = np.asarray(raw, dtype=np.int64).ravel()
        if width <= 0 or height <= 0:
            raise ValueError(f"msg.info width and height must be positive, got {width}x{height}")
        if data.size != width * height:
            raise ValueError(
                f"msg.data has {data.size} values, expected width*height = {width * height}"
            )
        if ((data < -1) | (data > 100)).any():
            raise ValueError("msg.data values must be -1 (unknown) or 0..100")
        yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
        prob = np.where(data < 0, 0.5, data / 100.0).reshape(height, width)
        return cls.from_probabilities(prob, resolution, Pose2D(ox, oy, yaw))

    def to_msg_fields(self, *, trinary: bool = False) -> OccupancyGridFields:
        """Field values of the equivalent ``nav_msgs/OccupancyGrid``.

        Parameters
        ----------
        trinary : bool, default False
            False: ``data`` is the rounded probability in percent, with -1 for
            cells whose log-odds are exactly 0 (never observed). True: 100 for
            occupied, 0 for free, -1 for unknown cells according to the grid's
            thresholds (what map_server publishes).

        Returns
        -------
        dict
            ``width``, ``height``, ``resolution``, ``origin_position`` (x, y, 0),
            ``origin_orientation`` quaternion (x, y, z, w) and ``data``, a new
            row-major int8 array of length ``width * height``.

        Examples
        --------
        >>> fields = OccupancyGrid.from_occupancy(np.array([[True, False]]), 0.1).to_msg_fields()
        >>> fields["data"], fields["width"], fields["height"]
        (array([100,   0], dtype=int8), 2, 1)
        """
        if trinary:
            data = np.full(self.shape, -1, dtype=np.int8)
            data[self.occupied()] = 100
            data[self.free()] = 0
        else:
            data = np.rint(self.probability() * 100.0).astype(np.int8)
            data[self._logodds == 0.0] = -1
        half = 0.5 * self._origin.theta
        return {
            "width": self.shape[1],
            "height": self.shape[0],
            "resolution": self._resolution,
            "origin_position": (self._origin.x, self._origin.y, 0.0),
            "origin_orientation": (0.0, 0.0, math.sin(half), math.cos(half)),
            "data": data.ravel(),
        }

    # ------------------------------------------------------------------ files
    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> OccupancyGrid:
        """Load a ROS map_server map (YAML + image).

        Understands the keys ``image``, ``resolution``, ``origin`` [x, y, yaw],
        ``negate``, ``occupied_thresh``, ``free_thresh`` (all required, as in
        Nav2's map_server) and ``mode`` (``trinary`` by default, ``scale`` or
        ``raw``). PGM images (P5, P2) are read with numpy; other formats such as
        PNG need Pillow. The image's top row becomes the last grid row. The
        YAML's thresholds become the grid's thresholds, so the views reproduce
        map_server's trinary classification.

        Raises
        ------
        FileNotFoundError
            Missing YAML or image file.
        ValueError
            Missing or invalid YAML keys, malformed PGM.
        ImportError
            A non-PGM image and Pillow is not installed.
        """
        meta = _mapfile.read_map_yaml(path)
        grey, alpha = _mapfile.read_image(meta.image)
        prob, unknown = _mapfile.pixel_occupancy(grey, alpha, meta)
        p = np.clip(prob, _P_MIN, _P_MAX)
        logodds = np.where(unknown, 0.0, np.log(p / (1.0 - p)))[::-1]
        return cls(
            logodds,
            meta.resolution,
            Pose2D(*meta.origin),
            occupied_thresh=meta.occupied_thresh,
            free_thresh=meta.free_thresh,
        )

    def save(self, path: str | os.PathLike[str], *, mode: str = "trinary") -> Path:
        """Save as a ROS map_server map: ``path`` (YAML) and a P5 PGM beside it.

        Parameters
        ----------
        path : str or path-like
            YAML file to write; the image is the same name with suffix ``.pgm``.
        mode : {"trinary", "scale"}
            ``trinary`` writes map_saver's pixels (0 occupied, 254 free, 205
            unknown, or a mid grey when 205 would not be unknown under the grid's
            thresholds); ``scale`` writes ``round(255 * (1 - p))``. Either way
            loading the files gives back the same occupied/free/unknown classes.

        Returns
        -------
        Path
            The image file written.
        """
        yaml_path = Path(path)
        if mode not in ("trinary", "scale"):
            raise ValueError(f"mode must be 'trinary' or 'scale', got {mode!r}")
        occ_t, free_t = self._occupied_thresh, self._free_thresh
        if mode == "trinary":
            unknown_px = 205
            p_unknown = (255 - unknown_px) / 255.0
            if not free_t <= p_unknown <= occ_t:
                unknown_px = round(255.0 * (1.0 - 0.5 * (occ_t + free_t)))
            pixels = np.full(self.shape, unknown_px, dtype=np.uint8)
            pixels[self.free()] = 254
            pixels[self.occupied()] = 0
        else:
            pixels = np.rint(255.0 * (1.0 - self.probability())).astype(np.uint8)
            # Rounding may push a class-boundary probability across a threshold.
            p_px = (255.0 - pixels) / 255.0
            pixels[self.occupied() & ~(p_px > occ_t)] = 0
            pixels[self.free() & ~(p_px < free_t)] = 255
            between = self.unknown() & ((p_px > occ_t) | (p_px < free_t))
            pixels[between] = round(255.0 * (1.0 - 0.5 * (occ_t + free_t)))
        image = yaml_path.with_suffix(".pgm")
        _mapfile.write_pgm(image, pixels[::-1])
        _mapfile.write_map_yaml(
            yaml_path,
            _mapfile.MapMetadata(
                image,
                self._resolution,
                (self._origin.x, self._origin.y, self._origin.theta),
                False,
                occ_t,
                free_t,
                mode,
            ),
        )
        return image

    # ------------------------------------------------------------ coordinates
    def world_to_cell(self, points: ArrayLike) -> NDArray[np.int64]:
        """Cells ``(row, col)`` containing world points ``(x, y)``; shape (N, 2) int64.

        Cells are not clipped: points outside the map give indices outside
        ``[0, rows) × [0, cols)``; use :meth:`contains` to test. Vectorised in a
        numba kernel (10^6 points take milliseconds).
        """
        pts = np.ascontiguousarray(as_points(points, "points"))
        out = np.empty((pts.shape[0], 2), dtype=np.int64)
        o = self._origin
        world_to_cell_kernel(pts, o.x, o.y, o.theta, self._resolution, out)
        return out

    def cell_to_world(self, cells: ArrayLike) -> NDArray[np.float64]:
        """World ``(x, y)`` of the centres of cells ``(row, col)``; shape (N, 2)."""
        arr = as_points(cells, "cells")
        if not np.all(arr == np.round(arr)):
            raise ValueError("cells must hold integer (row, col) indices")
        local = (arr[:, ::-1] + 0.5) * self._resolution
        return self._origin.transform_points(local)

    def contains(self, points: ArrayLike) -> NDArray[np.bool_]:
        """Whether each world point ``(x, y)`` lies inside the map; shape (N,)."""
        cells = self.world_to_cell(points)
        rows, cols = self.shape
        return (cells[:, 0] >= 0) & (cells[:, 0] < rows) & (cells[:, 1] >= 0) & (cells[:, 1] < cols)

    # ------------------------------------------------------------------ views
    def probability(self) -> NDArray[np.float64]:
        """Occupancy probability ``1 - 1 / (1 + exp(l))`` of every cell, shape (rows, cols)."""
        return np.asarray(1.0 / (1.0 + np.exp(-self._logodds.astype(np.float64))))

    def occupied(self, threshold: float | None = None) -> NDArray[np.bool_]:
        """Cells with ``p > threshold`` (default: the grid's ``occupied_thresh``)."""
        th = _threshold(threshold, self._occupied_thresh, "threshold")
        return np.asarray(self._logodds > _logit_bound(th))

    def free(self, threshold: float | None = None) -> NDArray[np.bool_]:
        """Cells with ``p < threshold`` (default: the grid's ``free_thresh``)."""
        th = _threshold(threshold, self._free_thresh, "threshold")
        return np.asarray(self._logodds < _logit_bound(th))

    def unknown(
        self, occupied_thresh: float | None = None, free_thresh: float | None = None
    ) -> NDArray[np.bool_]:
        """Cells neither occupied nor free under the given (or the grid's) thresholds."""
        return ~self.occupied(occupied_thresh) & ~self.free(free_thresh)

    # --------------------------------------------------------------- inflation
    def inflate(self, radius_m: float) -> NDArray[np.bool_]:
        """Occupied cells grown by ``radius_m``: a boolean mask, shape (rows, cols).

        A cell is in the mask when its centre lies within ``radius_m`` (m) of the
        centre of an occupied cell (exact Euclidean distance transform). Unknown
        cells are not obstacles here.

        Examples
        --------
        >>> occ = np.zeros((5, 5), dtype=bool)
        >>> occ[2, 2] = True
        >>> OccupancyGrid.from_occupancy(occ, 0.5).inflate(0.5).astype(int)
        array([[0, 0, 0, 0, 0],
               [0, 0, 1, 0, 0],
               [0, 1, 1, 1, 0],
               [0, 0, 1, 0, 0],
               [0, 0, 0, 0, 0]])
        """
        radius = positive_float(radius_m, "radius_m", allow_zero=True)
        dist = obstacle_distance(self.occupied())
        return np.asarray(dist <= radius / self._resolution + _CELL_EPS)

    def costmap(
        self,
        inscribed_radius: float,
        inflation_radius: float,
        cost_scaling_factor: float = 10.0,
        *,
        inflate_unknown: bool = False,
    ) -> NDArray[np.uint8]:
        """ROS 2 Nav2 static + inflation layer costs, uint8 array (rows, cols).

        254 lethal (occupied), 253 inscribed (centre within ``inscribed_radius``
        of an obstacle), ``int(252 * exp(-cost_scaling_factor * (d -
        inscribed_radius)))`` out to ``ceil(inflation_radius / resolution)`` cells,
        0 free, 255 unknown (unknown cells take an inflated cost only when it is
        >= 253, or > 0 with ``inflate_unknown``), as Nav2's ``InflationLayer``.

        Parameters
        ----------
        inscribed_radius : float
            Radius of the robot's inscribed circle, m (>= 0).
        inflation_radius : float
            Distance up to which costs decay, m (>= ``inscribed_radius``).
        cost_scaling_factor : float, default 10.0
            Exponential decay rate, 1/m (> 0); Nav2's default.
        inflate_unknown : bool, default False
            Nav2's ``inflate_unknown`` parameter.
        """
        insc = positive_float(inscribed_radius, "inscribed_radius", allow_zero=True)
        infl = positive_float(inflation_radius, "inflation_radius", allow_zero=True)
        if infl < insc:
            raise ValueError(
                f"inflation_radius ({infl}) must be >= inscribed_radius ({insc})"
            )
        scale = positive_float(cost_scaling_factor, "cost_scaling_factor")
        return inflation_costs(
            self.occupied(),
            self.unknown(),
            self._resolution,
            insc + _CELL_EPS * self._resolution,
            infl,
            scale,
            bool(inflate_unknown),
        )

    def traversal_costs(
        self,
        inscribed_radius: float = 0.0,
        inflation_radius: float | None = None,
        cost_scaling_factor: float = 10.0,
        *,
        cost_weight: float = 4.0,
        unknown_cost: float = math.inf,
    ) -> NDArray[np.float64]:
        """Per-cell traversal costs for the grid planners, float64 (rows, cols).

        Built from :meth:`costmap`: lethal (254) and inscribed (253) cells are
        ``inf`` (the robot's centre cannot go there), unknown cells (255) cost
        ``unknown_cost``, and a Nav2 cost ``c`` in 0..252 becomes
        ``1 + cost_weight * c / 252``, so free space costs exactly 1.

        Parameters
        ----------
        inscribed_radius : float, default 0.0
            Robot's inscribed radius, m. 0 treats the robot as a point.
        inflation_radius : float, optional
            Decay distance, m; defaults to ``inscribed_radius`` (no cost band
            beyond the rounding to whole cells).
        cost_scaling_factor : float, default 10.0
            Decay rate of the inflation cost, 1/m.
        cost_weight : float, default 4.0
            Extra cost of a cell next to the inscribed zone; 4 makes the scale
            match NavFn's ``50 + 0.8 c`` divided by its neutral cost 50.
        unknown_cost : float, default inf
            Cost of unknown cells: ``inf`` (impassable, the default) or any
            value >= 1 to let planners cross unexplored space.
        """
        insc = positive_float(inscribed_radius, "inscribed_radius", allow_zero=True)
        infl = insc if inflation_radius is None else inflation_radius
        weight = positive_float(cost_weight, "cost_weight", allow_zero=True)
        unknown = float(unknown_cost)
        if math.isnan(unknown) or unknown < 1.0:
            raise ValueError(f"unknown_cost must be >= 1 or inf, got {unknown_cost}")
        cost = self.costmap(insc, infl, cost_scaling_factor)
        out = 1.0 + weight * cost.astype(np.float64) / (INSCRIBED_INFLATED_OBSTACLE - 1)
        out[cost >= INSCRIBED_INFLATED_OBSTACLE] = math.inf
        out[cost == NO_INFORMATION] = unknown
        return out

    # --------------------------------------------------------------- mapping
    def integrate_scan(
        self,
        scan: LaserScan,
        pose: Pose2D | ArrayLike,
        *,
        hit: float = DEFAULT_HIT,
        miss: float = DEFAULT_MISS,
        clamp: tuple[float, float] = DEFAULT_CLAMP,
        max_range: float | None = None,
        exact: bool = False,
    ) -> int:
        """Ray-cast one scan into the grid, updating the log-odds **in place**.

        Every valid beam (finite, ``range_min <= r < range_max``) adds ``miss`` to
        the cells it crosses and ``hit`` to its end cell. The crossed cells are
        the Bresenham line from the sensor's cell to the end cell (default, the
        fastest), or with ``exact=True`` every cell the beam segment passes
        through (Amanatides–Woo traversal: about 25 % slower, leaves no gaps
        between neighbouring beams where Bresenham steps diagonally). Readings
        ``>= range_max`` and ``+inf`` (no return) clear the cells up to
        ``range_max`` and mark nothing; NaN, ``-inf`` and too-close readings are
        skipped. Beams are clipped to the map (the sensor may be outside it): the
        walk runs between the cells where the beam enters and leaves the map, and
        a beam ending outside marks no hit.

        Each cell changes at most once per scan, even when several beams cross it
        (near the sensor almost all of them do): it takes ``hit`` if it is the end
        cell of any beam and ``miss`` otherwise (occupied wins, as in OctoMap's
        ``computeUpdate``). The result is clamped to ``clamp``.

        Parameters
        ----------
        scan : LaserScan
            The scan, beam angles in the sensor frame.
        pose : Pose2D or array_like [x, y, theta]
            World pose of the sensor; beam ``n`` ends at
            ``(x + d cos(θ_n + θ), y + d sin(θ_n + θ))``.
        hit, miss : float
            Log-odds increments (``hit >= 0 >= miss``); defaults are OctoMap's
            ``logit(0.7)`` and ``logit(0.4)``.
        clamp : (float, float)
            Log-odds bounds, default ``(logit(0.12), logit(0.97))``.
        max_range : float, optional
            Use ``min(scan.range_max, max_range)`` as the maximum range: longer
            readings clear up to it and mark no hit.
        exact : bool, default False
            Exact grid traversal instead of Bresenham lines.

        Returns
        -------
        int
            Number of cells updated.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(4.0, 4.0, 0.5)
        >>> scan = LaserScan([1.4], 0.0, 0.1, 0.1, 3.0)
        >>> grid.integrate_scan(scan, Pose2D(0.25, 1.25, 0.0))
        4
        >>> grid.occupied()[2].astype(int)
        array([0, 0, 0, 1, 0, 0, 0, 0])
        >>> bool((grid.logodds[2, :3] < 0).all())
        True
        """
        if not isinstance(scan, LaserScan):
            raise TypeError(f"scan must be a LaserScan, got {type(scan).__name__}")
        p = as_pose(pose, "pose")
        h = positive_float(hit, "hit", allow_zero=True)
        m = finite_float(miss, "miss")
        if m > 0.0:
            raise ValueError(f"miss must be <= 0 (a log-odds decrement), got {m}")
        lo, hi = _clamp_pair(clamp)
        rmax = scan.range_max
        if max_range is not None:
            rmax = min(rmax, positive_float(max_range, "max_range"))
        o = self._origin
        return int(
            integrate_beams(
                self._logodds,
                o.x,
                o.y,
                o.theta,
                self._resolution,
                p.x,
                p.y,
                p.theta,
                scan.ranges,
                scan.angle_min,
                scan.angle_increment,
                scan.range_min,
                rmax,
                h,
                m,
                lo,
                hi,
                bool(exact),
            )
        )


def _clamp_pair(clamp: Iterable[float]) -> tuple[float, float]:
    try:
        lo_raw, hi_raw = clamp
    except (TypeError, ValueError):
        raise ValueError(f"clamp must be a (low, high) pair, got {clamp!r}") from None
    lo = finite_float(lo_raw, "clamp[0]")
    hi = finite_float(hi_raw, "clamp[1]")
    if not lo < hi:
        raise ValueError(f"clamp must satisfy low < high, got {clamp!r}")
    return lo, hi
