"""The lab's map built from simulated scans, as the paper built it with Hector mapping.

The robot drives a mapping tour (:data:`MAP_TOUR`: through the lab and the side
room, ON-OFF on its EKF estimate, at 0.2 m/s by default) in the simulated lab
(the true floor plan) with its LiDAR; every scan is matched and written into
the map by :class:`~navkit.mapping.ScanMapper`, wheel odometry giving each
scan's guess. The built map's quality is measured as the paper does (the
inside dimensions of the lab and the side room, wall face to wall face) and
against the rasterised floor plan (cell agreement, coverage), and the mapper's
trajectory against the truth.

The maps the other experiments plan on (:func:`lab_map`, :func:`lab_planner`,
:func:`tour_legs`, :func:`track_route`) are either this built map
(``source="scans"``) or the rasterised floor plan (``source="plan"``); the
simulated world is the floor plan either way. Everything is cached per process
and depends only on its arguments (the mapping tour that builds the map runs
with the fixed seed :data:`MAP_SEED`), so every worker builds the same map.
"""

from __future__ import annotations

import copy
import itertools
import math
import threading
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit.estimation import DiffOdometry
from navkit.geometry import Pose2D, Twist2D, angle_diff
from navkit.mapping import OccupancyGrid, ScanMapper
from navkit.planning import MapPlanner, Path2D
from navkit.sim import EncoderReading, Observation, Simulation, Trace, TrackerController
from navkit.sim.scenarios._indoor_nav_lab import (
    MAP_TOUR,
    PLAN_INFLATION_SCANS,
    PLAN_RADIUS,
    PLAN_RADIUS_SCANS,
    ROOM_SPANS,
    TARGETS,
    TOUR_START,
    TRACK_PATHS,
    anchored,
    lab_grid,
    lab_world,
)
from navkit.sim.scenarios._indoor_nav_robot import (
    CONTROL_RATE,
    DRIVE,
    ENCODER_BITS,
    PHYSICS_RATE,
    TICKS_PER_REV,
    fusion,
    make_robot,
    make_tracker,
)

__all__ = [
    "MAPPING_SPEED",
    "MAP_SEED",
    "MAP_SOURCES",
    "SNAP_DISTANCE",
    "TURN_PER_SPEED",
    "MappingRun",
    "lab_map",
    "lab_planner",
    "map_agreement",
    "mapping_tour",
    "mapping_values",
    "plan_between",
    "plan_inflation",
    "room_spans",
    "run_mapping",
    "scan_map",
    "span_key",
    "tour_legs",
    "track_route",
]

#: Where the planning map comes from: built from simulated scans, or the floor plan.
MAP_SOURCES = ("scans", "plan")
#: The mapping tour's speed, m/s (the paper: mapping degrades above 0.2 m/s), and
#: its in-place turn rate per unit of speed (as the tracking runs': 0.6 rad/s at 0.3 m/s).
MAPPING_SPEED = 0.2
TURN_PER_SPEED = 2.0  # (rad/s) / (m/s)
#: Seed of the mapping tour that builds the map every experiment plans on.
MAP_SEED = 0
#: On a built map a start or goal near a wall drawn off its true place may fall in
#: the wall's inflation; it is then joined to the nearest passable cell within this, m.
SNAP_DISTANCE = 0.3


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class MappingRun:
    """One mapping tour: the built map, the trajectories at each scan and the trace.

    Attributes
    ----------
    grid : OccupancyGrid
        The built map (ScanMapper's finest level), in the world frame.
    trajectory, truth, odometry : ndarray, shape (n, 3)
        The mapper's, the true and the wheel-odometry pose at each of the n scans.
    trace : Trace
        The simulated run (true and EKF poses, the scans).
    match_time : float
        Wall-clock time spent matching and writing the scans, s, all together.
    unmatched : int
        Scans whose match could not be made (their pose is the odometry guess).
    speed : float
        The tour's driving speed, m/s.
    """

    grid: OccupancyGrid
    trajectory: FloatArray
    truth: FloatArray
    odometry: FloatArray
    trace: Trace
    match_time: float
    unmatched: int
    speed: float


