"""User code typed against navkit's public annotations (review 50).

Not collected by pytest: ``tests/test_review50_typing_user_code.py`` runs ``mypy
--strict`` on it. ``assert_type`` checks what a user's checker infers; a
``# type: ignore[...]`` marks a call the annotations must refuse (``--strict``
reports an ignore that is not needed, so each one is checked as well).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal, assert_type

import numpy as np
from numpy.typing import NDArray
from rosbags.typesys.store import Typestore

from navkit.estimation import CompassCalibration, FusionStatus, UpdateResult, compass_to_yaw
from navkit.geometry import Pose2D, angle_diff, wrap_angle
from navkit.kinematics import tick_delta, ticks_to_distance
from navkit.mapping import MapMode, OccupancyGrid, ScanMatchReason, ScanMatchResult
from navkit.mapping.io import grid_from_msg, grid_to_msg_fields, scan_from_msg, write_map
from navkit.sim import EndReason, Event
from navkit.sim.scenarios import IndoorNav


def numpy_scalars_give_floats() -> None:
    # A NumPy scalar (a reading from an array, a float32 driver value) is one number:
    # the call returns a Python float, as for a float (was float | NDArray).
    reading = np.float32(3.5)
    assert_type(wrap_angle(reading), float)
    assert_type(wrap_angle(np.int64(7)), float)
    assert_type(angle_diff(reading, 0.5), float)
    assert_type(angle_diff(np.float16(1.0), np.int32(2)), float)
    assert_type(ticks_to_distance(np.int64(1024), ticks_per_rev=2048, wheel_radius=0.1), float)
    assert_type(compass_to_yaw(reading), float)
    assert_type(CompassCalibration()(np.float32(90.0)), float)
    assert_type(tick_delta(np.uint16(65535), np.uint16(2), bits=16), int)
    # Python numbers and lists as before.
    assert_type(wrap_angle(4), float)
    assert_type(wrap_angle([1.0, 7.0]), NDArray[np.float64])
    headings: list[float] = [math.pi, 4.0]
    assert_type(angle_diff(headings, 0.0), NDArray[np.float64])


def arrays_stay_a_union(angles: NDArray[np.float64]) -> None:
    # A 0-d array gives a float: NumPy's annotations do not say an array's number of
    # dimensions (np.array's is tuple[Any, ...]), so an array gives the union.
    assert_type(wrap_angle(angles), float | NDArray[np.float64])


def map_modes_are_the_literal(grid: OccupancyGrid, folder: Path) -> None:
    # "mode : {"trinary", "scale"}": a misspelt mode is a type error, not a run-time one.
    write_map(grid, folder / "a.yaml", mode="scale")
    grid.save(folder / "b.yaml", mode="trinary")
    grid_to_msg_fields(grid, mode="trinary")
    chosen: MapMode = "scale"
    write_map(grid, folder / "c.yaml", mode=chosen)
    write_map(grid, folder / "d.yaml", mode="pgm")  # type: ignore[arg-type]
    grid.save(folder / "e.yaml", mode="trinay")  # type: ignore[arg-type]
    grid_to_msg_fields(grid, mode="raw")  # type: ignore[arg-type]


def map_source_is_the_literal() -> None:
    scenario = IndoorNav(map_source="plan")
    assert_type(scenario.map_source, Literal["scans", "plan"])
    IndoorNav(map_source="scan")  # type: ignore[arg-type]


def event_kinds_are_end_reasons(kind: str) -> None:
    # Event.kind is checked to be one of EndReason on construction, as Metrics.reason.
    event = Event(1.5, "collision", "touched")
    assert_type(event.kind, EndReason)
    if event.kind == "colision":  # type: ignore[comparison-overlap]
        pass
    Event(1.5, kind, "built from any str, checked at run time")


def scan_match_reasons_are_the_literal() -> None:
    # The constructor takes the pose as three numbers and the covariance as array_like
    # (it converts both); reason is one of ScanMatchReason afterwards.
    result = ScanMatchResult(
        (1.0, 2.0, 0.0), [[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]], 4, 0.9, True, "converged"
    )
    assert_type(result.reason, ScanMatchReason)
    assert_type(result.pose, Pose2D)
    if result.reason == "max iterations":  # type: ignore[comparison-overlap]
        pass


def update_status_may_be_none(result: UpdateResult) -> None:
    # None for a rejected result built without a status: the annotation keeps None.
    assert_type(result.status, FusionStatus | None)


def messages_from_a_bag(typestore: Typestore, raw: bytes) -> None:
    # rosbags types what it deserialises as object: the message arguments stay
    # unconstrained (a Protocol of the fields read would refuse these calls).
    scan_from_msg(typestore.deserialize_cdr(raw, "sensor_msgs/msg/LaserScan"))
    grid_from_msg(typestore.deserialize_ros1(raw, "nav_msgs/msg/OccupancyGrid"))
