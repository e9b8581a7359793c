"""ROS message conversion in navkit.mapping.io: nav_msgs/OccupancyGrid and sensor_msgs/LaserScan."""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid
from navkit.mapping.io import (
    OccupancyGridMsgFields,
    grid_from_msg,
    grid_to_msg_fields,
    scan_from_msg,
)


def fake_msg(data: list[int], width: int, height: int, yaw: float) -> SimpleNamespace:
    return SimpleNamespace(
        info=SimpleNamespace(
            width=width,
            height=height,
            resolution=0.05,
            origin=SimpleNamespace(
                position=SimpleNamespace(x=1.5, y=-2.0, z=0.0),
                orientation=SimpleNamespace(x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2)),
            ),
        ),
        data=data,
    )


def test_msg_round_trip() -> None:
    data = [-1, 0, 100, 50, 20, 80]
    grid = grid_from_msg(fake_msg(data, 3, 2, 0.7))
    assert grid.shape == (2, 3)
    assert grid.origin.theta == pytest.approx(0.7)
    assert (grid.origin.x, grid.origin.y) == (1.5, -2.0)
    # data row 0 is the row at the origin (lowest y in the grid frame).
    assert grid.occupied().tolist() == [[False, False, True], [False, False, True]]
    fields = grid_to_msg_fields(grid)
    assert fields.data.dtype == np.int8
    assert fields.data.tolist() == [-1, 0, 100, -1, 20, 80]  # 50 % is log-odds 0
    assert fields.origin_orientation[2:] == pytest.approx((math.sin(0.35), math.cos(0.35)))
    trinary = grid_to_msg_fields(grid, mode="trinary").data.tolist()
    assert trinary == [-1, 0, 100, -1, -1, 100]
    assert (fields.width, fields.height, fields.resolution) == (3, 2, 0.05)
    assert fields.origin_position == (1.5, -2.0, 0.0)
    again = grid_from_msg(fake_msg(list(fields.data), 3, 2, 0.7))
    assert np.array_equal(again.occupied(), grid.occupied())
    assert np.array_equal(again.free(), grid.free())


def test_bad_msgs() -> None:
    with pytest.raises(ValueError, match="expected width\\*height = 6"):
        grid_from_msg(fake_msg([0] * 5, 3, 2, 0.0))
    with pytest.raises(ValueError, match=r"-1 \(unknown\) or 0\.\.100"):
        grid_from_msg(fake_msg([0, 0, 0, 0, 0, 101], 3, 2, 0.0))
    with pytest.raises(TypeError, match="nav_msgs/OccupancyGrid"):
        grid_from_msg(SimpleNamespace(data=[0]))
    with pytest.raises(ValueError, match=r"msg\.info\.width must be a positive integer"):
        grid_from_msg(fake_msg([], 0, 2, 0.0))
    with pytest.raises(TypeError, match="grid must be an OccupancyGrid"):
        grid_to_msg_fields(np.zeros((2, 2)))  # type: ignore[arg-type]


def test_msg_fields_are_a_frozen_record() -> None:
    grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1)
    fields = grid_to_msg_fields(grid)
    assert isinstance(fields, OccupancyGridMsgFields)
    with pytest.raises(dataclasses.FrozenInstanceError):
        fields.width = 3  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        fields.data[0] = 0
    # Built from a caller's array: a read-only int8 copy, the caller's array untouched.
    data = np.array([100, -1, 0, 42])
    record = OccupancyGridMsgFields(2, 2, 0.5, (0, 0, 0), (0, 0, 0, 1), data)
    data[0] = 7
    assert record.data.dtype == np.int8 and record.data.tolist() == [100, -1, 0, 42]
    assert data.flags.writeable
    assert record.origin_orientation == (0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"width": 0}, ValueError, "width must be a positive integer"),
        ({"height": 1.5}, TypeError, "height must be an integer, got float"),
        ({"resolution": -1.0}, ValueError, r"resolution must be >= 1e-6 and <= 1e6 m"),
        ({"origin_position": (0.0, 0.0)}, ValueError, "origin_position must hold 3"),
        ({"origin_orientation": (0, 0, math.nan, 1)}, ValueError, "origin_orientation"),
        ({"data": [0, 0, 0]}, ValueError, r"data must have shape \(4,\)"),
        ({"data": [0, 0, 0, 101]}, ValueError, r"-1 \(unknown\) or 0\.\.100"),
        ({"data": [0.0, 0.0, 0.0, 0.0]}, TypeError, "data must hold integers"),
        ({"data": [[0, 0], [0]]}, ValueError, "data must be a flat sequence of integers"),
    ],
)
def test_bad_msg_fields(kwargs: dict[str, object], error: type[Exception], match: str) -> None:
    args: dict[str, object] = {
        "width": 2,
        "height": 2,
        "resolution": 0.5,
        "origin_position": (0.0, 0.0, 0.0),
        "origin_orientation": (0.0, 0.0, 0.0, 1.0),
        "data": [0, 0, 0, 0],
    }
    args.update(kwargs)
    with pytest.raises(error, match=match):
        OccupancyGridMsgFields(**args)  # type: ignore[arg-type]


def test_scan_from_msg() -> None:
    msg = SimpleNamespace(
        ranges=[1.0, math.inf, 0.01],
        angle_min=-0.5,
        angle_increment=0.25,
        range_min=0.05,
        range_max=4.0,
        intensities=[3.0, 2.0, 1.0],
    )
    scan = scan_from_msg(msg)
    assert isinstance(scan, LaserScan)
    assert (scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max) == (
        -0.5,
        0.25,
        0.05,
        4.0,
    )
    assert scan.valid_mask().tolist() == [True, False, False]
    assert scan.intensities is not None and scan.intensities.tolist() == [3.0, 2.0, 1.0]
    msg.intensities = []
    assert scan_from_msg(msg).intensities is None
    del msg.intensities
    assert scan_from_msg(msg).intensities is None


