"""A fast 2-D simulator that closes the loop: world, LiDAR, wheels, compass, IMU.

* :class:`World`: static obstacles from shapely geometry (polygons are solid,
  lines are walls), exact :class:`Circle` s, the occupied cells of an
  :class:`~navkit.mapping.OccupancyGrid` (any map_server map), and
  :class:`MovingObstacle` s on constant-velocity or scripted paths.
* :class:`Lidar`: exact ray casting (numba; a uniform grid over the edges,
  cell traversal of occupancy grids) with range noise by distance band
  (:class:`RangeNoise`, the omnidirectional robot paper's by default), angular
  jitter, dropouts and REP 117 readings, returned as
  :class:`~navkit.mapping.LaserScan`.
* :class:`Robot`: an ``OmniDrive`` or ``DiffDrive`` body with wheel-speed
  saturation, acceleration limits, slip, wheel-radius error, a circular or
  polygonal footprint, :class:`WheelEncoders`, a :class:`Compass` and an
  :class:`Imu`; every sensor has a rate and a delivery latency.
* :class:`Simulation`: the loop at a fixed rate; a controller receives an
  :class:`Observation` (time-stamped readings, an :class:`Estimator`'s pose)
  and returns a ``Twist2D``; seeded, so runs are reproducible. It returns a
  :class:`Trace` with :class:`Metrics` and :class:`Event` s.

Units are SI (m, rad, s, Hz); poses are ``Pose2D`` or ``[x, y, theta]``.

Examples
--------
>>> import math
>>> from shapely.geometry import box
>>> from navkit.geometry import Twist2D
>>> from navkit.kinematics import DiffDrive
>>> world = World([box(0.0, 0.0, 6.0, 4.0).exterior, Circle((4.0, 2.0), 0.3)])
>>> scan = Lidar(n_beams=8, noise=None).scan(world, (1.0, 2.0, 0.0))
>>> float(scan.ranges[4])  # straight ahead, to the circle
2.7
>>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,
...               lidar=Lidar(), max_wheel_acceleration=40.0)
>>> def forward(obs: Observation) -> Twist2D:
...     return Twist2D(0.4, 0.0, 0.0)
>>> trace = Simulation(world, robot, forward, start=(1.0, 1.0, 0.0), goal=(3.0, 1.0)).run()
>>> trace.metrics.reached, trace.metrics.collisions
(True, 0)
"""

from navkit.sim._adapters import Tracker, TrackerController
from navkit.sim._estimators import Estimator
from navkit.sim._lidar import Lidar
from navkit.sim._noise import RangeNoise
from navkit.sim._robot import Robot
from navkit.sim._scenario import (
    Scenario,
    ScenarioResult,
    Scene,
    Table,
    Trial,
    TrialResult,
    trial_seed,
)
from navkit.sim._sensors import (
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Reading,
    ScanReading,
    WheelEncoders,
)
from navkit.sim._simulation import Controller, Observation, Simulation
from navkit.sim._sweep import sweep
from navkit.sim._trace import EndReason, Event, Metrics, Trace
from navkit.sim._warmup import WARMUP_STEPS, WarmupReport, WarmupStep, warmup
from navkit.sim._world import Circle, MovingObstacle, World

__all__ = [
    "WARMUP_STEPS",
    "Circle",
    "Compass",
    "CompassReading",
    "Controller",
    "EncoderReading",
    "EndReason",
    "Estimator",
    "Event",
    "Imu",
    "ImuReading",
    "Lidar",
    "Metrics",
    "MovingObstacle",
    "Observation",
    "RangeNoise",
    "Reading",
    "Robot",
    "ScanReading",
    "Scenario",
    "ScenarioResult",
    "Scene",
    "Simulation",
    "Table",
    "Trace",
    "Tracker",
    "TrackerController",
    "Trial",
    "TrialResult",
    "WarmupReport",
    "WarmupStep",
    "WheelEncoders",
    "World",
    "sweep",
    "trial_seed",
    "warmup",
]
