"""The greedy scenario's TurtleBot3 Burger, its map and the greedy-step controller."""

from __future__ import annotations

import functools
import math

import numpy as np

from navkit.errors import NoPathError
from navkit.geometry import Twist2D, angle_diff
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid
from navkit.planning import MapPlanner, Path2D, greedy_step
from navkit.sim import Lidar, Observation, RangeNoise, Robot, WheelEncoders, World

__all__ = [
    "BODY_RADIUS",
    "DRIVE",
    "TICKS_PER_REV",
    "GreedyController",
    "astar_route",
    "burger",
    "tb3_map",
    "tb3_world",
]

#: TurtleBot3 Burger: 0.16 m track, 33 mm wheels, 0.22 m/s and 2.84 rad/s at most
#: (ROBOTIS e-Manual), a round body of 0.105 m radius (its Nav2 robot_radius).
WHEEL_RADIUS = 0.033
DRIVE = DiffDrive(track=0.16, wheel_radius=WHEEL_RADIUS)
BODY_RADIUS = 0.105
MAX_SPEED = 0.22  # m/s
MAX_TURN = 2.84  # rad/s
MAX_WHEEL_ACCELERATION = 30.0  # rad/s²: 1 m/s² at the rim
#: Dynamixel XL430 encoders: 4096 counts per turn.
TICKS_PER_REV = 4096.0
#: The paper's laser: 360 beams out to 1 m (its 21 × 21 grid of 0.1 m cells covers
#: ±1 m); the LDS-01's 0.12 m minimum and 5 Hz. Noise: the LDS-01's datasheet
#: accuracy taken as one standard deviation, ±15 mm below 0.5 m (absolute: 3 %
#: there, as before review 49, understated it near the sensor, 3.6 mm at 0.12 m)
#: and ±5 % beyond.
LIDAR_RANGE = 1.0
LIDAR_RATE = 5.0
LIDAR_NOISE = RangeNoise(limits=(0.5, math.inf), sigma=(0.0, 0.05), absolute=(0.015, 0.0))
#: Default growth of the local grid's returns: cells within this distance of a
#: return are treated as blocked (the body's radius and a margin), so that a line
#: of sight is also a lane the body fits through.
INFLATION = 0.25  # m
#: Heading gain of the waypoint follower, 1/s; the forward speed falls with the
#: heading error (cos) and to zero beyond 60°.
TURN_GAIN = 2.5
STOP_ANGLE = math.radians(60.0)
#: The robot stops when its odometry is this close to the goal, m.
ARRIVE_TOLERANCE = 0.05
#: A* on the full map keeps the body's radius from every occupied or unknown cell.
PLAN_RADIUS = BODY_RADIUS


@functools.lru_cache(maxsize=4)
def tb3_map(path: str) -> OccupancyGrid:
    """The TurtleBot3 world map (``map.yaml``), loaded once per process."""
    return OccupancyGrid.load(path)


@functools.lru_cache(maxsize=4)
def tb3_world(path: str) -> World:
    """The simulated world: the map's occupied and unknown cells block."""
    return World(grid=tb3_map(path))


@functools.lru_cache(maxsize=64)
def astar_route(path: str, start: tuple[float, float], goal: tuple[float, float]) -> Path2D:
    """A*'s path on the full map (8-connected, inflated by the body), world frame."""
    return _planner(path).plan(start, goal)


@functools.lru_cache(maxsize=4)
def _planner(path: str) -> MapPlanner:
    return MapPlanner(tb3_map(path), robot_radius=PLAN_RADIUS)


@functools.lru_cache(maxsize=4)
def burger(noise: bool) -> Robot:
    """The Burger with its 1 m laser and wheel encoders (range noise on or off)."""
    return Robot(
        drive=DRIVE,
        footprint=BODY_RADIUS,
        max_wheel_speed=MAX_SPEED / WHEEL_RADIUS,
        max_wheel_acceleration=MAX_WHEEL_ACCELERATION,
        encoders=WheelEncoders(ticks_per_rev=TICKS_PER_REV, bits=None, rate=30.0),
        lidar=Lidar(
            n_beams=360,
            range_min=0.12,
            range_max=LIDAR_RANGE,
            rate=LIDAR_RATE,
            noise=LIDAR_NOISE if noise else None,
        ),
    )