def test_scan_from_msg_trusts_ranges_and_increment_over_angle_max() -> None:
    # angle_max says 5 beams, ranges holds 3: the beams are where ranges and the increment put them.
    msg = SimpleNamespace(
        ranges=[1.0, 1.0, 1.0],
        angle_min=0.5,
        angle_max=-0.5,
        angle_increment=-0.25,
        range_min=0.05,
        range_max=4.0,
    )
    scan = scan_from_msg(msg)
    assert scan.angles().tolist() == [0.5, 0.25, 0.0]
    assert scan.angle_max == 0.0


def test_scan_from_msg_requires_the_ros_fields() -> None:
    with pytest.raises(TypeError, match="'range_max'"):
        scan_from_msg(
            SimpleNamespace(ranges=[1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1)
        )


# ------------------------------------------------------------ issue 12: bad input
def msg_with(**info: object) -> SimpleNamespace:
    msg = fake_msg([0, 100], 2, 1, 0.0)
    data = info.pop("data", None)
    if data is not None:
        msg.data = data
    for key, value in info.items():
        if key in ("x", "y"):
            setattr(msg.info.origin.position, key, value)
        elif key.startswith("q"):
            setattr(msg.info.origin.orientation, key[1:], value)
        else:
            setattr(msg.info, key, value)
    return msg


@pytest.mark.parametrize(
    ("info", "error", "match"),
    [
        ({"data": [0, 10**26]}, ValueError, r"msg\.data values must be -1 \(unknown\) or 0\.\.100"),
        ({"data": [0.0, 100.0]}, TypeError, r"msg\.data must hold integers"),
        ({"data": [True, False]}, TypeError, r"msg\.data must hold integers"),
        ({"data": ["0", "100"]}, TypeError, r"msg\.data must hold integers"),
        # NumPy's own "inhomogeneous shape" error named no argument.
        ({"data": [[0, 100], [0]]}, ValueError, r"msg\.data must be a flat sequence of integers"),
        ({"width": 2.0}, TypeError, r"msg\.info\.width must be an integer, got float"),
        ({"height": True}, TypeError, r"msg\.info\.height must be an integer, got bool"),
        ({"width": 10**10, "height": 10**10}, ValueError, r"exceeds OccupancyGrid\.MAX_CELLS"),
        ({"resolution": 0.0}, ValueError, r"msg\.info\.resolution must be >= 1e-6"),
        ({"resolution": "0.1"}, TypeError, r"msg\.info\.resolution must be a real number"),
        ({"x": math.nan}, ValueError, r"msg\.info\.origin\.position\.x must be finite"),
        ({"y": 1 + 1j}, TypeError, r"msg\.info\.origin\.position\.y must be a real number"),
        ({"x": 1e12}, ValueError, r"msg\.info: origin x and y must lie within ±1e9 m"),
        ({"qw": math.inf}, ValueError, r"msg\.info\.origin\.orientation\.w must be finite"),
    ],
)
def test_bad_grid_messages(info: dict[str, object], error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        grid_from_msg(msg_with(**info))


def test_grid_messages_with_object_arrays_of_integers() -> None:
    """Python integers in an object array are occupancy values like any others."""
    values = [100, -1]
    want = grid_from_msg(msg_with(data=values))
    got = grid_from_msg(msg_with(data=np.array(values, dtype=object)))
    np.testing.assert_array_equal(got.logodds, want.logodds)
    with pytest.raises(ValueError, match=r"msg\.data values must be -1 \(unknown\) or 0\.\.100"):
        grid_from_msg(msg_with(data=np.array([-1, 101], dtype=object)))


def test_quaternions_are_normalised() -> None:
    # A zero quaternion (ROS 1's default) is no rotation; a scaled one the same as its unit.
    assert grid_from_msg(msg_with(qx=0.0, qy=0.0, qz=0.0, qw=0.0)).origin.theta == 0.0
    half = 0.35
    big = msg_with(qz=1e200 * math.sin(half), qw=1e200 * math.cos(half))
    assert grid_from_msg(big).origin.theta == pytest.approx(0.7)


def test_grid_to_msg_fields_mode_must_be_scale_or_trinary() -> None:
    grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1)
    for value in (True, 1, None, b"scale"):
        with pytest.raises(TypeError, match="mode must be a str"):
            grid_to_msg_fields(grid, mode=value)  # type: ignore[arg-type]
    for text in ("raw", "Trinary", ""):
        with pytest.raises(ValueError, match="mode must be 'scale' or 'trinary'"):
            grid_to_msg_fields(grid, mode=text)
    assert grid_to_msg_fields(grid, mode=np.str_("trinary")).data.tolist() == [100, 0]


def test_msg_fields_from_lists_copy() -> None:
    data = [100, -1]
    position = [0.0, 0.0, 0.0]
    fields = OccupancyGridMsgFields(2, 1, 0.1, position, (0.0, 0.0, 0.0, 1.0), data)  # type: ignore[arg-type]
    data[0] = 0
    position[0] = 5.0
    assert fields.data.tolist() == [100, -1] and fields.origin_position == (0.0, 0.0, 0.0)
    with pytest.raises(TypeError, match="origin_position must be a sequence of 3 numbers"):
        OccupancyGridMsgFields(2, 1, 0.1, 3.0, (0, 0, 0, 1), [0, 0])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"data values must be -1 \(unknown\) or 0\.\.100"):
        OccupancyGridMsgFields(2, 1, 0.1, (0, 0, 0), (0, 0, 0, 1), [0, 10**30])
