"""User code typed against navkit's public annotations (review 27).

Not collected by pytest (no test_ prefix; only functions, never called):
``tests/test_review27_typing_user_code.py`` runs ``mypy --strict`` on it through
``mypy.api.run``. Each function is a program the docstrings or docs/ describe; an
annotation narrower than the documented input, a result typed ``Any`` or wider than
what can happen, or a callback type a documented callable cannot satisfy fails it.
"""

from __future__ import annotations

import math
from typing import Literal, assert_type

import numpy as np
from numpy.typing import NDArray

from navkit.estimation import MeasurementLog
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import CellPlanner, FieldDStar, MapPlanner
from navkit.sim import (
    Lidar,
    Observation,
    RangeNoise,
    Robot,
    Simulation,
    WheelEncoders,
    World,
    sweep,
    warmup,
)
from navkit.sim.scenarios import Demo


def field_dstar_nodes_follow_continuous(flag: bool) -> None:
    # As OccupancyGrid.world_to_cell: int64 nodes, or float64 node coordinates.
    planner = FieldDStar(np.ones((4, 4)), resolution=0.5, origin=(1.0, 0.0, 0.0))
    assert_type(planner.world_to_node((1.6, 1.2)), NDArray[np.int64])
    assert_type(planner.world_to_node([[1.6, 1.2]], continuous=True), NDArray[np.float64])
    nodes = planner.world_to_node((1.6, 1.2), continuous=flag)
    assert_type(nodes, NDArray[np.int64] | NDArray[np.float64])


def encoder_ticks_of_a_list() -> None:
    ticks = WheelEncoders(ticks_per_rev=1024, bits=16).ticks([0.5 * math.pi, 0.0])
    assert_type(ticks, NDArray[np.int64])


def robot_and_sensors_from_lists() -> None:
    # Documented array_like (and converted): a polygon's vertices, per-wheel errors, a
    # mount pose as (x, y, theta), noise bands as lists or arrays.
    noise = RangeNoise(limits=[3.0, math.inf], sigma=[0.02, 0.05], bias=np.zeros(2))
    lidar = Lidar(mount=(0.1, 0.0, 0.0), noise=noise)
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=[[0.2, 0.0], [-0.1, 0.1], [-0.1, -0.1]],
        wheel_radius_error=[0.01, -0.01],
        lidar=lidar,
    )
    # Read back: always an array of errors; a radius or the polygon's vertices.
    assert_type(robot.wheel_radius_error, NDArray[np.float64])
    assert_type(robot.footprint, float | NDArray[np.float64])
    assert_type(lidar.mount, Pose2D)
    assert_type(noise.sigma, tuple[float, ...])
    Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_radius_error=0.02)


def records_documented_as_array_like() -> None:
    MeasurementLog(
        [0.0], [[0.5, 0.0, 0.0, 0.0]], [[1e-4, 1.0, 1.0, 1.0]], [[True, False, False, False]]
    )
    LocalGrid([[False] * 3] * 3, resolution=0.1, half_width=0.1)


def progress_callbacks_may_return_something() -> None:
    # What a progress bar's update returns is ignored, e.g. a typed tqdm's bool | None.
    def report(done: int, total: int) -> bool | None:
        return done == total

    Demo().run(1, progress=report)
    sweep("demo", trials=1, progress=report)
    warmup(progress=report)


def map_planner_settings_round_trip() -> None:
    old = MapPlanner(OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1))
    assert_type(old.planner, Literal["astar", "field_dstar"] | CellPlanner)
    MapPlanner(OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.1), planner=old.planner)


def simulation_estimator_is_checked() -> None:
    def forward(obs: Observation) -> Twist2D:
        return Twist2D(0.5, 0.0, 0.0)

    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    # Never run: the documented estimators only (an ignore that silences nothing is
    # itself an error under --strict).
    Simulation(World(), robot, forward, start=(0.0, 0.0, 0.0), estimator="fusion")  # type: ignore[arg-type]