@lru_cache(maxsize=4)
def mapping_tour(resolution: float, furniture: bool) -> Path2D:
    """The mapping tour's path: Field D* legs on the floor plan between :data:`MAP_TOUR`.

    The operator's route: planned on the floor plan (the operator knows the lab),
    not on the map being built.

    Examples
    --------
    >>> tour = mapping_tour(0.1, True)
    >>> tour.points[0].tolist(), 55.0 < tour.length < 65.0
    ([1.0, 1.0], True)
    """
    planner = lab_planner(resolution, furniture, "field_dstar", "plan")
    legs = [anchored(plan_between(planner, a, b), a, b) for a, b in itertools.pairwise(MAP_TOUR)]
    pts = np.vstack([legs[0].points] + [leg.points[1:] for leg in legs[1:]])
    seg = np.diff(pts, axis=0)
    keep = np.concatenate(([True], np.hypot(seg[:, 0], seg[:, 1]) > 1e-9))
    pts = pts[keep]
    length = sum(leg.length for leg in legs)
    return Path2D(pts, "world", cost=sum(leg.cost for leg in legs), length=length,
                  expanded=sum(leg.expanded for leg in legs))  # fmt: skip


class _MappingDrive:
    """Controller: ON-OFF along the tour on the EKF estimate; wheel odometry fed from the
    encoder readings, its pose kept at each reading's stamp (the mapper's guesses)."""

    def __init__(self, tour: Path2D, speed: float, odometry: DiffOdometry) -> None:
        tracker = make_tracker(speed, TURN_PER_SPEED * speed)
        tracker.set_path(tour)
        self.follow = TrackerController(tracker, control_rate=CONTROL_RATE)
        self.odometry = odometry
        start = odometry.pose
        self.stamps: list[float] = [-math.inf]
        self.poses: list[tuple[float, float, float]] = [(start.x, start.y, start.theta)]

    @property
    def done(self) -> bool:
        return self.follow.done

    def __call__(self, obs: Observation) -> Twist2D:
        for reading in obs.new:
            if isinstance(reading, EncoderReading):
                p = self.odometry.update(int(reading.ticks[0]), int(reading.ticks[1]))
                self.stamps.append(reading.stamp)
                self.poses.append((p.x, p.y, p.theta))
        return self.follow(obs)


def run_mapping(
    seed: int, *, resolution: float, furniture: bool, speed: float, tour: Path2D | None = None
) -> MappingRun:
    """Drive the mapping tour at ``speed`` with the LiDAR and build the map from its scans.

    ``tour`` replaces :func:`mapping_tour` (a route from the tour's start).

    Examples
    --------
    >>> short = Path2D(np.array([[1.0, 1.0], [3.0, 1.5]]), "world", cost=2.06, length=2.06,
    ...                expanded=0)
    >>> run = run_mapping(0, resolution=0.1, furniture=True, speed=0.5, tour=short)
    >>> run.trace.metrics.collisions, run.trajectory.shape[0] == len(run.trace.scans) > 40
    (0, True)
    """
    if tour is None:
        tour = mapping_tour(resolution, furniture)
    start = Pose2D(*TOUR_START)
    rng = np.random.default_rng(seed)
    robot = make_robot(rng, lidar=True)
    odometry = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV, bits=ENCODER_BITS,
                            pose=start)  # fmt: skip
    drive = _MappingDrive(tour, speed, odometry)
    sim = Simulation(
        lab_world(furniture), robot, drive, start=start, estimator=fusion(start),
        rate=PHYSICS_RATE, control_rate=CONTROL_RATE, duration=60.0 + 4.0 * tour.length / speed,
        seed=rng, record_scans=True, stop_at_goal=False,
    )  # fmt: skip
    trace = sim.run()
    stamps = np.array([r.stamp for r in trace.scans])
    # Wheel odometry at each scan: the last encoder reading taken at or before it.
    at = np.searchsorted(np.array(drive.stamps), stamps + 1e-9, side="right") - 1
    odom = np.array(drive.poses, dtype=np.float64)[at].reshape(-1, 3)
    truth = trace.poses[np.searchsorted(trace.times, stamps - 1e-9)].reshape(-1, 3)
    mapper = ScanMapper(resolution=resolution, pose=start)
    unmatched = 0
    t0 = time.perf_counter()
    for reading, guess in zip(trace.scans, odom, strict=True):
        result = mapper.update(reading.scan, odometry=guess)
        unmatched += result.reason not in ("converged", "max_iterations")
    match_time = time.perf_counter() - t0
    return MappingRun(
        grid=mapper.map, trajectory=np.array(mapper.trajectory), truth=truth, odometry=odom,
        trace=trace, match_time=match_time, unmatched=unmatched, speed=speed,
    )  # fmt: skip


