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

from navkit.control import OnOffTracker
from navkit.estimation import DiffOdometry, PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.planning import Path2D
from navkit.sim import (
    Compass,
    EncoderReading,
    Imu,
    Observation,
    Robot,
    Simulation,
    Trace,
    WheelEncoders,
)
from navkit.sim.scenarios._indoor_nav_lab import (
    BODY_RADIUS,
    PLAN_ROUTES,
    TOUR_START,
    TRACK_PATHS,
    heading_share,
    lab_planner,
    lab_world,
    tour_legs,
    track_route,
)

__all__ = [
    "DRIVE",
    "TICKS_PER_REV",
    "make_robot",
    "make_tracker",
    "run_localisation",
    "run_planning",
    "run_tracking",
]

#: The robot: a differential drive, 0.40 m track, 75 mm wheels.
DRIVE = DiffDrive(track=0.40, wheel_radius=0.075)
TICKS_PER_REV = 2048
ENCODER_BITS = 16
PHYSICS_RATE = 100.0  # Hz
CONTROL_RATE = 20.0  # Hz
#: Wheel imperfections: each wheel's true radius is off by N(0, 0.2 %) (after a
#: calibration), and slip takes N(0, 0.5 %) of the rim speed per physics step.
RADIUS_ERROR_SIGMA = 0.002
WHEEL_SLIP = 0.005
#: The 9-DoF IMU: gyro white noise (rad/s), gyro bias spread (rad/s), accelerometer
#: noise (m/s²); its magnetometer heading (the Compass): noise and bias spread (rad).
GYRO_NOISE = 0.005
GYRO_BIAS_SIGMA = 0.0005
ACCEL_NOISE = 0.05
HEADING_NOISE = math.radians(2.0)
HEADING_BIAS_SIGMA = math.radians(0.5)
#: EKF process noise per second for [x, y, θ, v, ω, a]: robot_localization's defaults
#: except the heading's, 1e-4 rad²/s instead of 0.06: the heading follows the turn
#: rate, which the gyro measures, so it needs little noise of its own; with the default
#: the filter follows the magnetometer's noise (about 1.4° mean heading error here).
PROCESS_NOISE = (0.05, 0.05, 1e-4, 0.025, 0.02, 0.01)
#: ON-OFF tracker settings (heading tolerance and goal tolerance are the paper's).
SPEED = 0.3  # m/s
TURN_RATE = 0.6  # rad/s
#: A tracked path ends within this distance of its goal (true position), m.
SUCCESS_RADIUS = 0.2
#: Planning times: best of this many searches from scratch.
TIMING_REPEATS = 3


def make_robot(rng: np.random.Generator) -> Robot:
    """The indoor robot with this trial's wheel errors and sensor biases.

    Examples
    --------
    >>> robot = make_robot(np.random.default_rng(0))
    >>> robot.n_wheels, robot.imu is not None, robot.compass is not None
    (2, True, True)
    """
    radius_error = np.clip(rng.normal(0.0, RADIUS_ERROR_SIGMA, 2), -0.01, 0.01)
    gyro_bias = float(rng.normal(0.0, GYRO_BIAS_SIGMA))
    heading_bias = float(np.clip(rng.normal(0.0, HEADING_BIAS_SIGMA), -0.05, 0.05))
    return Robot(
        drive=DRIVE,
        footprint=BODY_RADIUS,
        max_wheel_speed=12.0,
        max_wheel_acceleration=20.0,
        wheel_slip=WHEEL_SLIP,
        wheel_radius_error=radius_error,
        encoders=WheelEncoders(ticks_per_rev=TICKS_PER_REV, bits=ENCODER_BITS, rate=50.0),
        imu=Imu(gyro_noise=GYRO_NOISE, gyro_bias=gyro_bias, accel_noise=ACCEL_NOISE, rate=50.0),
        compass=Compass(noise=HEADING_NOISE, bias=heading_bias, rate=10.0),
    )


