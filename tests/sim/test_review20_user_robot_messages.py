"""Messages a new user meets building a simulated robot (session 24, USER).

A class where an instance is wanted, a drive named by a string, a wheel radius
error in percent and compass angles in degrees are refused as before; the
messages now say what to pass instead.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Compass, Imu, Lidar, Robot, WheelEncoders

DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)


@pytest.mark.parametrize(
    ("name", "kind", "article"),
    [("encoders", WheelEncoders, "a"), ("lidar", Lidar, "a"), ("compass", Compass, "a"),
     ("imu", Imu, "an")],
)
def test_a_sensor_class_asks_for_an_instance(name: str, kind: type, article: str) -> None:
    cls = kind.__name__
    with pytest.raises(TypeError, match=rf"^{name} must be {article} {cls} or None, got "
                       rf"the class {cls} itself: pass an instance, {cls}\(\)$"):
        Robot(drive=DRIVE, footprint=0.2, **{name: kind})
    with pytest.raises(TypeError, match=rf"^{name} must be {article} {kind.__name__} or None, "
                       r"got bool$"):
        Robot(drive=DRIVE, footprint=0.2, **{name: True})
    robot = Robot(drive=DRIVE, footprint=0.2, **{name: kind()})  # what the message says
    assert isinstance(getattr(robot, name), kind)


@pytest.mark.parametrize("drive", ["diff", OmniDrive, DiffDrive, None])
def test_a_drive_that_is_not_one_says_how_to_build_one(drive: object) -> None:
    with pytest.raises(TypeError, match=r"^drive must be an OmniDrive or a DiffDrive, got .*: "
                       r"build one, e\.g\. DiffDrive\(track=0\.3, wheel_radius=0\.05\) or "
                       r"OmniDrive\.three_wheel\(wheel_radius=0\.05, base_radius=0\.2\)$"):
        Robot(drive=drive, footprint=0.2)  # type: ignore[arg-type]
    if isinstance(drive, type):
        with pytest.raises(TypeError, match=rf"got the class {drive.__name__} itself"):
            Robot(drive=drive, footprint=0.2)  # type: ignore[arg-type]
    # both examples the message gives are valid drives
    for example in (DiffDrive(track=0.3, wheel_radius=0.05),
                    OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)):
        assert Robot(drive=example, footprint=0.2).drive is example


@given(st.floats(0.5, 100.0, exclude_min=True))
def test_a_wheel_radius_error_in_percent_explains_the_fraction(percent: float) -> None:
    with pytest.raises(ValueError, match=r"^wheel_radius_error must lie in \[-0\.5, 0\.5\], got "
                       r"\[.*\]: it is the true radius over the nominal one, minus 1 "):
        Robot(drive=DRIVE, footprint=0.2, wheel_radius_error=percent)
    assert Robot(drive=DRIVE, footprint=0.2, wheel_radius_error=0.02).wheel_radius_error[0] == 0.02


@given(st.floats(4.0, 180.0))
def test_compass_angles_in_degrees_suggest_radians(degrees: float) -> None:
    # Review 46: a bias is also offered its wrap (the same reading), so the degrees
    # hint need not come last.
    with pytest.raises(ValueError, match=r"^bias must lie in .* rad, got .*(\(|; or )degrees\? "
                       r"pass math\.radians\(.*\)"):
        Compass(bias=degrees)
    with pytest.raises(ValueError, match=r"\(degrees\? pass math\.radians"):
        Compass(noise=degrees)
    assert Compass(bias=math.radians(degrees)).bias == math.radians(degrees)


@pytest.mark.parametrize("value", [7.0, 90.0, 359.0, -45.0])
def test_north_in_degrees_suggests_radians(value: float) -> None:
    with pytest.raises(
        ValueError, match=r"^north must lie in .*(\(|; or )degrees\? pass math\.radians"
    ):
        Compass(north=value)


@pytest.mark.parametrize("value", [1e4, -1e4, 400.0])
def test_no_degrees_hint_where_degrees_would_not_fit_either(value: float) -> None:
    """Beyond a turn in degrees the value is no angle at all: no hint."""
    with pytest.raises(ValueError) as info:
        Compass(north=value)
    assert "degrees" not in str(info.value)
    with pytest.raises(ValueError) as info:
        Compass(noise=-0.1)
    assert "degrees" not in str(info.value)