@lru_cache(maxsize=4)
def scan_map(resolution: float, furniture: bool, speed: float = MAPPING_SPEED) -> MappingRun:
    """The mapping tour with seed :data:`MAP_SEED`, cached: the map the experiments use.

    Examples
    --------
    >>> scan_map.cache_info().maxsize  # built once per process and arguments
    4
    """
    return run_mapping(MAP_SEED, resolution=resolution, furniture=furniture, speed=speed)


def span_key(name: str) -> str:
    """The value key of a room span: ``"side room width"`` -> ``"side_room_width"``.

    Examples
    --------
    >>> span_key("lab width")
    'lab_width'
    """
    return name.replace(" ", "_")


def room_spans(grid: OccupancyGrid) -> dict[str, float]:
    """The rooms' inside dimensions (:data:`ROOM_SPANS`) measured on a map, m.

    Along each measuring line, from the room's point outwards both ways to the
    first occupied cell; a wall face is taken at the centre of that cell. A
    span is the median over the lines that find both walls (NaN if none does).

    Examples
    --------
    >>> spans = room_spans(lab_grid(0.05, True))
    >>> round(spans["lab width"], 3), round(spans["side room depth"], 3)
    (14.15, 4.3)
    """
    occupied = grid.occupied()
    rows, cols = occupied.shape
    out: dict[str, float] = {}
    for name, (_, axis, lines, inside) in ROOM_SPANS.items():
        found = []
        for c in lines:
            point = (inside, c) if axis == "x" else (c, inside)
            r0, c0 = (int(v) for v in grid.world_to_cell(np.array(point, dtype=np.float64)))
            if not (0 <= r0 < rows and 0 <= c0 < cols) or occupied[r0, c0]:
                continue
            line = occupied[r0, :] if axis == "x" else occupied[:, c0]
            k = c0 if axis == "x" else r0
            below = np.flatnonzero(line[:k])
            above = np.flatnonzero(line[k + 1 :])
            if below.size and above.size:
                found.append((k + 1 + int(above[0]) - int(below[-1])) * grid.resolution)
        out[name] = float(np.median(found)) if found else math.nan
    return out


def map_agreement(grid: OccupancyGrid, truth: OccupancyGrid) -> tuple[float, float]:
    """How a built map agrees with the rasterised floor plan, cell by cell.

    Returns ``(agreement, coverage)``: the share of the plan's cells known on
    the built map (occupied or free) on which both say the same, and the share
    of the plan's free cells the built map has as free.

    Examples
    --------
    >>> plan = lab_grid(0.1, True)
    >>> map_agreement(plan, plan)
    (1.0, 1.0)
    """
    rows, cols = truth.shape
    rr, cc = np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij")
    centres = truth.cell_to_world(np.column_stack((rr.ravel(), cc.ravel())))
    cells = grid.world_to_cell(np.ascontiguousarray(centres))
    inside = (
        (cells[:, 0] >= 0) & (cells[:, 0] < grid.shape[0])
        & (cells[:, 1] >= 0) & (cells[:, 1] < grid.shape[1])
    )  # fmt: skip
    occ = np.zeros(rows * cols, dtype=bool)
    free = np.zeros(rows * cols, dtype=bool)
    occ[inside] = grid.occupied()[cells[inside, 0], cells[inside, 1]]
    free[inside] = grid.free()[cells[inside, 0], cells[inside, 1]]
    known = occ | free
    true_occ = truth.occupied().ravel()
    agreement = float(np.mean(occ[known] == true_occ[known])) if known.any() else math.nan
    true_free = truth.free().ravel()
    coverage = float(np.mean(free[true_free])) if true_free.any() else math.nan
    return agreement, coverage


def _position_errors(poses: FloatArray, truth: FloatArray) -> tuple[float, float, float]:
    """Mean and largest position error (m) and mean absolute heading error (rad)."""
    if poses.shape[0] == 0:
        return math.nan, math.nan, math.nan
    err = np.hypot(poses[:, 0] - truth[:, 0], poses[:, 1] - truth[:, 1])
    dth = np.abs(angle_diff(poses[:, 2], truth[:, 2]))
    return float(err.mean()), float(err.max()), float(dth.mean())