def make_tracker() -> OnOffTracker:
    """The ON-OFF tracker with the scenario's settings.

    Examples
    --------
    >>> make_tracker().speed
    0.3
    """
    return OnOffTracker(speed=SPEED, turn_rate=TURN_RATE, heading_tolerance=math.radians(10.0),
                        goal_tolerance=0.05)  # fmt: skip


def _fusion(start: Pose2D) -> PlanarFusion:
    return PlanarFusion(
        x0=[start.x, start.y, start.theta, 0.0, 0.0, 0.0], process_noise=PROCESS_NOISE, t0=0.0
    )


def _errors(truth: Pose2D, estimate: Pose2D) -> tuple[float, float, float]:
    """Absolute errors in x, y (m) and heading (rad) of an estimate."""
    dth = (estimate.theta - truth.theta + math.pi) % (2.0 * math.pi) - math.pi
    return abs(estimate.x - truth.x), abs(estimate.y - truth.y), abs(dth)


class _Tour:
    """Controller: ON-OFF along the tour's legs on the fused estimate; at each target it
    records the true pose and both estimates (wheel odometry fed from the same readings)."""

    def __init__(self, legs: Sequence[Path2D], odometry: DiffOdometry) -> None:
        self.legs = legs
        self.odometry = odometry
        self.tracker = make_tracker()
        self.tracker.set_path(legs[0])
        self.leg = 0
        self.done = False
        self.fused: list[tuple[float, float, float]] = []
        self.wheels: list[tuple[float, float, float]] = []

    def __call__(self, obs: Observation) -> Twist2D:
        for reading in obs.new:
            if isinstance(reading, EncoderReading):
                self.odometry.update(int(reading.ticks[0]), int(reading.ticks[1]))
        if obs.estimate is None:
            return Twist2D(0.0, 0.0, 0.0)
        twist = self.tracker.step(obs.estimate, 1.0 / CONTROL_RATE)
        if self.tracker.done:
            self.fused.append(_errors(obs.true_pose, obs.estimate))
            self.wheels.append(_errors(obs.true_pose, self.odometry.pose))
            self.leg += 1
            if self.leg == len(self.legs):
                self.done = True
                return Twist2D(0.0, 0.0, 0.0)
            self.tracker.set_path(self.legs[self.leg])
            twist = self.tracker.step(obs.estimate, 1.0 / CONTROL_RATE)
        return twist


def _mean(rows: list[tuple[float, float, float]], k: int) -> float:
    return float(np.mean([r[k] for r in rows])) if rows else math.nan