@functools.lru_cache(maxsize=8)
def _disk(radius_cells: float) -> np.ndarray:
    """Cells within ``radius_cells`` of the centre cell (a dilation structure)."""
    k = math.floor(radius_cells)
    r = np.arange(-k, k + 1)
    out: np.ndarray = (r[:, None] ** 2 + r[None, :] ** 2) <= radius_cells**2
    return out


def inflated_grid(scan: LaserScan, inflation: float) -> tuple[LocalGrid, LocalGrid]:
    """The paper's 21 × 21 grid of a scan and the same grid with returns grown by ``inflation``."""
    grid = scan.to_local_grid()
    if inflation < 0.5 * grid.resolution:
        return grid, grid
    from scipy import ndimage

    structure = _disk(round(inflation / grid.resolution, 9))
    grown = ndimage.binary_dilation(grid.occupied, structure=structure)
    return grid, LocalGrid(grown, resolution=grid.resolution, half_width=grid.half_width)


class GreedyController:
    """The TurtleBot3 greedy planner in the loop: a greedy step per scan, then steer.

    At every new scan the 21 × 21 grid is built and its returns grown by
    ``inflation`` (m); :func:`~navkit.planning.greedy_step` picks the cell to head
    for (on the plain grid if the grown one leaves no line of sight; the robot
    turns on the spot toward the goal if neither does). The cell's centre is
    kept in world coordinates (through the odometry) and steered to until the
    next scan. ``done`` turns true when the odometry is within
    ``ARRIVE_TOLERANCE`` of the goal.

    An ordinary class with ``__slots__``: it keeps the current waypoint and counters.
    """

    __slots__ = (
        "_goal", "_inflation", "_last_stamp", "_waypoint", "arrived_at", "done", "fallbacks",
        "steps",
    )  # fmt: skip

    def __init__(self, goal_xy: tuple[float, float], *, inflation: float = INFLATION) -> None:
        self._goal = goal_xy
        self._inflation = inflation
        self._waypoint: tuple[float, float] | None = None
        self._last_stamp = -math.inf
        self.done = False
        self.arrived_at = math.nan
        self.steps = 0
        self.fallbacks = 0

    def __call__(self, obs: Observation) -> Twist2D:
        est = obs.estimate
        if est is None:  # pragma: no cover - DiffOdometry always has a pose
            return Twist2D(0.0, 0.0, 0.0)
        gx, gy = self._goal
        if math.hypot(gx - est.x, gy - est.y) <= ARRIVE_TOLERANCE:
            self.done = True
            self.arrived_at = obs.t
            return Twist2D(0.0, 0.0, 0.0)
        c, s = math.cos(est.theta), math.sin(est.theta)
        if obs.scan is not None and obs.scan.stamp > self._last_stamp:
            self._last_stamp = obs.scan.stamp
            dx, dy = gx - est.x, gy - est.y
            goal_robot = (c * dx + s * dy, -s * dx + c * dy)
            self._waypoint = self._plan(obs.scan.scan, goal_robot, est.x, est.y, c, s)
        if self._waypoint is None:  # walled in (or before the first scan): face the goal
            err = angle_diff(math.atan2(gy - est.y, gx - est.x), est.theta)
            return Twist2D(0.0, 0.0, _clip(TURN_GAIN * err, MAX_TURN))
        wx, wy = self._waypoint
        err = angle_diff(math.atan2(wy - est.y, wx - est.x), est.theta)
        forward = 0.0 if abs(err) >= STOP_ANGLE else MAX_SPEED * math.cos(err)
        forward = min(forward, math.hypot(gx - est.x, gy - est.y))  # slow down at the goal
        return Twist2D(forward, 0.0, _clip(TURN_GAIN * err, MAX_TURN))

    def _plan(
        self, scan: LaserScan, goal_robot: tuple[float, float], x: float, y: float, c: float,
        s: float,
    ) -> tuple[float, float] | None:  # fmt: skip
        plain, grown = inflated_grid(scan, self._inflation)
        self.steps += 1
        for k, grid in enumerate((grown, plain) if grown is not plain else (plain,)):
            try:
                step = greedy_step(grid, goal_robot)
            except NoPathError:
                continue
            # A fallback is a step planned on the plain grid after the grown one
            # failed (not a grid that failed: a step may fail on both).
            self.fallbacks += k
            px, py = float(step.waypoint_robot_xy[0]), float(step.waypoint_robot_xy[1])
            return x + c * px - s * py, y + s * px + c * py
        return None


def _clip(value: float, limit: float) -> float:
    return min(max(value, -limit), limit)
