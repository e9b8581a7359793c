"""The demo's closed loop: plan with A*, track the fused estimate, guard with the LiDAR."""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import FloatArray
from navkit.control import RegulatedPurePursuit
from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import MapPlanner, Path2D
from navkit.sim import (
    Imu,
    Lidar,
    Observation,
    Robot,
    Simulation,
    Trace,
    TrackerController,
    WheelEncoders,
    World,
)
from navkit.sim.scenarios._demo_maps import OFFICE_TOUR, WILLOW_TOUR, office_grid

__all__ = ["BODY_RADIUS", "PLAN_RADIUS", "Clearance", "Leg", "Setup", "run_leg", "setup"]

#: The robot: a TurtleBot-sized differential drive (0.3 m track, 0.05 m wheels),
#: 0.2 m body radius; the planner keeps its centre 0.3 m from walls and
#: unknown space, and prefers the middle of corridors (costs decay to 0.8 m).
DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)
BODY_RADIUS = 0.2
PLAN_RADIUS = 0.3
INFLATION_RADIUS = 0.8
MAX_SPEED = 0.5  # m/s
PHYSICS_RATE = 50.0  # Hz
CONTROL_RATE = 20.0  # Hz
#: The leg is reached when the true position comes within this of the goal; the
#: tracker stops when its estimate is within ``GOAL_TOLERANCE``, the run when the
#: tracker stops.
GOAL_RADIUS = 0.25  # m
GOAL_TOLERANCE = 0.05  # m
#: LiDAR guard: the forward speed is scaled down linearly from full at
#: ``SLOW_GAP`` of free space ahead of the body to zero at ``STOP_GAP``.
SLOW_GAP, STOP_GAP = 0.5, 0.1  # m
OFFICE_LABEL = "synthetic office (24 x 14 m, built in code)"
WILLOW_LABEL = "Willow Garage office map"


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Setup:
    """A map, its simulated world and planner, and the tour's waypoints."""

    label: str
    grid: OccupancyGrid
    world: World
    planner: MapPlanner
    tour: tuple[tuple[float, float], ...]
    clearance: Clearance


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Leg:
    """One leg of the tour: its plan, how long planning took, and the run."""

    route: Path2D
    plan_time: float
    trace: Trace


class Clearance:
    """Distance (m) from a world point to the nearest occupied cell centre, for the tracker.

    What ``RegulatedPurePursuit(clearance=grid)`` computes from a grid, but
    once per map rather than once per tracker: the distance transform of a
    large map costs more than a short trial. Outside the map: ``inf``.
    """

    __slots__ = ("_distance", "_grid")

    def __init__(self, grid: OccupancyGrid) -> None:
        self._distance: FloatArray = grid.obstacle_distance()
        self._grid = grid

    def __call__(self, x: float, y: float) -> float:
        row, col = self._grid.world_to_cell(np.array([x, y]))
        rows, cols = self._distance.shape
        return float(self._distance[row, col]) if 0 <= row < rows and 0 <= col < cols else math.inf


@functools.lru_cache(maxsize=4)
def setup(map_path: str | None) -> Setup:
    """The map of ``map_path`` (None: the synthetic office), built once per process."""
    if map_path is None:
        grid, tour, label = office_grid(), OFFICE_TOUR, OFFICE_LABEL
    else:
        grid, tour, label = OccupancyGrid.load(map_path), WILLOW_TOUR, WILLOW_LABEL
    planner = MapPlanner(grid, robot_radius=PLAN_RADIUS, inflation_radius=INFLATION_RADIUS)
    planner.plan(tour[0], tour[1])  # loads the compiled search, so plan times are the search's
    return Setup(label, grid, World(grid=grid), planner, tour, Clearance(grid))


def robot() -> Robot:
    """The simulated robot: wheel slip, a 0.5 % wheel-radius error and noisy sensors."""
    return Robot(
        drive=DRIVE,
        footprint=BODY_RADIUS,
        max_wheel_speed=20.0,  # rad/s: 1 m/s
        max_wheel_acceleration=40.0,  # rad/s²: 2 m/s²
        wheel_slip=0.01,
        wheel_radius_error=0.005,
        encoders=WheelEncoders(ticks_per_rev=4096.0, rate=50.0),
        lidar=Lidar(n_beams=360, range_max=8.0, rate=10.0),  # the default range noise
        imu=Imu(gyro_noise=0.005, accel_noise=0.05, rate=50.0),
    )