def run_localisation(
    seed: int, *, resolution: float, furniture: bool, targets: int
) -> tuple[dict[str, float], Trace]:
    """Tour the first ``targets`` target points; errors of both estimates at each target.

    Returns the values (mean absolute errors ``wheel_x``, ``wheel_y``,
    ``wheel_heading``, ``fused_x``, ...; ``targets_reached``, ``collisions``,
    ``distance``, ``duration``) and the trace (its estimates: the fused ones).

    Examples
    --------
    >>> values, trace = run_localisation(3, resolution=0.1, furniture=True, targets=1)
    >>> values["targets_reached"], values["fused_heading"] < values["wheel_heading"]
    (1.0, True)
    """
    legs = tour_legs(resolution, furniture, targets)
    start = Pose2D(*TOUR_START)
    rng = np.random.default_rng(seed)
    robot = make_robot(rng)
    odometry = DiffOdometry(DRIVE, ticks_per_rev=TICKS_PER_REV, encoder_bits=ENCODER_BITS,
                            pose=start)  # fmt: skip
    tour = _Tour(legs, odometry)
    length = sum(leg.length for leg in legs)
    sim = Simulation(
        lab_world(furniture), robot, tour, start=start, estimator=_fusion(start),
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


def _timed_plan(planner_name: str, resolution: float, furniture: bool, route: int) -> Path2D:
    planner = lab_planner(resolution, furniture, planner_name)
    start, goal = PLAN_ROUTES[route]
    return planner.plan(start, goal)


def run_planning(
    route: int, *, resolution: float, furniture: bool
) -> tuple[dict[str, float], dict[str, Path2D]]:
    """Field D* and 8-connected A* on planning route ``route``: length, headings, time.

    Returns values ``{planner}_length`` (m), ``{planner}_off45`` (share of
    segments whose heading is not a multiple of 45°), ``{planner}_expanded``
    and ``{planner}_wall_time`` (s, best of 3 searches from scratch; wall-clock, so
    it varies from run to run) for ``astar`` and ``fdstar``, and the paths.

    Examples
    --------
    >>> values, paths = run_planning(0, resolution=0.1, furniture=True)
    >>> values["fdstar_length"] < values["astar_length"], values["astar_off45"]
    (True, 0.0)
    """
    values: dict[str, float] = {}
    paths: dict[str, Path2D] = {}
    for key, name in (("astar", "astar"), ("fdstar", "field_dstar")):
        path = _timed_plan(name, resolution, furniture, route)  # warm (compiles once)
        best = math.inf
        for _ in range(TIMING_REPEATS):
            t0 = time.perf_counter()
            _timed_plan(name, resolution, furniture, route)
            best = min(best, time.perf_counter() - t0)
        values[f"{key}_length"] = path.length
        values[f"{key}_off45"] = heading_share(path.points)
        values[f"{key}_expanded"] = float(path.expanded)
        values[f"{key}_wall_time"] = best
        paths[key] = path
    return values, paths


class _Follow:
    """Controller: the ON-OFF tracker on the fused estimate."""

    def __init__(self, tracker: OnOffTracker) -> None:
        self.tracker = tracker

    @property
    def done(self) -> bool:
        return bool(self.tracker.done)

    def __call__(self, obs: Observation) -> Twist2D:
        if obs.estimate is None:
            return Twist2D(0.0, 0.0, 0.0)
        twist: Twist2D = self.tracker.step(obs.estimate, 1.0 / CONTROL_RATE)
        return twist


def run_tracking(
    seed: int, path: int, *, resolution: float, furniture: bool
) -> tuple[dict[str, float], Trace]:
    """ON-OFF tracking of tracking path ``path`` (planned by Field D*) on the EKF estimate.

    Returns values ``tracked`` (1.0 when the tracker finished without a
    collision and the true final position lies within 0.2 m of the goal),
    ``done``, ``collisions``, final true errors ``x``, ``y`` (m) and
    ``heading`` (rad, to the goal heading), ``length`` (m, the plan's),
    ``cross_track_max`` (m) and ``duration`` (s); and the trace.

    Examples
    --------
    >>> values, trace = run_tracking(1, 3, resolution=0.1, furniture=True)
    >>> values["tracked"], values["collisions"]
    (1.0, 0.0)
    """
    route = track_route(resolution, furniture, path)
    start_t, goal_t = TRACK_PATHS[path]
    start, goal = Pose2D(*start_t), Pose2D(*goal_t)
    rng = np.random.default_rng(seed)
    robot = make_robot(rng)
    tracker = make_tracker()
    tracker.set_path(route, goal_heading=goal.theta)
    sim = Simulation(
        lab_world(furniture), robot, _Follow(tracker), start=start, goal=goal_t,
        reference_path=route, estimator=_fusion(start), rate=PHYSICS_RATE,
        control_rate=CONTROL_RATE, duration=60.0 + 4.0 * route.length / SPEED, seed=rng,
        stop_at_goal=False,
    )  # fmt: skip
    trace = sim.run()
    m = trace.metrics
    final = Pose2D(*(float(v) for v in trace.poses[-1]))
    ex, ey, eth = _errors(final, goal)
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
