"""The three experiments of the indoor-navigation scenario, one trial each.

* :func:`run_localisation` — a tour through the lab's target points on the
  ON-OFF tracker, driven on the EKF (wheel odometry + IMU) estimate; at each
  target the fused and the wheel-only estimates are compared with the truth.
* :func:`run_planning` — Field D* against 8-connected A* on one route.
* :func:`run_tracking` — ON-OFF tracking of one Field D* path on the EKF
  estimate.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence

import numpy as np

from navkit.estimation import DiffOdometry
from navkit.geometry import Pose2D, Twist2D
from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D
from navkit.sim import EncoderReading, Observation, Simulation, Trace, TrackerController
from navkit.sim.scenarios._indoor_nav_lab import (
    PLAN_ROUTES,
    TOUR_START,
    TRACK_PATHS,
    heading_share,
    lab_world,
)
from navkit.sim.scenarios._indoor_nav_mapping import (
    lab_planner,
    plan_between,
    tour_legs,
    track_route,
)
from navkit.sim.scenarios._indoor_nav_robot import (
    CONTROL_RATE,
    DRIVE,
    ENCODER_BITS,
    PHYSICS_RATE,
    SPEED,
    SUCCESS_RADIUS,
    TICKS_PER_REV,
    errors,
    fusion,
    make_robot,
    make_tracker,
)

__all__ = ["run_localisation", "run_planning", "run_tracking"]

#: Planning times: best of this many searches from scratch.
TIMING_REPEATS = 3


class _Tour:
    """Controller: ON-OFF along the tour's legs on the fused estimate; at each target it
    records the true pose and both estimates (wheel odometry fed from the same readings)."""

    def __init__(self, legs: Sequence[Path2D], odometry: DiffOdometry) -> None:
        self.legs = legs
        self.odometry = odometry
        self.tracker = make_tracker()
        self.tracker.set_path(legs[0])
        self.follow = TrackerController(self.tracker, control_rate=CONTROL_RATE)
        self.leg = 0
        self.done = False
        self.fused: list[tuple[float, float, float]] = []
        self.wheels: list[tuple[float, float, float]] = []

    def __call__(self, obs: Observation) -> Twist2D:
        for reading in obs.new:
            if isinstance(reading, EncoderReading):
                self.odometry.update(int(reading.ticks[0]), int(reading.ticks[1]))
        twist = self.follow(obs)
        if self.follow.done and obs.estimate is not None:
            self.fused.append(errors(obs.true_pose, obs.estimate))
            self.wheels.append(errors(obs.true_pose, self.odometry.pose))
            self.leg += 1
            if self.leg == len(self.legs):
                self.done = True
                return Twist2D(0.0, 0.0, 0.0)
            self.tracker.set_path(self.legs[self.leg])
            twist = self.follow(obs)
        return twist


def _mean(rows: list[tuple[float, float, float]], k: int) -> float:
    return float(np.mean([r[k] for r in rows])) if rows else math.nan


def run_localisation(
    seed: int, *, resolution: float, furniture: bool, targets: int, source: str
) -> tuple[dict[str, float], Trace]:
    """Tour the first ``targets`` target points; errors of both estimates at each target.

    Returns the values (mean absolute errors ``wheel_x``, ``wheel_y``,
    ``wheel_heading``, ``fused_x``, ...; ``targets_reached``, ``collisions``,
    ``distance``, ``duration``) and the trace (its estimates: the fused ones).

    Examples
    --------
    >>> values, trace = run_localisation(3, resolution=0.1, furniture=True, targets=1,
    ...                                   source="plan")
    >>> values["targets_reached"], values["fused_heading"] < values["wheel_heading"]
    (1.0, True)
    """
    legs = tour_legs(resolution, furniture, targets, source)
    start = Pose2D(*TOUR_START)
    rng = np.random.default_rng(seed)
    robot = make_robot(rng)
    odometry = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV, bits=ENCODER_BITS,
                            pose=start)  # fmt: skip
    tour = _Tour(legs, odometry)
    length = sum(leg.length for leg in legs)
    sim = Simulation(
        lab_world(furniture), robot, tour, start=start, estimator=fusion(start),
        rate=PHYSICS_RATE, control_rate=CONTROL_RATE, duration=60.0 + 4.0 * length / SPEED,
        seed=rng, stop_at_goal=False,
    )  # fmt: skip
    trace = sim.run()
    values = {
        "targets_reached": float(len(tour.fused)),
        "collisions": float(trace.metrics.collisions),
        "distance": trace.metrics.distance,
        "duration": trace.metrics.duration,
    }
    for name, rows in (("wheel", tour.wheels), ("fused", tour.fused)):
        for k, axis in enumerate(("x", "y", "heading")):
            values[f"{name}_{axis}"] = _mean(rows, k)
    return values, trace


def _timed_plan(
    planner_name: str, resolution: float, furniture: bool, route: int, source: str
) -> Path2D:
    planner = lab_planner(resolution, furniture, planner_name, source)
    start, goal = PLAN_ROUTES[route]
    return plan_between(planner, start, goal)


def _planned_part(points_xy: np.ndarray, grid: OccupancyGrid) -> np.ndarray:
    """A world path's points without :class:`MapPlanner`'s links to its end cells' centres.

    ``MapPlanner`` joins a start or goal off its cell's centre to that centre
    by a short straight link (half a cell diagonal at most): the headings
    compared are the planner's, so a first (last) point whose neighbour is its
    own cell's centre is left out.
    """
    pts = np.asarray(points_xy, dtype=np.float64)
    lo, hi = 0, len(pts)
    for end, inner in ((0, 1), (-1, -2)):
        if hi - lo <= 2:
            break
        centre = grid.cell_to_world(grid.world_to_cell(pts[end][None, :]))[0]
        if np.allclose(pts[inner], centre, rtol=0, atol=1e-9 * grid.resolution) and not (
            np.allclose(pts[end], centre, rtol=0, atol=1e-9 * grid.resolution)
        ):
            lo, hi = (1, hi) if end == 0 else (lo, hi - 1)
    return pts[lo:hi]


def run_planning(
    route: int, *, resolution: float, furniture: bool, source: str
) -> tuple[dict[str, float], dict[str, Path2D]]:
    """Field D* and 8-connected A* on planning route ``route``: length, headings, time.

    Returns values ``{planner}_length`` (m), ``{planner}_off45`` (share of
    segments whose heading is not a multiple of 45°), ``{planner}_expanded``
    and ``{planner}_wall_time`` (s, best of 3 searches from scratch; wall-clock, so
    it varies from run to run) for ``astar`` and ``fdstar``, and the paths.

    Examples
    --------
    >>> values, paths = run_planning(0, resolution=0.1, furniture=True, source="plan")
    >>> values["fdstar_length"] < values["astar_length"], values["astar_off45"]
    (True, 0.0)
    """
    values: dict[str, float] = {}
    paths: dict[str, Path2D] = {}
    for key, name in (("astar", "astar"), ("fdstar", "field_dstar")):
        path = _timed_plan(name, resolution, furniture, route, source)  # warm (compiles once)
        best = math.inf
        for _ in range(TIMING_REPEATS):
            t0 = time.perf_counter()
            _timed_plan(name, resolution, furniture, route, source)
            best = min(best, time.perf_counter() - t0)
        values[f"{key}_length"] = path.length
        grid = lab_planner(resolution, furniture, name, source).grid
        values[f"{key}_off45"] = heading_share(_planned_part(path.points, grid))
        values[f"{key}_expanded"] = float(path.expanded)
        values[f"{key}_wall_time"] = best
        paths[key] = path
    return values, paths


def run_tracking(
    seed: int, path: int, *, resolution: float, furniture: bool, source: str
) -> tuple[dict[str, float], Trace]:
    """ON-OFF tracking of tracking path ``path`` (planned by Field D*) on the EKF estimate.

    Returns values ``tracked`` (1.0 when the tracker finished without a
    collision and the true final position lies within 0.2 m of the goal),
    ``done``, ``collisions``, final true errors ``x``, ``y`` (m) and
    ``heading`` (rad, to the goal heading), ``length`` (m, the plan's),
    ``cross_track_max`` (m) and ``duration`` (s); and the trace.

    Examples
    --------
    >>> values, trace = run_tracking(1, 3, resolution=0.1, furniture=True, source="plan")
    >>> values["tracked"], values["collisions"]
    (1.0, 0.0)
    """
    route = track_route(resolution, furniture, path, source)
    start_t, goal_t = TRACK_PATHS[path]
    start, goal = Pose2D(*start_t), Pose2D(*goal_t)
    rng = np.random.default_rng(seed)
    robot = make_robot(rng)
    tracker = make_tracker()
    tracker.set_path(route, goal_yaw=goal.theta)
    sim = Simulation(
        lab_world(furniture), robot, TrackerController(tracker, control_rate=CONTROL_RATE),
        start=start, goal=goal_t,
        reference_path=route, estimator=fusion(start), rate=PHYSICS_RATE,
        control_rate=CONTROL_RATE, duration=60.0 + 4.0 * route.length / SPEED, seed=rng,
        stop_at_goal=False,
    )  # fmt: skip
    trace = sim.run()
    m = trace.metrics
    final = Pose2D(*(float(v) for v in trace.poses[-1]))
    ex, ey, eth = errors(final, goal)
    done = tracker.done
    tracked = done and m.collisions == 0 and math.hypot(ex, ey) <= SUCCESS_RADIUS
    values = {
        "tracked": float(tracked),
        "done": float(done),
        "collisions": float(m.collisions),
        "x": ex,
        "y": ey,
        "heading": eth,
        "length": route.length,
        "cross_track_max": m.cross_track_max,
        "duration": m.duration,
    }
    return values, trace
