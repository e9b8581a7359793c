"""Sensor parameters at and beyond their ranges (review 34, mutation testing of _sensors).

Mutants that the sensor tests let live: an ``Imu`` whose ``latency`` went
unchecked, ``_bounded`` refusing the upper end of a closed range (``bias = π``),
``WheelEncoders.ticks`` accepting wheel angles beyond ±1e9 rad, and
``real_float`` refusing a NumPy NaN or infinity where the caller allows one.
The expectations are the docstrings' ranges, ends included.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.sim import Compass, Imu, WheelEncoders
from navkit.sim._sensors import real_float


def test_the_ends_of_each_closed_range_are_accepted() -> None:
    assert Compass(bias=math.pi).bias == math.pi
    assert Compass(bias=-math.pi).bias == -math.pi
    assert Compass(north=2.0 * math.pi).north == 2.0 * math.pi
    assert Compass(noise=0.0).noise == 0.0
    assert WheelEncoders(ticks_per_rev=1.0).ticks_per_rev == 1.0
    assert WheelEncoders(ticks_per_rev=1e9).ticks_per_rev == 1e9


@pytest.mark.parametrize("bias", [math.nextafter(math.pi, 4.0), -math.nextafter(math.pi, 4.0)])
def test_just_beyond_a_range_is_refused(bias: float) -> None:
    with pytest.raises(ValueError, match="bias"):
        Compass(bias=bias)


@pytest.mark.parametrize("latency", [-0.01, math.nan, 2e4])
def test_imu_latency_is_checked(latency: float) -> None:
    with pytest.raises(ValueError, match="latency"):
        Imu(latency=latency)


def test_imu_rate_is_checked() -> None:
    with pytest.raises(ValueError, match="rate"):
        Imu(rate=0.0)


@pytest.mark.parametrize("angle", [1.5e9, -2e9])
def test_wheel_angles_beyond_1e9_rad_are_refused(angle: float) -> None:
    enc = WheelEncoders()
    with pytest.raises(ValueError, match="wheel_angles"):
        enc.ticks(np.array([0.0, angle]))
    assert enc.ticks(np.array([1e9, -1e9])).shape == (2,)  # the ends are within


@pytest.mark.parametrize("kind", [float, np.float64, np.float32])
def test_real_float_lets_through_only_the_allowed_non_finite_values(kind: type) -> None:
    nan, inf = kind("nan"), kind("inf")
    assert math.isnan(real_float(nan, "v", allow_nan=True))
    assert real_float(inf, "v", allow_inf=True) == math.inf
    assert real_float(-inf, "v", allow_inf=True) == -math.inf
    assert type(real_float(nan, "v", allow_nan=True)) is float
    for value, options in ((nan, {"allow_inf": True}), (inf, {"allow_nan": True}), (nan, {})):
        with pytest.raises(ValueError, match="v"):
            real_float(value, "v", **options)


@pytest.mark.parametrize("degrees", [180.0, -180.0, 90.0])
def test_an_angle_in_degrees_gets_the_hint_up_to_the_range_ends(degrees: float) -> None:
    # 180 degrees is pi rad, the end of bias's range: still a plausible angle in degrees.
    with pytest.raises(ValueError, match=r"degrees\? pass math\.radians"):
        Compass(bias=degrees)


def test_compass_reading_adds_bias_and_scaled_noise_clockwise_from_north() -> None:
    # degrees(north - yaw + bias + noise * z) mod 360, each term with its own sign.
    compass = Compass(noise=0.1, bias=0.05)
    want = math.degrees(math.pi / 2 - 0.3 + 0.05 + 0.1 * 2.0) % 360.0
    assert compass.heading_deg(0.3, 2.0) == pytest.approx(want, abs=1e-12)
    want = math.degrees(math.pi / 2 - 0.3 + 0.05 - 0.1 * 1.5) % 360.0
    assert compass.heading_deg(0.3, -1.5) == pytest.approx(want, abs=1e-12)


@pytest.mark.parametrize(("yaw", "z"), [(2e6, 0.0), (0.0, -2e6)])
def test_compass_refuses_yaw_or_draw_beyond_1e6(yaw: float, z: float) -> None:
    with pytest.raises(ValueError, match="within"):
        Compass().heading_deg(yaw, z)


@pytest.mark.parametrize("bits", [1, 65, 0])
def test_encoder_bits_outside_2_to_64_are_refused(bits: int) -> None:
    with pytest.raises(ValueError, match="bits"):
        WheelEncoders(bits=bits)


def test_encoder_bits_given_as_a_numpy_integer_are_kept_as_a_plain_int() -> None:
    enc = WheelEncoders(bits=np.int64(16))
    assert type(enc.bits) is int and enc.bits == 16