def mapping_values(run: MappingRun, *, resolution: float, furniture: bool) -> dict[str, float]:
    """A mapping tour's figures: room dimensions, cell agreement, trajectory errors.

    Keys: ``speed``, ``scans``, ``distance``, ``collisions``, ``duration``,
    ``unmatched``; for every room span (:func:`span_key`) the measured span (m);
    ``room_error`` (mean absolute error of the four spans, m); ``agreement``,
    ``coverage`` (:func:`map_agreement`); ``trajectory_mean``, ``trajectory_max``
    (m), ``trajectory_heading`` (rad) of the mapper and ``odometry_*`` of the
    wheel odometry at the same scans; ``match_wall_time`` (s per scan, wall clock).

    Examples
    --------
    >>> short = Path2D(np.array([[1.0, 1.0], [3.0, 1.5]]), "world", cost=2.06, length=2.06,
    ...                expanded=0)
    >>> run = run_mapping(0, resolution=0.1, furniture=True, speed=0.5, tour=short)
    >>> values = mapping_values(run, resolution=0.1, furniture=True)
    >>> values["trajectory_mean"] < 0.1, values["agreement"] > 0.8, values["collisions"]
    (True, True, 0.0)
    """
    m = run.trace.metrics
    n = run.trajectory.shape[0]
    values = {
        "speed": run.speed,
        "scans": float(n),
        "distance": m.distance,
        "collisions": float(m.collisions),
        "duration": m.duration,
        "unmatched": float(run.unmatched),
    }
    spans = room_spans(run.grid)
    errors = [abs(spans[name] - spec[0]) for name, spec in ROOM_SPANS.items()]
    values.update({span_key(name): value for name, value in spans.items()})
    values["room_error"] = float(np.mean(errors))
    agreement, coverage = map_agreement(run.grid, lab_grid(resolution, furniture))
    values["agreement"], values["coverage"] = agreement, coverage
    for key, poses in (("trajectory", run.trajectory), ("odometry", run.odometry)):
        mean, worst, heading = _position_errors(poses, run.truth)
        values.update({f"{key}_mean": mean, f"{key}_max": worst, f"{key}_heading": heading})
    values["match_wall_time"] = run.match_time / max(n, 1)
    return values


# ----------------------------------------------------------- maps to plan on
@lru_cache(maxsize=8)
def lab_map(resolution: float, furniture: bool, source: str) -> OccupancyGrid:
    """The map the experiments plan on: built from scans (``"scans"``) or the plan's.

    Examples
    --------
    >>> lab_map(0.1, True, "plan").shape
    (120, 144)
    """
    if source == "scans":
        return scan_map(resolution, furniture).grid
    return lab_grid(resolution, furniture)


def lab_planner(resolution: float, furniture: bool, planner: str, source: str) -> MapPlanner:
    """A :class:`MapPlanner` (``"astar"`` or ``"field_dstar"``) on :func:`lab_map`, cached.

    On the floor plan obstacles are inflated by 0.35 m; on the map built from
    scans by 0.4 m, with costs decaying out to 0.8 m (see
    :data:`PLAN_INFLATION_SCANS`), and unknown space is impassable and inflated too.
    An A* planner is shared by every caller (its :meth:`~MapPlanner.plan` is
    thread-safe); a Field D* one keeps search state, so each thread gets its
    own copy of the cached planner (trials of a sweep on a thread pool plan at
    the same time).

    Examples
    --------
    >>> lab_planner(0.1, False, "astar", "plan").robot_radius
    0.35
    """
    shared = _lab_planner(resolution, furniture, planner, source)
    if planner == "astar":
        return shared
    copies: dict[tuple[float, bool, str], tuple[MapPlanner, MapPlanner]] | None
    copies = getattr(_THREAD_PLANNERS, "copies", None)
    if copies is None:
        copies = _THREAD_PLANNERS.copies = {}
    key = (resolution, furniture, source)
    held = copies.get(key)
    if held is None or held[0] is not shared:  # none yet, or the cache made a new one
        held = copies[key] = (shared, copy.copy(shared))
    return held[1]


# This thread's copies of the cached Field D* planners, by lab_planner's arguments.
_THREAD_PLANNERS = threading.local()


