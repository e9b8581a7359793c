"""The omni-apf scenario's robot, world and controller (built per process, cached)."""

from __future__ import annotations

import functools
import math

import numpy as np
from shapely.geometry import Polygon, box

from navkit._shared.types import FloatArray
from navkit.control import limit_velocity_change
from navkit.geometry import Twist2D, angle_diff
from navkit.kinematics import OmniDrive
from navkit.planning import PiecewiseAttraction, piecewise_repulsive_force_from_scan
from navkit.sim import Compass, Lidar, Observation, RangeNoise, Robot, WheelEncoders, World

__all__ = [
    "ARRIVE_TOLERANCE",
    "BODY_RADIUS",
    "DRIVE",
    "ApfController",
    "obstacle_boxes",
    "omni_robot",
    "omni_world",
]

#: The robot: three omni wheels at 30°, 150° and 270° (the paper's Y layout),
#: 5 cm wheels 0.2 m from the centre, a round body of 0.22 m radius.
DRIVE = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
BODY_RADIUS = 0.22
MAX_WHEEL_SPEED = 12.0  # rad/s: 0.6 m/s at the rim
MAX_WHEEL_ACCELERATION = 20.0  # rad/s²: 1 m/s² at the rim

#: The paper's measured delivery delays: 0.50 s for the LiDAR topic, 0.08 s for
#: odometry (here the wheel encoders and the compass, which make up the odometry).
LIDAR_LATENCY = 0.50
ODOMETRY_LATENCY = 0.08
#: Sensor noise of the noisy runs: the paper's RPLIDAR range errors (RangeNoise's
#: default), a compass with 1° standard deviation (the paper does not give one) and
#: a little random wheel slip (the odometry then drifts as on a real floor).
COMPASS_NOISE = math.radians(1.0)
WHEEL_SLIP = 0.005

#: Field parameters (the paper's symbols). Attraction: α(d - r) in the linear zone
#: of width s, α·s = MAX_SPEED beyond; repulsion of every beam: δ inside r,
#: β(s + r - ρ) in the linear zone, 0 beyond.
MAX_SPEED = 0.35  # m/s
ALPHA = 1.0  # 1/s
GOAL_RADIUS = 0.005  # m
ATTRACTION_SPREAD = MAX_SPEED / ALPHA  # m
REPULSION_DELTA = 0.05  # m/s per beam
REPULSION_BETA = 0.03  # 1/s per beam
OBSTACLE_RADIUS = 0.3  # m: body radius and a margin
REPULSION_SPREAD = 0.6  # m
MAX_ACCEL = 0.5  # m/s²
MAX_DECEL = 1.0  # m/s²
HEADING_GAIN = 2.0  # 1/s
MAX_OMEGA = 1.0  # rad/s
#: The robot stops when its odometry says it is this close to the target, m,
#: or when the field has come to rest (the commanded speed below SETTLE_SPEED)
#: within SETTLE_RADIUS of it: a box within the repulsion's reach of the target
#: makes an equilibrium a little short of it.
ARRIVE_TOLERANCE = 0.015
SETTLE_RADIUS = 0.04
SETTLE_SPEED = 0.002  # m/s

#: Where the obstacle stands on each route: 1.5 m along it, its centre 0.2 m to
#: the side of the straight line, a 0.3 m square box: a robot driving straight
#: would hit it (its body sweeps 0.22 m to each side of the line).
OBSTACLE_ALONG = 1.5
OBSTACLE_OFFSET = 0.2
OBSTACLE_HALF = 0.15
#: Half the side of the square room around the routes, m.
ROOM_HALF = 4.5


def obstacle_boxes(targets: tuple[tuple[float, float], ...]) -> tuple[Polygon, ...]:
    """One box on the straight route from the origin to each target."""
    out = []
    for tx, ty in targets:
        d = math.hypot(tx, ty)
        ux, uy = tx / d, ty / d
        along = min(OBSTACLE_ALONG, 0.5 * d)
        cx = along * ux - OBSTACLE_OFFSET * uy
        cy = along * uy + OBSTACLE_OFFSET * ux
        h = OBSTACLE_HALF
        out.append(box(cx - h, cy - h, cx + h, cy + h))
    return tuple(out)


@functools.lru_cache(maxsize=16)
def omni_world(targets: tuple[tuple[float, float], ...], obstacles: bool) -> World:
    """A square room with, when ``obstacles``, a box on the way to every target."""
    reach = max(max(abs(x), abs(y)) for x, y in targets)
    half = max(ROOM_HALF, reach + 1.5)
    items: list[object] = [box(-half, -half, half, half).exterior]
    if obstacles:
        items.extend(obstacle_boxes(targets))
    return World(items)


