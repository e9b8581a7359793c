"""Behaviour the simulator's docstrings promise that no earlier test pinned down.

Found by mutation testing (session 13): each test here fails on a one-line
change of the source that every other test let pass (a range limit, a
boundary rule, a term of a formula). Expected values are computed from the
docstrings.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.sim import Compass, Imu, Lidar, WheelEncoders, World
from navkit.sim._latency import DelayLine


# ---------------------------------------------------------------------- LiDAR
def test_lidar_range_max_must_exceed_range_min() -> None:
    # range_max lies in (range_min, 1e6]: equal limits leave no valid reading.
    with pytest.raises(ValueError, match="range_min"):
        Lidar(range_min=1.0, range_max=1.0)
    assert Lidar(range_min=1.0, range_max=1.0 + 1e-9).range_max == 1.0 + 1e-9


def test_lidar_dropout_one_is_allowed_and_drops_every_beam() -> None:
    # dropout is a probability in [0, 1]: 1 is a scanner that never returns.
    world = World(box(0.0, 0.0, 4.0, 3.0).exterior)
    scan = Lidar(dropout=1.0, n_beams=8, noise=None).scan(world, (1.0, 1.0, 0.0), seed=3)
    assert scan.ranges.shape == (8,)
    assert np.isnan(scan.ranges).all()
    with pytest.raises(ValueError, match="dropout"):
        Lidar(dropout=math.nextafter(1.0, 2.0))


def test_lidar_angle_jitter_pi_is_the_largest_allowed() -> None:
    # angle_jitter lies in [0, π] rad.
    assert Lidar(angle_jitter=math.pi).angle_jitter == math.pi
    with pytest.raises(ValueError, match="angle_jitter"):
        Lidar(angle_jitter=math.nextafter(math.pi, 4.0))



def test_lidar_fov_beyond_a_turn_is_refused() -> None:
    # fov lies in (0, 2π]; only float rounding of 2π itself is forgiven.
    assert Lidar(fov=2.0 * math.pi).full_circle
    for fov in (2.0 * math.pi + 1e-6, 2.0 * math.pi + 1e-4, 7.0):
        with pytest.raises(ValueError, match="fov"):
            Lidar(fov=fov)


# ------------------------------------------------------------------- sensors
def test_compass_reading_formula_and_draw_range() -> None:
    # degrees(north - yaw + bias + noise × z) mod 360, in [0, 360); z within ±1e6.
    compass = Compass(bias=0.1, noise=0.05, north=0.3)
    expected = math.degrees(0.3 - 1.0 + 0.1 + 0.05 * 0.7) % 360.0
    assert compass.heading_deg(1.0, z=0.7) == pytest.approx(expected, abs=1e-9)
    assert 0.0 <= compass.heading_deg(0.0, z=1e6) < 360.0
    for z in (1e6 * (1.0 + 1e-15), -2e6):
        with pytest.raises(ValueError, match="z"):
            compass.heading_deg(0.0, z=z)


# -------------------------------------------------------------------- latency
def test_delay_line_delivers_every_item_due_within_the_tolerance() -> None:
    # Items are delivered, all of them in order, once due by now + 1e-9 s
    # (inclusive), not a hair earlier.
    line: DelayLine[str] = DelayLine(0.25)
    for k, item in enumerate("abc"):
        line.push_at(0.25 * k + 0.25, item)  # due at 0.25, 0.5, 0.75
    assert line.pop_due(0.25 - 2e-9) == []
    assert line.pop_due(0.5 - 5e-10) == [(0.25, "a"), (0.5, "b")]
    boundary = 0.75 - 1e-9
    assert boundary + 1e-9 == 0.75  # the comparison at exactly now + 1e-9
    assert line.pop_due(boundary) == [(0.75, "c")]
    assert len(line) == 0


def test_sensor_option_ranges() -> None:
    # The documented ranges, at and just beyond their ends.
    assert WheelEncoders(bits=2).ticks(np.array([2.0 * math.pi * 5 / 1024])).tolist() == [1]
    assert WheelEncoders(ticks_per_rev=1.0).ticks_per_rev == 1.0
    assert Imu(gyro_bias=-100.0, accel_bias=-1000.0).gyro_bias == -100.0
    assert Imu(gyro_bias=-0.5).gyro_bias == -0.5
    assert Compass(bias=-math.pi).bias == -math.pi
    bad: list[tuple[Any, dict[str, Any], str]] = [
        (WheelEncoders, {"bits": 1}, "bits"),
        (WheelEncoders, {"ticks_per_rev": 0.999}, "ticks_per_rev"),
        (Imu, {"gyro_bias": -100.5}, "gyro_bias"),
        (Compass, {"bias": math.pi + 0.01}, "bias"),
        (Compass, {"bias": -math.pi - 0.01}, "bias"),
    ]
    for cls, kwargs, name in bad:
        with pytest.raises(ValueError, match=name):
            cls(**kwargs)