def gap_ahead(scan: LaserScan, half_width: float) -> float:
    """Free distance ahead of a round body (m) in a scan from its centre.

    Beams pointing forward whose end lies within ``half_width`` of the
    heading line; ``inf`` when none hits.
    """
    ranges = scan.ranges
    angles = scan.angles()
    ok = np.isfinite(ranges) & (np.abs(angles) < 0.5 * math.pi)
    ahead = ranges[ok] * np.cos(angles[ok])
    beside = np.abs(ranges[ok] * np.sin(angles[ok]))
    hits = ahead[beside < half_width]
    return float(hits.min()) - BODY_RADIUS if hits.size else math.inf


class Driver:
    """Controller: Regulated Pure Pursuit on the estimated pose, slowed by the LiDAR.

    The tracker never sees the true pose: it steers on the estimator's. When
    the latest scan shows an obstacle close ahead of the body the forward
    speed is scaled down (to zero at ``STOP_GAP``).
    """

    __slots__ = ("_follow",)

    def __init__(self, tracker: RegulatedPurePursuit) -> None:
        self._follow = TrackerController(tracker, control_rate=CONTROL_RATE)

    @property
    def done(self) -> bool:
        return self._follow.done

    def __call__(self, obs: Observation) -> Twist2D:
        twist = self._follow(obs)
        if obs.scan is not None and twist.vx > 0.0:
            gap = gap_ahead(obs.scan.scan, BODY_RADIUS + 0.05)
            scale = min(max((gap - STOP_GAP) / (SLOW_GAP - STOP_GAP), 0.0), 1.0)
            if scale < 1.0:
                twist = Twist2D(twist.vx * scale, twist.vy, twist.omega)
        return twist


def _heading(points: FloatArray) -> float:
    """Direction of a path's start: towards its first point 0.2 m or more away."""
    far = np.nonzero(np.hypot(*(points - points[0]).T) >= 0.2)[0]
    step = points[far[0] if far.size else -1] - points[0]
    return math.atan2(float(step[1]), float(step[0])) if np.any(step) else 0.0


def run_leg(scene: Setup, index: int, *, seed: int, duration: float) -> Leg:
    """Plan leg ``index`` of the tour, then drive it on the fused estimate.

    Parameters
    ----------
    scene : Setup
        The map, world, planner and tour.
    index : int
        The leg: from waypoint ``index`` to waypoint ``index + 1``.
    seed : int
        The simulation's seed (sensor noise, wheel slip).
    duration : float
        Longest simulated time, s.

    Returns
    -------
    Leg
        The route, the planning time (s, wall clock) and the trace.
    """
    start_xy, goal_xy = scene.tour[index], scene.tour[index + 1]
    began = time.perf_counter()
    route = scene.planner.plan(start_xy, goal_xy)
    plan_time = time.perf_counter() - began
    heading = _heading(route.points)
    end = route.points[-1]
    tracker = RegulatedPurePursuit(
        max_speed=MAX_SPEED,
        lookahead_time=1.0,
        clearance=scene.clearance,
        goal_tolerance=GOAL_TOLERANCE,
    )
    tracker.set_path(route)
    x, y = float(route.points[0, 0]), float(route.points[0, 1])
    fusion = PlanarFusion(x0=[x, y, heading, 0.0, 0.0, 0.0], t0=0.0)
    trace = Simulation(
        scene.world, robot(), Driver(tracker), start=(x, y, heading), goal=end,
        goal_tolerance=GOAL_RADIUS, reference_path=route, estimator=fusion, rate=PHYSICS_RATE,
        control_rate=CONTROL_RATE, duration=duration, seed=seed, record_scans=True,
        stop_at_goal=False,
    ).run()  # fmt: skip
    return Leg(route, plan_time, trace)