@lru_cache(maxsize=16)
def _lab_planner(resolution: float, furniture: bool, planner: str, source: str) -> MapPlanner:
    """The cached planner :func:`lab_planner` hands out (or copies, for Field D*)."""
    grid = lab_map(resolution, furniture, source)
    radius, inflation = plan_inflation(source)
    if planner == "astar":
        return MapPlanner(grid, robot_radius=radius, inflation_radius=inflation, planner="astar")
    return MapPlanner(grid, robot_radius=radius, inflation_radius=inflation, planner="field_dstar")


def plan_inflation(source: str) -> tuple[float, float]:
    """The planners' ``(robot_radius, inflation_radius)`` on a map source, m.

    Examples
    --------
    >>> plan_inflation("plan"), plan_inflation("scans")
    ((0.35, 0.35), (0.4, 0.8))
    """
    if source == "scans":
        return PLAN_RADIUS_SCANS, PLAN_INFLATION_SCANS
    return PLAN_RADIUS, PLAN_RADIUS


@lru_cache(maxsize=8)
def tour_legs(resolution: float, furniture: bool, targets: int, source: str) -> tuple[Path2D, ...]:
    """Field D* paths from the tour's start through its first ``targets`` targets, cached.

    Examples
    --------
    >>> legs = tour_legs(0.1, True, 2, "plan")
    >>> len(legs), legs[1].points[-1].tolist() == list(TARGETS[1])
    (2, True)
    """
    planner = lab_planner(resolution, furniture, "field_dstar", source)
    points = [TOUR_START[:2], *TARGETS[:targets]]
    pairs = itertools.pairwise(points)
    return tuple(anchored(plan_between(planner, a, b), a, b) for a, b in pairs)


@lru_cache(maxsize=16)
def track_route(resolution: float, furniture: bool, index: int, source: str) -> Path2D:
    """The Field D* path of tracking path ``index``, cached.

    Examples
    --------
    >>> route = track_route(0.1, True, 0, "plan")
    >>> route.points[0].tolist(), route.points[-1].tolist()
    ([1.0, 1.0], [13.4, 2.4])
    """
    start, goal = TRACK_PATHS[index]
    planner = lab_planner(resolution, furniture, "field_dstar", source)
    return anchored(plan_between(planner, start[:2], goal[:2]), start[:2], goal[:2])


def plan_between(
    planner: MapPlanner, start: tuple[float, float], goal: tuple[float, float]
) -> Path2D:
    """``planner.plan(start, goal)``, an end point in an obstacle's inflation first moved out.

    A start or goal on an impassable cell is replaced by the nearest passable
    cell's centre within :data:`SNAP_DISTANCE` (on a built map a wall may be
    drawn that much closer than it is) that a straight step reaches without
    crossing another obstacle than the one the point is in (never through a
    thin wall to its far side), and the path then begins (ends) with that step
    from (to) the given point. Otherwise the plain plan (and the planner's error
    when no such centre is that near).

    Examples
    --------
    >>> planner = lab_planner(0.1, True, "astar", "plan")
    >>> path = plan_between(planner, (1.0, 0.4), (3.0, 1.0))  # (1, 0.4): 0.3 m from the wall
    >>> path.points[0].tolist(), bool(path.length >= math.dist((1.0, 0.4), (3.0, 1.0)))
    ([1.0, 0.4], True)
    """
    a, b = _passable(planner, start), _passable(planner, goal)
    path = planner.plan(a, b)
    if a == start and b == goal:
        return path
    pts = np.vstack([[start]] * (a != start) + [path.points] + [[goal]] * (b != goal))
    extra = math.dist(start, a) + math.dist(b, goal)
    return Path2D(pts, "world", cost=path.cost + extra, length=path.length + extra,
                  expanded=path.expanded)  # fmt: skip


