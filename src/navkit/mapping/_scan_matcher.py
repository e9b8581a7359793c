"""Gauss–Newton scan-to-map matching (Hector SLAM's matcher, with the exact gradient)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.float32 import length_in_cells
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, bounded_int, scan_reading_hint
from navkit.geometry import Pose2D, as_pose
from navkit.mapping._grid import OccupancyGrid, _owned_grid
from navkit.mapping._limits import RANGE_LIMIT, RESOLUTION_MAX, bounded_float
from navkit.mapping._scan import LaserScan
from navkit.mapping._scan_matcher_kernels import (
    STATUS_MAX_ITERATIONS,
    STATUS_SINGULAR,
    accumulate,
    correlative_search,
    match_level,
)

__all__ = ["ScanMatchReason", "ScanMatchResult", "ScanMatcher", "bounded_int", "scan_points"]

#: Fewest valid points a scan needs to be matched (three unknowns).
MIN_POINTS = 3
#: Smallest ratio of the weakest to the strongest direction of the Hessian
#: (rotation scaled by the RMS range of the points, so all three are in m⁻²)
#: below which the fit is called degenerate: a featureless corridor, a single wall.
DEGENERACY_RATIO = 1e-2
_MAX_LEVELS = 16
FLOOR = 0.0
#: Largest mean ``(1 - M)²`` of a scan whose points all lie on a plateau of occupied
#: cells (zero Hessian) for the match to count as converged there: M of at least
#: 0.9 on average (a scan with nothing mapped in reach has 0.25, on unknown cells).
PLATEAU_COST = 0.01
_MAX_ITERATIONS = 10_000
# Finest rotation step of the correlative pre-search (rad) and most steps each way.
_MIN_SEARCH_STEP = math.radians(0.25)
_MAX_SEARCH_STEPS = 360
# Most candidate poses of one pre-search (about 15 s at the worst, 0.45 µs a pose
# for a 360-beam scan): a window of 100 m on a 1 cm grid would otherwise be 3e11.
_MAX_SEARCH_POSES = 2**25

ScanMatchReason = Literal[
    "converged", "max_iterations", "no valid beams", "guess outside the map", "degenerate"
]
"""Every ``reason`` a :class:`ScanMatchResult` can give (the values of ``REASONS``)."""

#: Every ``reason`` a :class:`ScanMatchResult` can give.
REASONS = (
    "converged",
    "max_iterations",
    "no valid beams",
    "guess outside the map",
    "degenerate",
)


def scan_points(scan: LaserScan, range_max: float | None) -> FloatArray:
    """Sensor-frame end points (M, 2) of the valid beams shorter than ``range_max``."""
    points = scan.to_points()
    if range_max is not None and points.shape[0]:
        keep = scan.ranges[scan.valid_mask()] < range_max
        points = points[keep]
    return np.ascontiguousarray(points)


def _readonly(arr: FloatArray) -> FloatArray:
    arr.flags.writeable = False
    return arr


def _unknown_covariance() -> FloatArray:
    return _readonly(np.diag(np.full(3, np.inf)))


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class ScanMatchResult:
    """Outcome of :meth:`ScanMatcher.match`.

    Attributes
    ----------
    pose : Pose2D
        Matched world pose of the sensor; the guess itself when the match could
        not be made (``reason`` other than ``"converged"`` or ``"max_iterations"``),
        except that a ``"degenerate"`` match with both ``translation_weight``
        and ``rotation_weight`` of the matcher above 0 keeps its estimate: the
        pull towards the guess fixes what the map leaves free.
    covariance : ndarray, shape (3, 3)
        Covariance of ``(x, y, theta)`` (m², m·rad, rad²): the residual variance
        ``Σ (1 - M)² / (n - 3)`` times the inverse Gauss–Newton Hessian on the
        finest level. Read-only. Infinite variances (zero covariances) when no
        match could be made (every ``reason`` but ``"converged"`` and
        ``"max_iterations"``). Where every point lies on a plateau of occupied
        cells (walls drawn on cell edges are two cells thick, and a noise-free
        scan's points fall between the two), the map's Hessian is zero though the
        scan fits: the match is ``"converged"`` at the last iterate (with the
        matcher's prior weights or without), with the
        covariance of a uniform error over one cell (``resolution² / 12`` m² per
        axis, and the rotation moving the points' RMS range ``r`` by as much:
        ``resolution² / (12 r²)`` rad²), if the plateau ends within a cell in
        every direction; one the scan could slide on (inside a solid block,
        along a corridor) is ``"degenerate"``.
        This is the uncertainty of the fit, not a bound on the pose error:
        it leaves out the map's discretisation, and range noise beyond about
        half a cell (a point more than a cell from its wall adds nothing to
        the fit's slope). Measured over 100 simulated scans each (360 beams,
        RMS range 2.6 m, a room mapped from the true pose in 5 cm cells): the
        spread of the matches is 0.7 to 1.2 times the reported standard
        deviations at 1 % range noise, about 2 times at 2.23 % (the default
        of ``navkit.sim.RangeNoise``) and 4 times at 5 %; noise-free
        matches are biased by about 0.1 cell where walls lie inside cells and
        0.4 cell where they lie on cell edges of a map built with
        :func:`~navkit.mapping.integrate_scan` (2 to 5 times the reported
        deviation; the plateau matches of walls drawn on cell edges land
        within 0.3 mm, well inside their one-cell covariance). Adding the
        one-cell covariance (``resolution² / 12`` per axis) covered bias and
        spread up to 2.23 % noise (mean NEES 0.3 to 2.5; 3 is consistent),
        not at 5 % (12.5).
    iterations : int
        Gauss–Newton iterations done, all levels together.
    score : float
        Mean interpolated occupancy probability ``M`` of the scan's points at
        ``pose`` on the finest level, in [0, 1]: 1 when every point lies on a
        certain obstacle, 0.5 on unknown cells and off the map (past its
        edges cells count as unknown; see :class:`ScanMatcher`).
    converged : bool
        True when the finest level stopped on the convergence test.
    reason : str
        ``"converged"``; ``"max_iterations"`` (the last iterate is returned; it
        is usually usable); or, with ``pose`` the guess: ``"no valid beams"``
        (fewer than three usable returns), ``"guess outside the map"``,
        ``"degenerate"`` (the map constrains the pose in fewer than three
        directions: a featureless corridor, a single wall, no mapped
        obstacle in reach).

    Raises
    ------
    TypeError
        ``pose`` not a :class:`~navkit.geometry.Pose2D` or sequence of three
        numbers, ``covariance`` not real numbers, ``iterations`` not an
        integer, ``converged`` not a bool, ``reason`` not a str.
    ValueError
        ``pose`` or ``covariance`` of the wrong shape, ``covariance`` with NaN
        or -inf, ``iterations`` or ``score`` out of range, an unknown
        ``reason``.

    Examples
    --------
    >>> result = ScanMatchResult(Pose2D(1.0, 2.0, 0.0), np.eye(3), 4, 0.9, True, "converged")
    >>> result.converged, result.covariance.flags.writeable
    (True, False)
    """

    pose: Pose2D
    covariance: FloatArray
    iterations: int
    score: float
    converged: bool
    reason: ScanMatchReason

    if TYPE_CHECKING:
        # What the constructor converts and checks (the fields hold the results):
        # a pose as three numbers, the covariance as array_like, the reason as any str.
        def __init__(
            self,
            pose: Pose2D | ArrayLike,
            covariance: ArrayLike,
            iterations: int,
            score: float,
            converged: bool,
            reason: str,
        ) -> None: ...

    def __post_init__(self) -> None:
        pose: object = self.pose
        if not isinstance(pose, Pose2D):
            object.__setattr__(self, "pose", as_pose(pose, "pose"))  # type: ignore[arg-type]
        cov = np.array(
            as_float_array(self.covariance, "covariance", shape=(3, 3), finite=False), copy=True
        )
        if np.isnan(cov).any() or (cov == -np.inf).any():
            raise ValueError("covariance must not contain NaN or -inf")
        object.__setattr__(self, "covariance", _readonly(cov))
        object.__setattr__(self, "iterations", bounded_int(self.iterations, "iterations", 0, 2**62))
        object.__setattr__(self, "score", bounded_float(self.score, "score", 0.0, 1.0))
        if not isinstance(self.converged, (bool, np.bool_)):
            raise TypeError(f"converged must be a bool, got {type(self.converged).__name__}")
        object.__setattr__(self, "converged", bool(self.converged))
        reason = as_text(self.reason, "reason")
        if reason not in REASONS:
            raise ValueError(f"reason must be one of {REASONS}, got {reason!r}")
        object.__setattr__(self, "reason", reason)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("covariance",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("covariance",))


def _as_levels(maps: OccupancyGrid | Sequence[OccupancyGrid]) -> tuple[OccupancyGrid, ...]:
    if isinstance(maps, OccupancyGrid):
        return (maps,)
    given: object = maps
    if isinstance(given, (str, bytes)) or not isinstance(given, Sequence):
        raise TypeError(
            f"maps must be an OccupancyGrid or a sequence of them, got {type(maps).__name__}"
        )
    levels = tuple(maps)
    if not levels:
        raise ValueError("maps must hold at least one OccupancyGrid")
    if len(levels) > _MAX_LEVELS:
        raise ValueError(f"maps must hold at most {_MAX_LEVELS} levels, got {len(levels)}")
    for i, level in enumerate(levels):
        if not isinstance(level, OccupancyGrid):
            raise TypeError(f"maps[{i}] must be an OccupancyGrid, got {type(level).__name__}")
    return levels


def downsample(grid: OccupancyGrid) -> OccupancyGrid:
    """The grid at twice the cell size: each cell the largest log-odds of its 2 × 2 block.

    The largest value keeps thin walls (a hit wins over misses, as when a scan
    is written into a coarse map directly). Cells beyond an odd edge count as unknown.
    The maximum is taken over the four strided views of the cells, into the new
    grid's own array: a quarter of the grid's bytes, where a zero-padded copy of
    the grid and its reduction took 1.5 times them (1.5 GiB at ``MAX_CELLS``).
    """
    rows, cols = grid.shape
    cells = grid.logodds
    coarse = cells[0::2, 0::2].copy()  # (ceil(rows / 2), ceil(cols / 2)), C-contiguous
    for dr, dc in ((1, 0), (0, 1), (1, 1)):
        part = cells[dr::2, dc::2]
        into = coarse[: part.shape[0], : part.shape[1]]
        np.maximum(into, part, out=into)
    # A block cut by an odd edge has unknown cells (log-odds 0) beyond it.
    if rows % 2:
        np.maximum(coarse[-1], 0.0, out=coarse[-1])
    if cols % 2:
        np.maximum(coarse[:, -1], 0.0, out=coarse[:, -1])
    return _owned_grid(
        OccupancyGrid,
        coarse,
        resolution=2.0 * grid.resolution,
        origin=grid.origin,
        occupied_thresh=grid.occupied_thresh,
        free_thresh=grid.free_thresh,
    )


class ScanMatcher:
    """Gauss–Newton scan-to-map matching on the occupancy probability, coarse to fine.

    The scan's end points ``sᵢ`` (sensor frame) are placed in the world by the
    pose ``ξ = (x, y, θ)``, ``Sᵢ(ξ) = R(θ) sᵢ + (x, y)``, and ``ξ`` is moved to
    bring every point onto an obstacle of the map: Gauss–Newton on
    ``Σ [1 - M(Sᵢ(ξ))]²`` (Kohlbrecher et al., "A flexible and scalable SLAM
    system with full 3D motion estimation", SSRR 2011)::

        Δξ = H⁻¹ Σ [∇M(Sᵢ(ξ)) ∂Sᵢ/∂ξ]ᵀ [1 - M(Sᵢ(ξ))],
        H  = Σ [∇M(Sᵢ(ξ)) ∂Sᵢ/∂ξ]ᵀ [∇M(Sᵢ(ξ)) ∂Sᵢ/∂ξ].

    ``M`` is the occupancy probability interpolated bilinearly between cell
    centres, and ``∇M`` its **exact** derivative. Between the centres of a
    map's edge cells and its edge (its outer half cell) the cells beyond the
    edge count as unknown (probability 0.5), as if the map had a margin of
    unknown cells: a wall drawn in the edge cells pulls the scan as one
    further in does, and a map one cell wide is matched too. Past the edge
    too, without end: ``M`` is 1/2 with no gradient a cell past the edge
    cells' centres. (Until review 50 it was 0 there, Hector SLAM's value out
    of its map's bounds, which made a map tight to its walls match worse
    than the same map padded with unknown cells.) So a match from a guess far
    off may end off the map, where its points read unknown: such a result
    scores about 1/2 and may still report ``"converged"`` (a 4 m x 3 m room
    matched from a guess 2.4 m off, in its corner, ended 1.4 m past its edge,
    score 0.53); check the pose against the map's bounds where that matters.
    (The probability of a cell is computed from its float32 log-odds with a
    single-precision ``exp``, for speed; that changes ``M`` and ``∇M`` by at
    most about 2e-8 and matched poses by about 1e-10 m, far below any map's
    resolution.) (Hector SLAM's C++
    ``interpMapValueWithDerivatives`` swaps the x and y interpolation factors
    in the gradient, a long-standing open bug, so its step direction is not
    the derivative of its own interpolant; navkit's gradient agrees with
    finite differences, as its tests check.)

    Matching runs from the coarsest map level to the finest, each starting
    from the previous level's pose. Each iteration clamps its step to
    ``max_step_cells`` cells of the level (translation) and ``max_step_angle``
    (rotation; Hector clamps at 0.2 rad), then halves it up to four times
    until the cost does not increase (a backtracking line search Hector does
    not have: it keeps a step from overshooting on the piecewise-bilinear
    surface). A level stops when a step is smaller than ``tolerance`` m and
    ``tolerance / 10`` rad (both doubled on each coarser level), when no
    halving lowers the cost, or after ``max_iterations``.

    Bad input never gives a NaN pose: the result carries the guess with
    ``converged=False`` and a ``reason`` (see :class:`ScanMatchResult`) when
    the scan has fewer than three valid returns, when the guess lies outside
    the finest map, or when the map does not constrain all three directions
    (the Hessian's weakest direction, rotation scaled by the RMS range of the
    points, is below 1e-2 of its strongest: a featureless corridor; with both
    weights above 0 the result then carries the estimate the pull towards the
    guess fixes, still with ``converged=False``). Wrong types and values
    raise ``TypeError`` / ``ValueError`` naming the argument.

    Parameters
    ----------
    levels : int, default 3
        Number of map levels built from a single grid given to :meth:`match`
        (each doubling the cell size; 1 to 16; fewer for grids too small or
        too coarse for them, see :meth:`pyramid`). A sequence of grids is
        used as given.
    max_iterations : int, default 20
        Gauss–Newton iterations per level, 1 to 10,000.
    max_step_cells : float, default 2.0
        Largest translation of one iteration, in cells of the level, in (0, 1e6].
    max_step_angle : float, default 0.2
        Largest rotation of one iteration, rad, in (0, π].
    tolerance : float, default 1e-3
        Convergence threshold on the finest level: a step shorter than this (m)
        and turning less than ``tolerance / 10`` rad; in (0, 1e6].
    range_max : float, optional
        Only returns shorter than this (m) are matched (all valid returns when None).
    translation_weight, rotation_weight : float, default 0.0
        Pull towards the guess: ``translation_weight² |t - t₀|² +
        rotation_weight² (θ - θ₀)²`` is added to the mean cost (1/m and 1/rad,
        in [0, 1e6]). It keeps directions the map leaves free near the guess;
        scale it with the inverse of the guess's expected error.
    search_distance, search_angle : float, default 0.0
        Half-widths of a correlative pre-search on the coarsest level (m in
        [0, 100], rad in [0, π]): the cost (nearest cells, plus the pull) is
        evaluated on a grid of translations one coarsest cell apart and of
        rotations that move the far points (90th percentile of the ranges) by
        half a cell (at most 360 each way), and Gauss–Newton starts from the
        best. Grids of more than 2**25 poses (about 15 s) have their
        translations spread further apart to fit. It widens the
        basin from about a coarse cell and a few degrees to the window; about
        ±2σ of the guess's error is a good window. 0 and 0: no search.

    Other Parameters
    ----------------
    max_range : float, optional
        Deprecated name of `range_max`.

    Raises
    ------
    TypeError
        An option of the wrong type (``levels`` and ``max_iterations`` not an
        integer, the others not a real number); both ``range_max`` and
        ``max_range`` given.
    ValueError
        An option outside its range, NaN or inf.

    Examples
    --------
    >>> import math
    >>> from navkit.mapping import integrate_scan
    >>> angles = np.linspace(-math.pi, math.pi, 180, endpoint=False)
    >>> with np.errstate(divide="ignore"):  # the walls of a 6 m × 4 m room
    ...     ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    >>> scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 180,
    ...                  range_min=0.1, range_max=10.0)          # a 6 m x 4 m room
    >>> room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.05,
    ...                            origin=(-4.0, -3.0, 0.0))
    >>> _ = integrate_scan(room, scan, (0.0, 0.0, 0.0), hit=2.2, miss=-0.4)
    >>> result = ScanMatcher().match(room, scan, Pose2D(0.15, -0.1, 0.1))
    >>> result.converged, result.reason
    (True, 'converged')
    >>> p = result.pose                                 # back within half a cell
    >>> bool(abs(p.x) < 0.025 and abs(p.y) < 0.025 and abs(p.theta) < 0.005)
    True
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_levels",
        "_max_iterations",
        "_max_range",
        "_max_step_angle",
        "_max_step_cells",
        "_rotation_weight",
        "_search_angle",
        "_search_distance",
        "_tolerance",
        "_translation_weight",
    )
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(
        self,
        *,
        levels: int = 3,
        max_iterations: int = 20,
        max_step_cells: float = 2.0,
        max_step_angle: float = 0.2,
        tolerance: float = 1e-3,
        range_max: float | None = None,
        translation_weight: float = 0.0,
        rotation_weight: float = 0.0,
        search_distance: float = 0.0,
        search_angle: float = 0.0,
        max_range: float | None = None,
    ) -> None:
        named = "range_max" if max_range is None else "max_range"  # as the caller wrote it
        range_max = renamed_keyword("max_range", max_range, "range_max", range_max, None)
        self._levels = bounded_int(levels, "levels", 1, _MAX_LEVELS)
        self._max_iterations = bounded_int(max_iterations, "max_iterations", 1, _MAX_ITERATIONS)
        self._max_step_cells = bounded_float(
            max_step_cells, "max_step_cells", 0.0, 1e6, "cells", low_open=True
        )
        self._max_step_angle = bounded_float(
            max_step_angle, "max_step_angle", 0.0, math.pi, "rad", low_open=True
        )
        self._tolerance = bounded_float(tolerance, "tolerance", 0.0, 1e6, "m", low_open=True)
        self._max_range = (
            None
            if range_max is None
            else bounded_float(range_max, named, 0.0, RANGE_LIMIT, "m", low_open=True)
        )
        self._translation_weight = bounded_float(
            translation_weight, "translation_weight", 0.0, 1e6, "1/m"
        )
        self._rotation_weight = bounded_float(rotation_weight, "rotation_weight", 0.0, 1e6, "1/rad")
        self._search_distance = bounded_float(search_distance, "search_distance", 0.0, 100.0, "m")
        self._search_angle = bounded_float(search_angle, "search_angle", 0.0, math.pi, "rad")

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(levels={self._levels}, max_iterations={self._max_iterations}, "
            f"max_step_cells={self._max_step_cells}, max_step_angle={self._max_step_angle}, "
            f"tolerance={self._tolerance}, range_max={self._max_range}, "
            # The pull and the pre-search change every match: without them ScanMapper's
            # default matcher (weights 1, search 0.1) printed as a bare ScanMatcher().
            f"translation_weight={self._translation_weight}, "
            f"rotation_weight={self._rotation_weight}, "
            f"search_distance={self._search_distance}, search_angle={self._search_angle})"
        )

    @property
    def levels(self) -> int:
        """Number of map levels built from a single grid."""
        return self._levels

    @property
    def range_max(self) -> float | None:
        """Returns at least this long (m) are not matched (None: every valid return)."""
        return self._max_range

    @property
    def max_range(self) -> float | None:
        """Deprecated alias of :attr:`range_max`.

        Examples
        --------
        >>> ScanMatcher(range_max=4.0).range_max  # the new name
        4.0
        """
        warnings.warn(
            "ScanMatcher.max_range is deprecated and will be removed in a future release: "
            "use ScanMatcher.range_max",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.range_max

    def pyramid(self, grid: OccupancyGrid) -> tuple[OccupancyGrid, ...]:
        """``grid`` and ``levels - 1`` coarser copies, finest first, each doubling the cell size.

        A coarse cell takes the largest log-odds of the 2 × 2 cells it covers,
        so thin walls survive. Build the pyramid once and pass it to
        :meth:`match` when matching many scans against the same map. The
        coarser levels are copies, made now: after the map changes (e.g.
        :func:`~navkit.mapping.integrate_scan` writing into ``grid`` in place),
        build the pyramid again, or the coarse levels, which guide the match,
        go on showing the map as it was.

        Parameters
        ----------
        grid : OccupancyGrid
            The finest level.

        Returns
        -------
        tuple of OccupancyGrid
            ``grid`` itself, then up to ``levels - 1`` coarser grids (fewer when
            a level shrinks to one cell or the next one's cells would exceed
            1e6 m, the largest resolution), finest first.

        Raises
        ------
        TypeError
            ``grid`` not an :class:`~navkit.mapping.OccupancyGrid`.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=1.0, height=0.5, resolution=0.1)
        >>> [(g.shape, g.resolution) for g in ScanMatcher(levels=3).pyramid(grid)]
        [((5, 10), 0.1), ((3, 5), 0.2), ((2, 3), 0.4)]
        """
        if not isinstance(grid, OccupancyGrid):
            raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
        out = [grid]
        for _ in range(self._levels - 1):
            # No coarser level when it would be one cell, or its cells larger
            # than a grid's largest resolution (1e6 m).
            if out[-1].shape == (1, 1) or 2.0 * out[-1].resolution > RESOLUTION_MAX:
                break
            out.append(downsample(out[-1]))
        return tuple(out)

    def match(
        self,
        maps: OccupancyGrid | Sequence[OccupancyGrid],
        scan: LaserScan,
        guess: Pose2D | ArrayLike,
    ) -> ScanMatchResult:
        """Align ``scan`` to the map, starting from the sensor pose ``guess``.

        Parameters
        ----------
        maps : OccupancyGrid or sequence of OccupancyGrid
            The map: one grid (its :meth:`pyramid` is built, ``levels`` levels,
            on every call) or the levels themselves, finest first (each may
            have its own resolution and origin; the finest defines the
            result's score and covariance). Not modified. Building the
            pyramid costs far more than a match: on a 1284 × 1379 map
            (Radish's aces log at 5 cm) ``match(grid, ...)`` took 117 ms and
            ``match(levels, ...)`` 2 ms. To match many scans against one map
            (localisation), build ``levels = matcher.pyramid(grid)`` once and
            pass ``levels``.
        scan : LaserScan
            The scan; its valid returns (shorter than ``range_max``) are matched.
        guess : Pose2D or array_like [x, y, theta]
            Initial world pose of the sensor.

        Returns
        -------
        ScanMatchResult
            Pose, covariance, iterations, score, converged flag and reason.

        Raises
        ------
        TypeError
            ``maps`` or ``scan`` of the wrong type.
        ValueError
            An empty sequence of maps, a guess that is not finite.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1)
        >>> scan = LaserScan([0.5], angle_min=0.0, angle_increment=0.1,
        ...                  range_min=0.1, range_max=4.0)
        >>> ScanMatcher().match(grid, scan, (1.0, 1.0, 0.0)).reason
        'no valid beams'
        """
        levels = self.pyramid(maps) if isinstance(maps, OccupancyGrid) else _as_levels(maps)
        if not isinstance(scan, LaserScan):
            raise TypeError(
                f"scan must be a LaserScan, got {type(scan).__name__}" + scan_reading_hint(scan)
            )
        start = as_pose(guess, "guess")
        return self._match(levels, scan_points(scan, self._max_range), start)

    def _match(
        self, levels: tuple[OccupancyGrid, ...], points: FloatArray, start: Pose2D
    ) -> ScanMatchResult:
        """Match validated sensor-frame ``points`` (M, 2), finest level first in ``levels``."""
        finest = levels[0]

        def failed(reason: str, iterations: int = 0) -> ScanMatchResult:
            score = self._score(finest, points, start) if points.shape[0] else 0.0
            return ScanMatchResult(start, _unknown_covariance(), iterations, score, False, reason)

        if points.shape[0] < MIN_POINTS:
            return failed("no valid beams")
        if not bool(finest.contains((start.x, start.y))):
            return failed("guess outside the map")
        pose = np.array([start.x, start.y, start.theta])
        prior = pose.copy()
        if self._search_distance > 0.0 or self._search_angle > 0.0:
            self._search(levels[-1], points, pose)
        iterations = 0
        status = STATUS_MAX_ITERATIONS
        # Scratch arrays of match_level, allocated here so that the kernel allocates nothing.
        hessian = np.empty((3, 3))
        gradient = np.empty(3)
        step = np.empty(3)
        no_hessian = np.empty((0, 0))
        for depth in range(len(levels) - 1, -1, -1):
            grid = levels[depth]
            o = grid.origin
            res = grid.resolution
            scale = res / finest.resolution
            trial = pose.copy()
            done, status = match_level(
                grid._logodds,
                o.x,
                o.y,
                o.theta,
                res,
                points,
                trial,
                self._max_iterations,
                self._max_step_cells * res,
                self._max_step_angle,
                self._tolerance * scale,
                self._tolerance * scale / 10.0,
                prior,
                self._translation_weight,
                self._rotation_weight,
                FLOOR,
                hessian,
                gradient,
                step,
                no_hessian,
            )
            iterations += done
            if status != STATUS_SINGULAR:
                pose = trial
        if status == STATUS_SINGULAR:
            # _plateau checks the map's own Hessian: the kernel's holds a prior's weights.
            plateau = self._plateau(finest, points, trial, iterations)
            if plateau is not None:
                return plateau
            return failed("degenerate", iterations)
        o = finest.origin
        cost, total = accumulate(
            finest._logodds,
            o.x,
            o.y,
            o.theta,
            finest.resolution,
            points,
            float(pose[0]),
            float(pose[1]),
            float(pose[2]),
            FLOOR,
            hessian,
            gradient,
        )
        n = points.shape[0]
        covariance = _covariance(hessian, cost, points)
        if covariance is None:
            if not hessian.any():
                # A plateau where a prior's weights kept the solve regular (at the guess).
                plateau = self._plateau(finest, points, pose, iterations)
                if plateau is not None:
                    return plateau
            if self._translation_weight > 0.0 and self._rotation_weight > 0.0:
                # The prior fixes what the map leaves free: keep its estimate.
                return ScanMatchResult(
                    Pose2D(float(pose[0]), float(pose[1]), float(pose[2])),
                    _unknown_covariance(),
                    iterations,
                    min(max(total / n, 0.0), 1.0),
                    False,
                    "degenerate",
                )
            return failed("degenerate", iterations)
        converged = status != STATUS_MAX_ITERATIONS
        return ScanMatchResult(
            Pose2D(float(pose[0]), float(pose[1]), float(pose[2])),
            covariance,
            iterations,
            min(max(total / n, 0.0), 1.0),
            converged,
            "converged" if converged else "max_iterations",
        )

    @staticmethod
    def _plateau(
        finest: OccupancyGrid, points: FloatArray, pose: FloatArray, iterations: int
    ) -> ScanMatchResult | None:
        """The match at ``pose`` if every point lies on a plateau of occupied cells.

        The Gauss–Newton Hessian is then exactly zero (no point sees a slope), as
        where nothing is in reach; but here the scan fits (mean ``(1 - M)²`` at most
        :data:`PLATEAU_COST`): walls drawn on cell edges are two cells thick, and a
        noise-free scan's points all fall between the two. The iterate is as good
        as the map can place the scan, to about a cell: the covariance is that of a
        uniform error over one cell (``resolution² / 12`` per axis, the rotation
        moving the points' RMS range by as much). None otherwise, and where the
        plateau does not end within a cell in every direction (the scan inside a
        solid block, or on a corridor's walls only).
        """
        o = finest.origin
        x, y, theta = (float(v) for v in pose)
        res = finest.resolution
        probe = np.empty((3, 3))
        gradient = np.empty(3)
        cost, total = accumulate(
            finest._logodds, o.x, o.y, o.theta, res, points,
            x, y, theta, FLOOR, probe, gradient,
        )  # fmt: skip
        n = points.shape[0]
        if probe.any() or not cost <= PLATEAU_COST * n:
            return None
        spread = res**2 / 12.0
        with np.errstate(under="ignore"):
            length = math.sqrt(float(np.mean(np.sum(points * points, axis=1)))) or 1.0
        # A plateau the scan could slide on places it nowhere: inside a solid block
        # every pose fits, along a corridor's walls every x. A thin plateau ends
        # within a cell: the Hessians a cell (and the rotation moving the RMS range
        # a cell) either side must fix every direction, as a match's own Hessian must.
        probes = np.zeros((3, 3))
        for axis, step in ((0, res), (1, res), (2, res / length)):
            for sign in (-1.0, 1.0):
                shifted = [x, y, theta]
                shifted[axis] += sign * step
                accumulate(
                    finest._logodds, o.x, o.y, o.theta, res, points,
                    shifted[0], shifted[1], shifted[2], FLOOR, probe, gradient,
                )  # fmt: skip
                probes += probe
        with np.errstate(under="ignore"):  # as in _covariance
            if _degenerate(probes, length):
                return None
        covariance = _readonly(np.diag([spread, spread, spread / (length * length)]))
        score = min(max(total / n, 0.0), 1.0)
        pose_found = Pose2D(x, y, theta)
        return ScanMatchResult(pose_found, covariance, iterations, score, True, "converged")

    def _search(self, grid: OccupancyGrid, points: FloatArray, pose: FloatArray) -> None:
        """Correlative pre-search on ``grid`` (the coarsest level): move ``pose`` to the best
        of a grid of poses within ``search_distance`` and ``search_angle`` of it."""
        res = grid.resolution
        # In cells of the decimal a float32 resolution stands for (a map from a ROS
        # message): 0.3 m at float32 0.01 are 30 steps, not 31 (review 53); whole cells
        # of the float32 itself in those (3 times float32 0.05: 3 steps, not 4; review 54).
        steps_xy = math.ceil(length_in_cells(self._search_distance, res) - 1e-9)
        reach = float(np.percentile(np.hypot(points[:, 0], points[:, 1]), 90.0))
        # A rotation step moves the far points (90th percentile) by half a cell.
        step_theta = min(max(0.5 * res / max(reach, res), _MIN_SEARCH_STEP), math.pi)
        steps_theta = min(math.ceil(self._search_angle / step_theta - 1e-9), _MAX_SEARCH_STEPS)
        if steps_theta:
            step_theta = self._search_angle / steps_theta
        step_xy = res
        rotations = 2 * steps_theta + 1
        if (2 * steps_xy + 1) ** 2 * rotations > _MAX_SEARCH_POSES:
            # Too many poses: the translations spread out to fit the budget.
            steps_xy = max(1, (math.isqrt(_MAX_SEARCH_POSES // rotations) - 1) // 2)
            step_xy = self._search_distance / steps_xy
        o = grid.origin
        correlative_search(
            grid._logodds,
            o.x,
            o.y,
            o.theta,
            res,
            points,
            pose,
            steps_xy,
            step_xy,
            steps_theta,
            step_theta,
            self._translation_weight,
            self._rotation_weight,
        )

    @staticmethod
    def _score(grid: OccupancyGrid, points: FloatArray, pose: Pose2D) -> float:
        o = grid.origin
        _, total = accumulate(
            grid._logodds,
            o.x,
            o.y,
            o.theta,
            grid.resolution,
            points,
            pose.x,
            pose.y,
            pose.theta,
            FLOOR,
            np.empty((0, 0)),
            np.empty(0),
        )
        score: float = min(max(float(total) / points.shape[0], 0.0), 1.0)
        return score


def _degenerate(hessian: FloatArray, length: float) -> bool:
    """Whether ``hessian`` leaves a direction free (call under ``np.errstate(under="ignore")``).

    Its eigenvalues, the rotation's scaled by the points' RMS range ``length``,
    spread more than :data:`DEGENERACY_RATIO`, or none is positive.
    """
    scaling = np.array([1.0, 1.0, 1.0 / length])
    eig = np.linalg.eigvalsh(hessian * np.outer(scaling, scaling))
    return not (eig[-1] > 0.0 and eig[0] > DEGENERACY_RATIO * eig[-1])


def _covariance(hessian: FloatArray, cost: float, points: FloatArray) -> FloatArray | None:
    """``σ² H⁻¹`` with ``σ² = cost / (n - 3)``; None when ``H`` is degenerate."""
    # A coordinate below 1e-154 squares to 0 and a near-perfect match's tiny cost
    # scales entries to 0, as under NumPy's defaults: no error under a caller's
    # np.seterr(under="raise") either (once per match: a microsecond).
    with np.errstate(under="ignore"):
        length = math.sqrt(float(np.mean(np.sum(points * points, axis=1)))) or 1.0
        if _degenerate(hessian, length):
            return None
        n = points.shape[0]
        sigma2 = cost / max(n - MIN_POINTS, 1)
        cov = np.linalg.inv(hessian) * sigma2
        cov = 0.5 * (cov + cov.T)
    if not np.isfinite(cov).all():
        return None
    return _readonly(cov)
