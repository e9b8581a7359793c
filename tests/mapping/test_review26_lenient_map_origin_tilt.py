"""grid_from_msg refuses a map origin rolled or pitched beyond 1e-3 rad (session 30).

An origin rolled by π (the map plane upside down) read as yaw 0: every cell's
world y came out mirrored. A planar grid's origin turns about z only; float32
rounding (~1e-7 rad) and ROS 1's zero quaternion still read as before.
"""

from __future__ import annotations

import math
from types import SimpleNamespace as NS

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.geometry import rpy_to_quaternion
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_from_msg, grid_to_msg_fields


def _msg(q: tuple[float, float, float, float]) -> NS:
    origin = NS(position=NS(x=1.0, y=2.0, z=0.0), orientation=NS(x=q[0], y=q[1], z=q[2], w=q[3]))
    return NS(info=NS(width=3, height=2, resolution=0.5, origin=origin), data=[100, 0, 0, 0, 0, -1])


def _q(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    x, y, z, w = (float(v) for v in rpy_to_quaternion(roll, pitch, yaw))
    return x, y, z, w


@pytest.mark.parametrize(
    ("q", "words"),
    [((1.0, 0.0, 0.0, 0.0), r"by 3\.14159 rad \(a roll or pitch, upside down\)"),
     ((0.0, 1.0, 0.0, 0.0), r"by 3\.14159 rad \(a roll or pitch, upside down\)"),
     (_q(math.pi, 0.0, 0.7), r"upside down"),
     (_q(0.0, math.pi / 2, 0.0), r"by 1\.5708 rad \(a roll or pitch\)"),
     (_q(0.1, 0.0, 0.0), r"by 0\.1 rad \(a roll or pitch\)"),
     (_q(0.0, -0.0011, 2.0), r"by 0\.0011 rad")],
)  # fmt: skip
def test_a_tilted_origin_is_refused_naming_the_orientation(
    q: tuple[float, float, float, float], words: str
) -> None:
    start = r"^msg\.info\.origin\.orientation \(x, y, z, w\) = "
    with pytest.raises(ValueError, match=start) as info:
        grid_from_msg(_msg(q))
    assert info.match(words) and info.match(r"only turn about z \(tilt at most 0\.001 rad\)")


@given(yaw=st.floats(-math.pi, math.pi), roll=st.floats(-9e-4, 9e-4),
       pitch=st.floats(-4e-4, 4e-4), scale=st.sampled_from([1.0, -1.0, 3.5, 1e-300]))  # fmt: skip
def test_an_origin_within_the_tolerance_reads_its_yaw(
    yaw: float, roll: float, pitch: float, scale: float
) -> None:
    # roll and pitch together tilt by at most hypot(9e-4, 4e-4) < 1e-3 rad.
    x, y, z, w = (scale * v for v in _q(roll, pitch, yaw))
    theta = grid_from_msg(_msg((x, y, z, w))).origin.theta
    assert abs(math.remainder(theta - yaw, 2.0 * math.pi)) < 1e-6


def test_ros_defaults_and_float32_rounding_still_read() -> None:
    assert grid_from_msg(_msg((0.0, 0.0, 0.0, 0.0))).origin.theta == 0.0  # ROS 1's default
    q32 = tuple(float(np.float32(v)) for v in _q(1e-7, -1e-7, 1.2))
    assert grid_from_msg(_msg(q32)).origin.theta == pytest.approx(1.2, abs=1e-6)  # type: ignore[arg-type]


@pytest.mark.parametrize("theta", [-3.0, -math.pi / 2, 0.0, 1.0, math.pi])
def test_published_grids_read_back(theta: float) -> None:
    grid = OccupancyGrid(np.zeros((2, 3)), resolution=0.5, origin=(1.0, 2.0, theta))
    fields = grid_to_msg_fields(grid)
    px, py, pz = fields.origin_position
    ox, oy, oz, ow = fields.origin_orientation
    msg = NS(info=NS(width=fields.width, height=fields.height, resolution=fields.resolution,
                     origin=NS(position=NS(x=px, y=py, z=pz),
                               orientation=NS(x=ox, y=oy, z=oz, w=ow))),
             data=fields.data)  # fmt: skip
    back = grid_from_msg(msg).origin
    assert abs(math.remainder(back.theta - theta, 2.0 * math.pi)) < 1e-12
