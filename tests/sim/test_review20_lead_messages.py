"""Messages that say how to fix a rate or a field of view (review 20, a new user's apps)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Imu, Lidar, Robot, Simulation, World


def test_a_sensor_faster_than_the_simulation_names_both_remedies() -> None:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, imu=Imu(rate=100.0))
    with pytest.raises(ValueError, match=r"robot\.imu\.rate \(100 Hz\).*Simulation\(rate=\)"):
        Simulation(World(box(-1.0, -1.0, 1.0, 1.0).exterior), robot, lambda obs: Twist2D(0.0),
                   start=(0.0, 0.0, 0.0), rate=50.0)  # fmt: skip
    # The remedy it names works.
    Simulation(World(box(-1.0, -1.0, 1.0, 1.0).exterior), robot, lambda obs: Twist2D(0.0),
               start=(0.0, 0.0, 0.0), rate=100.0)  # fmt: skip


@given(st.floats(min_value=6.3, max_value=360.0))
def test_a_field_of_view_in_degrees_gets_the_conversion(degrees: float) -> None:
    with pytest.raises(ValueError, match=r"degrees\? pass math\.radians") as caught:
        Lidar(fov=degrees)
    converted = float(str(caught.value).rsplit("math.radians(", 1)[1].rstrip(")"))
    assert Lidar(fov=math.radians(converted)).fov == pytest.approx(math.radians(degrees), rel=1e-5)


def test_a_field_of_view_beyond_any_angle_in_degrees_gets_no_hint() -> None:
    with pytest.raises(ValueError, match=r"fov must lie in \(0, 2π\] rad, got 400\.0$"):
        Lidar(fov=400.0)