def _passable(planner: MapPlanner, point: tuple[float, float]) -> tuple[float, float]:
    """``point``, or the passable cell centre it is joined to if it is blocked.

    The nearest passable cell centre within :data:`SNAP_DISTANCE` whose straight
    segment from ``point`` touches (a corner included; a cell whose edge ``point``
    lies on, only by entering it) no obstacle cell (occupied,
    or impassable unknown space) but those of the obstacle ``point`` is in: the
    8-connected blob of obstacle cells around its cell, near it. The step may thus
    leave the inflation band and a wall the map draws over the point, but never
    crosses another obstacle: a centre nearer as the crow flies but beyond a thin
    wall is not taken. Ties go to the lowest ``(row, col)``. ``point`` itself if
    no centre qualifies (the planner then says why it is blocked).
    """
    grid, costs = planner.grid, planner.costs
    rows, cols = costs.shape
    r, c = (int(v) for v in grid.world_to_cell(np.array(point, dtype=np.float64)))
    if 0 <= r < rows and 0 <= c < cols and math.isfinite(costs[r, c]):
        return point
    # Every cell a segment to a candidate centre (within k cells) can touch.
    k = math.ceil(SNAP_DISTANCE / grid.resolution)
    r0, r1 = max(r - k - 1, 0), min(r + k + 2, rows)
    c0, c1 = max(c - k - 1, 0), min(c + k + 2, cols)
    if r0 >= r1 or c0 >= c1:
        return point
    window = (slice(r0, r1), slice(c0, c1))
    passable = np.isfinite(costs[window])
    # Blocked cells that are not free on the map: occupied, or unknown (the lab's
    # planners keep unknown_cost=inf); the lab maps are never changed after.
    obstacle = ~passable & ~grid.free()[window]
    if 0 <= r < rows and 0 <= c < cols and obstacle[r - r0, c - c0]:
        from scipy import ndimage

        labels, _ = ndimage.label(obstacle, structure=np.ones((3, 3), dtype=bool))
        obstacle &= labels != labels[r - r0, c - c0]
    rr, cc = np.nonzero(passable)
    rr, cc = rr + r0, cc + c0
    centres = grid.cell_to_world(np.column_stack((rr, cc)))
    dist = np.hypot(centres[:, 0] - point[0], centres[:, 1] - point[1])
    near = dist <= SNAP_DISTANCE
    if not near.any():
        return point
    rr, cc, centres, dist = rr[near], cc[near], centres[near], dist[near]
    q = np.asarray(grid.world_to_cell(np.array(point, dtype=np.float64), continuous=True))
    ob_r, ob_c = np.nonzero(obstacle)
    clear = ~_segments_touch(q, rr, cc, ob_r + r0, ob_c + c0)
    if not clear.any():
        return point
    i = int(np.flatnonzero(clear)[np.argmin(dist[clear])])
    return float(centres[i, 0]), float(centres[i, 1])


def _segments_touch(
    q: FloatArray, rows: IntArray, cols: IntArray, cell_rows: IntArray, cell_cols: IntArray
) -> BoolArray:
    """Whether each segment from ``q`` to a cell centre ``(rows[i], cols[i])`` touches a cell.

    Continuous grid coordinates ``(row, col)``: cell ``(r, c)`` is the closed square
    ``[r - 1/2, r + 1/2] x [c - 1/2, c + 1/2]``, grown by 1e-9 so that a segment
    through a corner is caught whatever the rounding. A cell whose (grown) square
    holds ``q`` itself (``q`` on its edge: a point on a wall's face, as round
    coordinates lie) is touched only by a segment entering its inside (shrunk by
    1e-9), not by one leaving it. Slab clipping of every segment (axis 0) against
    every cell (axis 1).
    """
    graze = 1e-9
    at_q = (np.abs(cell_rows - q[0]) <= 0.5 + graze) & (np.abs(cell_cols - q[1]) <= 0.5 + graze)
    pad = np.where(at_q, -graze, graze)
    enter = np.zeros((rows.size, cell_rows.size))
    leave = np.ones((rows.size, cell_rows.size))
    for origin, ends, cells in ((q[0], rows, cell_rows), (q[1], cols, cell_cols)):
        step = (ends - origin)[:, None]
        low = (cells - 0.5 - pad - origin)[None, :]
        high = (cells + 0.5 + pad - origin)[None, :]
        along = step != 0.0
        safe = np.where(along, step, 1.0)
        # A segment parallel to this axis's slab is inside it for all t or never.
        inside = (low <= 0.0) & (high >= 0.0)
        with np.errstate(over="ignore"):  # a step of 1e-310 cells: +-inf is right
            t_lo, t_hi = low / safe, high / safe
        t_in = np.where(along, np.minimum(t_lo, t_hi), np.where(inside, 0.0, np.inf))
        t_out = np.where(along, np.maximum(t_lo, t_hi), np.where(inside, 1.0, -np.inf))
        enter = np.maximum(enter, t_in)
        leave = np.minimum(leave, t_out)
    touched: BoolArray = np.any(np.where(at_q[None, :], enter < leave, enter <= leave), axis=1)
    return touched
