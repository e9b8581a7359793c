"""Costs from occupancy grids: ROS 2 Nav2 costmaps and the planners' traversal costs.

The traversal-cost convention of navkit's grid planners (a 2-D float array,
finite values >= 1 per unit length, ``inf`` impassable) is checked by
:func:`validate_costs`; :func:`traversal_costs` builds such grids from an
:class:`~navkit.mapping.OccupancyGrid` through its Nav2 :func:`costmap`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.costs import validate_costs as _validate_costs
from navkit._shared.float32 import intended_resolution, length_in_cells
from navkit._shared.types import BoolArray, FloatArray
from navkit._shared.validation import as_bool
from navkit.mapping._grid import OccupancyGrid
from navkit.mapping._limits import (
    COST_LIMIT,
    RADIUS_LIMIT,
    SCALING_LIMIT,
    bounded_float,
    cost_or_inf,
)
from navkit.mapping._obstacle_distance import CELL_EPS, obstacle_distance_bands

__all__ = [
    "FREE_SPACE",
    "INSCRIBED_INFLATED_OBSTACLE",
    "LETHAL_OBSTACLE",
    "NO_INFORMATION",
    "costmap",
    "inflation_costs",
    "traversal_costs",
    "validate_costs",
]

# Cost values of ROS 2 Nav2 (nav2_costmap_2d/cost_values.hpp).
NO_INFORMATION = 255
LETHAL_OBSTACLE = 254
INSCRIBED_INFLATED_OBSTACLE = 253
FREE_SPACE = 0


def validate_costs(costs: ArrayLike) -> FloatArray:
    """Check a traversal-cost grid and return it as a C-contiguous float64 array.

    The grid planners' convention: a 2-D array indexed ``[row, col]`` whose
    finite values are >= 1 (cost per unit length of crossing the cell) and whose
    ``+inf`` entries are impassable. The input is never modified; it is copied
    only when a dtype or layout conversion is needed.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Candidate cost grid, indexed ``[row, col]``.

    Returns
    -------
    ndarray, shape (rows, cols)
        ``costs`` as C-contiguous float64 (the input itself when it already is).

    Raises
    ------
    ValueError
        Wrong dimension, empty grid, more than 2**31 - 1 cells (the grid
        planners' limit, checked before anything is converted or copied),
        non-numeric or boolean dtype, NaN, ``-inf`` or finite values below 1
        (the message gives the first offending cell).

    Examples
    --------
    >>> validate_costs([[1.0, 2.0], [np.inf, 1.5]])
    array([[1. , 2. ],
           [inf, 1.5]])
    >>> validate_costs([[0.5]])
    Traceback (most recent call last):
    ...
    ValueError: costs must be >= 1 where traversable (np.inf marks impassable cells); ...
    """
    return _validate_costs(costs, "costs")


def inflation_costs(
    occupied: BoolArray,
    unknown: BoolArray,
    resolution: float,
    robot_radius: float,
    inflation_radius: float,
    cost_scaling_factor: float,
    inflate_unknown: bool,
    inflate_around_unknown: bool = False,
) -> NDArray[np.uint8]:
    """Nav2 inflation-layer costs for a static layer of occupied/unknown cells.

    Reproduces ``nav2_costmap_2d::InflationLayer``: occupied cells get 254; cells
    whose centre lies within ``robot_radius`` (Nav2's inscribed radius) of an
    occupied centre get 253; farther cells up to
    ``ceil(inflation_radius / resolution)`` cells away (the resolution a float32
    stands for, except for a radius of whole cells of the float32 itself: see
    :func:`~navkit._shared.float32.length_in_cells`) get
    ``int(252 * exp(-cost_scaling_factor * (d - robot_radius)))``; the rest 0.
    Unknown cells keep 255 unless the inflated cost is >= 253 (or > 0 with
    ``inflate_unknown``). With ``inflate_around_unknown`` unknown cells are
    inflation sources too (and so become 254, as in Nav2). Distances use an
    exact Euclidean distance transform; where navkit and Nav2 differ, see the
    Notes of :func:`costmap`. ``robot_radius`` is compared as given: callers
    add the slack of :func:`costmap`. Arguments are not validated (see
    :func:`costmap`).

    Examples
    --------
    >>> occ = np.array([[True, False, False, False]])
    >>> inflation_costs(occ, ~occ & False, 1.0, 1.0, 2.0, 1.0, False)
    array([[254, 253,  92,   0]], dtype=uint8)
    """
    if inflate_around_unknown:
        occupied = occupied | unknown
    # Nav2's cell_inflation_radius, ceil(inflation_radius / resolution), in cells of
    # the decimal a float32 resolution stands for: 0.1 m on a 0.01 m map is 10 cells
    # read from its YAML and was 11 read from a ROS message (float32 0.00999999977),
    # whose cells sqrt(101) away got costs (review 52, FRESH on aa45556). A radius of
    # whole cells of the float32 itself is that many, as in Nav2: 3 x 0.0500000007 m
    # was 4 cells of the decimal 0.05 (review 54, FRESH2's finding).
    max_cells = math.ceil(length_in_cells(inflation_radius, resolution))
    cost = np.zeros(occupied.shape, dtype=np.uint8)
    # Band by band: the peak is the result and a band, not a float64 grid.
    for where, dist in obstacle_distance_bands(occupied):
        _inflate_band(cost[where], dist, max_cells, resolution, robot_radius, cost_scaling_factor)
        del dist  # before the next band is made: one band's distances at a time
    cost[occupied] = LETHAL_OBSTACLE
    keep_unknown = unknown & ~occupied
    if inflate_unknown:
        keep_unknown &= cost == FREE_SPACE
    else:
        keep_unknown &= cost < INSCRIBED_INFLATED_OBSTACLE
    cost[keep_unknown] = NO_INFORMATION
    return cost


def _inflate_band(
    cost: NDArray[np.uint8],
    dist: FloatArray,
    max_cells: int,
    resolution: float,
    robot_radius: float,
    cost_scaling_factor: float,
) -> None:
    """Write the inscribed and decaying costs of cells at distances ``dist`` into ``cost``.

    ``dist`` (a band's own array) is overwritten.
    """
    band = (dist > 0) & (dist <= max_cells)
    # Distances in metres, in place: one float64 grid, not two (peak memory).
    np.multiply(dist, resolution, out=dist)
    cost[band & (dist <= robot_radius)] = INSCRIBED_INFLATED_OBSTACLE
    band &= dist > robot_radius  # the decaying band
    # exp(-cost_scaling_factor * (d - robot_radius)) in place on every cell of dist,
    # though only the decaying band's are kept: no float64 copy of them (8 bytes a
    # cell, review 45), and whole-array loops (a where= mask's take twice as long).
    # Cells nearer than robot_radius may overflow and far cells underflow to 0
    # (cost 0, as Nav2's), and a tiny cost_scaling_factor (1e-300) underflows the
    # exponent: none is an error under a caller's np.seterr either.
    with np.errstate(over="ignore", under="ignore"):
        np.subtract(dist, robot_radius, out=dist)
        np.multiply(dist, -cost_scaling_factor, out=dist)
        np.exp(dist, out=dist)
        # Nav2 truncates: (unsigned char)((INSCRIBED_INFLATED_OBSTACLE - 1) * factor).
        np.multiply(dist, INSCRIBED_INFLATED_OBSTACLE - 1, out=dist)
    np.copyto(cost, dist, casting="unsafe", where=band)


def _inscribed(radius: float, resolution: float) -> float:
    """``radius`` (m) as compared with distances ``d * resolution``: as in cells of the
    decimal a float32 ``resolution`` above it stands for (see ``reach_cells``)."""
    intended = intended_resolution(resolution)
    return radius if intended >= resolution else radius * (resolution / intended)


def _check_grid(grid: object) -> OccupancyGrid:
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
    return grid


def costmap(
    grid: OccupancyGrid,
    *,
    robot_radius: float,
    inflation_radius: float,
    cost_scaling_factor: float = 10.0,
    inflate_unknown: bool = False,
    inflate_around_unknown: bool = False,
) -> NDArray[np.uint8]:
    """ROS 2 Nav2 static + inflation layer costs of a grid, uint8 array (rows, cols).

    254 lethal (occupied), 253 inscribed (centre within ``robot_radius`` of an
    obstacle), ``int(252 * exp(-cost_scaling_factor * (d - robot_radius)))``
    out to ``ceil(inflation_radius / resolution)`` cells, 0 free, 255 unknown
    (unknown cells take an inflated cost only when it is >= 253, or > 0 with
    ``inflate_unknown``), as Nav2's ``InflationLayer`` (but for the
    differences in Notes).

    Parameters
    ----------
    grid : OccupancyGrid
        Its occupied and unknown views are the static layer.
    robot_radius : float
        Radius of the robot's inscribed circle, m, in [0, 1e6]; Nav2's
        inscribed radius.
    inflation_radius : float
        Distance up to which costs decay, m, in [``robot_radius``, 1e6].
    cost_scaling_factor : float, default 10.0
        Exponential decay rate, 1/m, in (0, 1e12]; Nav2's default.
    inflate_unknown : bool, default False
        Nav2's ``inflate_unknown`` parameter: whether an *unknown cell* takes
        any inflated cost > 0 from a nearby obstacle (otherwise it stays 255
        unless that cost is >= 253). Unknown cells are not obstacles here.
    inflate_around_unknown : bool, default False
        Nav2's ``inflate_around_unknown`` parameter: unknown cells are
        inflation sources, like occupied ones (and become 254 themselves).
        This is what :func:`traversal_costs`'s ``inflate_unknown`` turns on.

    Returns
    -------
    ndarray of uint8, shape (rows, cols)
        New array of Nav2 costs: 254 lethal, 253 inscribed, 0..252 decaying
        inflation cost, 255 unknown.

    Raises
    ------
    TypeError
        ``grid`` is not an OccupancyGrid, a flag is not a bool, a number is
        not a real number.
    ValueError
        A number outside its range.

    Notes
    -----
    Where Nav2's costs differ (checked against oracles of both of its
    algorithms, on the ROS maps of ``NAVKIT_DATA``):

    * The static layer is the grid's occupied and unknown cells, classed by
      its thresholds. Nav2's static layer reads the ``nav_msgs/OccupancyGrid``
      values instead: by default only 100 is lethal, every other value free,
      and -1 unknown with ``track_unknown_space: true`` (as Nav2's bringup
      sets it for the global costmap; the costmap node's own default, false,
      makes -1 free too). ``mode: trinary`` maps read with
      :func:`~navkit.mapping.io.read_map` and trinary messages (0, 100, -1)
      give the same layer (-1 tracked as unknown). A message with other values read by
      :func:`~navkit.mapping.io.grid_from_msg` does not (values 66..99 are
      obstacles here, 20..65 unknown, and free in Nav2), nor does a
      ``mode: scale`` map: map_server publishes its pixels between the
      thresholds as ``rint((p - free_thresh) / (occupied_thresh -
      free_thresh) * 100)``, below 100 but at ``p == occupied_thresh``: free
      in Nav2 and unknown here (a map_saver PGM's 205 grey under
      ``mode: scale`` is free space there).
    * A cell exactly ``robot_radius`` from an obstacle is inscribed (253) here,
      also where rounding puts ``d * resolution`` just above the radius: Nav2
      compares ``d * resolution <= robot_radius`` in floating point, so at
      ``robot_radius=0.15`` on a 0.05 m grid the cells 3 cells away are 251
      there (``3 * 0.05 == 0.15000000000000002``) and 253 here, and
      :func:`traversal_costs` makes them impassable. The radius gets 1e-9 of
      a cell of slack here, as in :meth:`OccupancyGrid.inflate`, so that
      both agree on which cells the robot's body reaches. On a map whose
      resolution is a float32 (from a ROS message,
      :func:`~navkit.mapping.io.grid_from_msg`: 0.05 m arrives as
      0.05000000074505806 m, and 0.15 m is 2.99999996 of its cells) the
      radius and ``ceil(inflation_radius / resolution)`` (the cells the
      inflation reaches) are taken in cells of the decimal the float32
      stands for, so that the map is inflated as the same map read from its
      YAML (the decaying costs, computed at the float32's distances, may
      differ by one where the truncation is that close).
    * Nav2's classic ``InflationLayer`` (every release up to 2025; kept as
      ``LegacyInflationLayer`` since) propagates distances by a breadth-first
      wave, whose distances can only be too long, and which never reaches
      some cells within ``inflation_radius`` (the wave stops at a cell
      farther than that from the obstacle it started from, though another
      is nearer): such cells cost less there (0), and an unknown one under
      ``inflate_unknown`` stays 255 there where it takes its inflated cost
      here (seen on the Willow Garage map).
    * Nav2's refactored ``InflationLayer`` (2026) uses an exact distance
      transform too, in float32, and looks costs up at distances rounded to
      1/100 of a cell: a cost may differ by what the formula changes over
      1/200 of a cell (at most 1 with Nav2's defaults on a 0.05 m grid), and
      a cell whose rounded distance crosses ``robot_radius`` is inscribed in
      one and not the other (``sqrt(2)`` cells reads as 1.41).

    Peak memory about 3 bytes a cell and 40 MiB whatever the radius
    (measured, 4096 x 4096 cells: 84 MiB): the occupied and unknown masks (2)
    and the result (1), and the exact distance transform of a band of about
    2**21 cells (16 bytes a cell, and 3 for the band's masks), which needs no
    rows of its neighbours; a grid much wider than tall adds its transposed
    mask (1 byte a cell).

    Examples
    --------
    >>> from navkit.mapping import OccupancyGrid
    >>> grid = OccupancyGrid.from_occupancy(np.array([[True] + [False] * 5]), resolution=0.1)
    >>> costmap(grid, robot_radius=0.1, inflation_radius=0.4)
    array([[254, 253,  92,  34,  12,   0]], dtype=uint8)
    """
    g = _check_grid(grid)
    insc = bounded_float(robot_radius, "robot_radius", 0.0, RADIUS_LIMIT, "m")
    infl = bounded_float(inflation_radius, "inflation_radius", 0.0, RADIUS_LIMIT, "m")
    if infl < insc:
        raise ValueError(f"inflation_radius ({infl}) must be >= robot_radius ({insc})")
    scale = bounded_float(
        cost_scaling_factor, "cost_scaling_factor", 0.0, SCALING_LIMIT, "1/m", low_open=True
    )
    return inflation_costs(
        g.occupied(),
        g.unknown(),
        g.resolution,
        _inscribed(insc, g.resolution) + CELL_EPS * g.resolution,
        infl,
        scale,
        as_bool(inflate_unknown, "inflate_unknown"),
        as_bool(inflate_around_unknown, "inflate_around_unknown"),
    )


def traversal_costs(
    grid: OccupancyGrid,
    *,
    robot_radius: float = 0.0,
    inflation_radius: float | None = None,
    cost_scaling_factor: float = 10.0,
    cost_weight: float = 4.0,
    unknown_cost: float = math.inf,
    inflate_unknown: bool | None = None,
) -> FloatArray:
    """Per-cell traversal costs of a grid for the grid planners, float64 (rows, cols).

    Built from :func:`costmap`: lethal (254) and inscribed (253) cells are
    ``inf`` (the robot's centre cannot go there), unknown cells (255) cost
    ``unknown_cost``, and a Nav2 cost ``c`` in 0..252 becomes
    ``1 + cost_weight * c / 252``, so free space costs exactly 1. The result
    passes :func:`validate_costs`; its finite values are at most
    ``max(1 + cost_weight, unknown_cost)`` <= 1 + 1e9.

    Parameters
    ----------
    grid : OccupancyGrid
        The map.
    robot_radius : float, default 0.0
        Robot's inscribed radius, m, in [0, 1e6]. 0 treats the robot as a point.
    inflation_radius : float, optional
        Decay distance, m, in [``robot_radius``, 1e6]; defaults to
        ``robot_radius`` (no cost band beyond the rounding to whole cells).
    cost_scaling_factor : float, default 10.0
        Decay rate of the inflation cost, 1/m, in (0, 1e12].
    cost_weight : float, default 4.0
        Extra cost of a cell next to the inscribed zone, in [0, 1e9]. A cell's
        cost is Nav2 Smac Planner 2D's ``1 + cost_travel_multiplier * c / 252``
        with ``cost_travel_multiplier = cost_weight`` (Smac's default is 2);
        4 is within 1 % of NavFn's ``(50 + 0.8 c) / 50`` (its neutral cost 50;
        NavFn truncates ``50 + 0.8 c`` to an integer, 5.02 at ``c = 252`` where
        this gives 5). Both planners charge a move the cost of the cell it
        enters, where navkit's charge the mean of its two cells (see
        :func:`~navkit.planning.astar`).
    unknown_cost : float, default inf
        Cost of unknown cells: ``inf`` (impassable, the default) or a value
        in [1, 1e9] to let planners cross unexplored space.
    inflate_unknown : bool or None, default None
        Whether unknown cells count as obstacles when inflating: True makes
        every cell whose centre lies within ``robot_radius`` of unknown space
        impassable and lets the inflation cost decay from unknown cells as
        from occupied ones, so the robot's *body* keeps clear of space it
        knows nothing about (not only its centre); it needs
        ``unknown_cost=inf``. False inflates occupied cells only (unknown
        cells are then just cells of cost ``unknown_cost``; Nav2's default).
        None (the default) means True when ``unknown_cost`` is inf and False
        otherwise: a robot that may not enter unknown space should not brush
        it either, and one allowed to explore is not kept away from it. This
        is Nav2's ``inflate_around_unknown``, not the ``inflate_unknown``
        parameter of :func:`costmap` (which decides what cost an unknown cell
        takes, not whether it inflates).

    Returns
    -------
    ndarray, shape (rows, cols)
        New float64 costs per unit length: exactly 1 in free space,
        ``1 + cost_weight * c / 252`` for a Nav2 cost ``c`` in 0..252,
        ``unknown_cost`` on unknown cells, ``inf`` on lethal and inscribed ones.

    Raises
    ------
    TypeError
        ``grid`` is not an OccupancyGrid, ``inflate_unknown`` is not a bool or
        None, a number is not a real number (``unknown_cost=True`` included).
    ValueError
        A number outside its range; ``inflate_unknown=True`` with a finite
        ``unknown_cost``.

    Examples
    --------
    >>> from navkit.mapping import OccupancyGrid
    >>> occupied = np.array([[True, False, False, False, False]])
    >>> unknown = np.array([[False, False, False, False, True]])
    >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    >>> traversal_costs(grid, robot_radius=0.1, inflation_radius=0.2).round(3)
    array([[ inf,  inf, 2.46,  inf,  inf]])
    >>> traversal_costs(grid, robot_radius=0.1, inflation_radius=0.2,
    ...                 inflate_unknown=False).round(3)
    array([[ inf,  inf, 2.46, 1.  ,  inf]])
    >>> traversal_costs(grid, unknown_cost=5.0)
    array([[inf,  1.,  1.,  1.,  5.]])
    """
    g = _check_grid(grid)
    insc = bounded_float(robot_radius, "robot_radius", 0.0, RADIUS_LIMIT, "m")
    infl = insc if inflation_radius is None else inflation_radius
    weight = bounded_float(cost_weight, "cost_weight", 0.0, COST_LIMIT)
    unknown = cost_or_inf(unknown_cost, "unknown_cost")
    if inflate_unknown is None:
        around = unknown == math.inf
    else:
        around = as_bool(inflate_unknown, "inflate_unknown")
        if around and unknown != math.inf:
            raise ValueError(
                "inflate_unknown=True treats unknown cells as obstacles, so unknown_cost "
                f"must be inf, got {unknown}"
            )
    cost = costmap(
        g,
        robot_radius=insc,
        inflation_radius=infl,
        cost_scaling_factor=cost_scaling_factor,
        inflate_around_unknown=around,
    )
    # One look-up per cell in a table of the 256 Nav2 costs, each computed as the
    # formula computes it: the result's 8 bytes a cell and no float64 temporaries.
    table = 1.0 + weight * np.arange(256, dtype=np.float64) / (INSCRIBED_INFLATED_OBSTACLE - 1)
    table[INSCRIBED_INFLATED_OBSTACLE:] = math.inf
    table[NO_INFORMATION] = unknown
    out: FloatArray = table[cost]
    return out