@functools.lru_cache(maxsize=8)
def omni_robot(noise: bool, latency: bool) -> Robot:
    """The paper's robot with its sensors (noise and latencies on or off)."""
    lidar_latency = LIDAR_LATENCY if latency else 0.0
    odo_latency = ODOMETRY_LATENCY if latency else 0.0
    return Robot(
        drive=DRIVE,
        footprint=BODY_RADIUS,
        max_wheel_speed=MAX_WHEEL_SPEED,
        max_wheel_acceleration=MAX_WHEEL_ACCELERATION,
        wheel_slip=WHEEL_SLIP if noise else 0.0,
        encoders=WheelEncoders(ticks_per_rev=1024.0, bits=16, rate=50.0, latency=odo_latency),
        lidar=Lidar(
            n_beams=360,
            range_min=0.15,
            range_max=12.0,
            rate=10.0,
            latency=lidar_latency,
            noise=RangeNoise() if noise else None,
        ),
        compass=Compass(noise=COMPASS_NOISE if noise else 0.0, rate=20.0, latency=odo_latency),
    )


class ApfController:
    """The paper's motion law on the odometry estimate and the (late) LiDAR scan.

    The world-frame velocity is the piecewise attraction toward the target plus
    the piecewise repulsion of every LiDAR beam (rotated into the world by the
    compass-fused heading), clipped to ``MAX_SPEED`` and rate-limited; the heading
    is held at 0 by a proportional turn rate. ``done`` turns true when the
    odometry puts the robot within ``ARRIVE_TOLERANCE`` of the target, or
    within ``SETTLE_RADIUS`` with the field at rest.

    An ordinary class with ``__slots__``: it keeps the previous velocity.
    """

    __slots__ = ("_attraction", "_dt", "_goal", "_velocity", "arrived_at", "done")

    def __init__(self, goal_xy: tuple[float, float], *, control_rate: float) -> None:
        self._goal = np.array(goal_xy, dtype=np.float64)
        self._attraction = PiecewiseAttraction(
            self._goal, alpha=ALPHA, goal_radius=GOAL_RADIUS, spread=ATTRACTION_SPREAD
        )
        self._dt = 1.0 / control_rate
        self._velocity: FloatArray = np.zeros(2)
        self.done = False
        self.arrived_at = math.nan

    def __call__(self, obs: Observation) -> Twist2D:
        est = obs.estimate
        if est is None:  # pragma: no cover - OmniOdometry always has a pose
            return Twist2D(0.0, 0.0, 0.0)
        dist = math.hypot(est.x - self._goal[0], est.y - self._goal[1])
        if dist <= ARRIVE_TOLERANCE:
            return self._stop(obs.t)
        here = np.array([[est.x, est.y]])
        want = self._attraction.force(here)[0]
        c, s = math.cos(est.theta), math.sin(est.theta)
        if obs.scan is not None:
            fx, fy = piecewise_repulsive_force_from_scan(
                obs.scan.scan,
                delta=REPULSION_DELTA,
                beta=REPULSION_BETA,
                obstacle_radius=OBSTACLE_RADIUS,
                spread=REPULSION_SPREAD,
            )
            want = want + np.array([c * fx - s * fy, s * fx + c * fy])
        speed = math.hypot(want[0], want[1])
        if speed > MAX_SPEED:
            want = want * (MAX_SPEED / speed)
        # The time this command is held (whole physics steps); the nominal period
        # only for an observation made outside a Simulation.
        dt = self._dt if obs.dt is None else obs.dt
        v = limit_velocity_change(
            self._velocity, want, max_accel=MAX_ACCEL, max_decel=MAX_DECEL, dt=dt
        )
        self._velocity = v
        if dist <= SETTLE_RADIUS and math.hypot(v[0], v[1]) < SETTLE_SPEED:
            return self._stop(obs.t)
        omega = min(max(HEADING_GAIN * angle_diff(0.0, est.theta), -MAX_OMEGA), MAX_OMEGA)
        # World-frame velocity into the robot frame.
        return Twist2D(c * v[0] + s * v[1], -s * v[0] + c * v[1], omega)

    def _stop(self, t: float) -> Twist2D:
        self.done = True
        self.arrived_at = t
        return Twist2D(0.0, 0.0, 0.0)
