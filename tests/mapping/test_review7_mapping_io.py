"""Seventh review of navkit.mapping.io: copies of the result records, limits, quaternions."""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.mapping.io import (
    BagImu,
    BagOdometry,
    BagScans,
    CarmenLog,
    OccupancyGridMsgFields,
    grid_from_msg,
    grid_to_msg_fields,
    read_carmen,
)

_SCAN = LaserScan(
    np.array([1.0, 2.0]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
)


def _fields() -> OccupancyGridMsgFields:
    data = np.array([100, -1], dtype=np.int8)
    return OccupancyGridMsgFields(2, 1, 0.1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), data)


def _scans() -> BagScans:
    return BagScans("/scan", "laser", np.array([1.5]), np.array([1.6]), (_SCAN,))


def _odometry() -> BagOdometry:
    return BagOdometry(
        "/odom",
        "odom",
        "base_link",
        np.zeros(1),
        np.zeros(1),
        np.array([[1.0, 2.0, 0.5]]),
        np.array([[0.0, 0.0, 0.247404, 0.968912]]),
        np.array([[0.3, 0.0, 0.1]]),
        np.zeros((1, 6, 6)),
        np.eye(6)[None],
    )


def _imu() -> BagImu:
    return BagImu(
        "/imu",
        "imu_link",
        np.zeros(1),
        np.zeros(1),
        np.array([[0.0, 0.0, 0.0, 1.0]]),
        np.array([[0.0, 0.0, 0.2]]),
        np.array([[0.0, 0.0, 9.8]]),
        *[np.eye(3)[None]] * 3,
    )


def _carmen() -> CarmenLog:
    return CarmenLog(
        (_SCAN,), (Pose2D(0.0, 0.0, 0.0),), (Pose2D(1.0, 0.0, 0.0),), np.ones(1), np.ones((2, 4))
    )


# Subclasses at module level, so that pickle finds them.
class FieldsPlus(OccupancyGridMsgFields):
    pass


class ScansPlus(BagScans):
    pass


class OdometryPlus(BagOdometry):
    pass


class ImuPlus(BagImu):
    pass


class CarmenPlus(CarmenLog):
    __slots__ = ("tag",)  # a subclass's own slot as well as a __dict__ entry


_RECORDS: list[tuple[Callable[[], Any], type]] = [
    (_fields, FieldsPlus),
    (_scans, ScansPlus),
    (_odometry, OdometryPlus),
    (_imu, ImuPlus),
    (_carmen, CarmenPlus),
]
_COPIES: dict[str, Callable[[Any], Any]] = {
    "copy": copy.copy,
    "deepcopy": copy.deepcopy,
    "pickle": lambda obj: pickle.loads(pickle.dumps(obj)),
}


def _arrays(record: Any) -> dict[str, np.ndarray]:
    return {
        name: getattr(record, name)
        for name in type(record).__dataclass_fields__
        if isinstance(getattr(record, name), np.ndarray)
    }


@pytest.mark.parametrize("how", list(_COPIES))
@pytest.mark.parametrize(("make", "subclass"), _RECORDS)
def test_copies_keep_arrays_read_only(make: Callable[[], Any], subclass: type, how: str) -> None:
    original = make()
    copied = _COPIES[how](original)
    assert type(copied) is type(original)
    arrays = _arrays(original)
    assert arrays
    for name, array in arrays.items():
        again = getattr(copied, name)
        np.testing.assert_array_equal(again, array)
        assert not again.flags.writeable, name
        with pytest.raises(ValueError, match="read-only"):
            again[...] = 0
    assert not any(a.flags.writeable for a in _arrays(original).values())


@pytest.mark.parametrize("how", list(_COPIES))
@pytest.mark.parametrize(("make", "subclass"), _RECORDS)
def test_subclass_copies_keep_class_and_attributes(
    make: Callable[[], Any], subclass: type, how: str
) -> None:
    base = make()
    record = subclass(*(getattr(base, name) for name in type(base).__dataclass_fields__))
    if hasattr(record, "__dict__"):
        object.__setattr__(record, "extra", {"note": 5})
    if "tag" in getattr(subclass, "__slots__", ()):
        object.__setattr__(record, "tag", "mine")
    copied = _COPIES[how](record)
    assert type(copied) is subclass
    if hasattr(record, "__dict__"):
        assert getattr(copied, "extra", None) == {"note": 5}
    if "tag" in getattr(subclass, "__slots__", ()):
        assert getattr(copied, "tag", None) == "mine"
    for name, array in _arrays(record).items():
        np.testing.assert_array_equal(getattr(copied, name), array)
        assert not getattr(copied, name).flags.writeable, name


def test_old_pickle_state_still_loads() -> None:
    # Pickles made before: the bare list of field values.
    fields = _fields()
    clone = OccupancyGridMsgFields.__new__(OccupancyGridMsgFields)
    clone.__setstate__([getattr(fields, n) for n in OccupancyGridMsgFields.__dataclass_fields__])
    np.testing.assert_array_equal(clone.data, fields.data)
    assert clone.width == 2
    assert pickle.dumps(fields) == pickle.dumps(copy.copy(fields))


def _msg(q: tuple[float, float, float, float]) -> SimpleNamespace:
    ns = SimpleNamespace
    return ns(
        info=ns(
            width=1,
            height=1,
            resolution=0.1,
            origin=ns(
                position=ns(x=0.0, y=0.0, z=0.0),
                orientation=ns(x=q[0], y=q[1], z=q[2], w=q[3]),
            ),
        ),
        data=[0],
    )


def _reference_yaw(q: tuple[float, float, float, float]) -> float:
    """Yaw of ``q`` (any scale) with exact rational arithmetic, then atan2."""
    from fractions import Fraction

    x, y, z, w = (Fraction(v) for v in q)
    sin_part = 2 * (w * z + x * y)
    cos_part = w * w + x * x - y * y - z * z  # = (1 - 2(y² + z²)) |q|²
    big = max(abs(sin_part), abs(cos_part))  # > 0 for a non-zero quaternion
    return math.atan2(float(sin_part / big), float(cos_part / big))


def test_grid_from_msg_yaw_of_a_sub_normal_quaternion() -> None:
    # |q| rounds by a factor √2 here: the normalised quaternion was not a unit one.
    grid = grid_from_msg(_msg((0.0, 0.0, 5e-324, 5e-324)))
    assert grid.origin.theta == pytest.approx(math.pi / 2, abs=1e-12)
    grid = grid_from_msg(_msg((0.0, 0.0, 1e-323, 5e-324)))
    assert grid.origin.theta == pytest.approx(_reference_yaw((0.0, 0.0, 1e-323, 5e-324)))


@settings(max_examples=50, deadline=None)
@given(
    yaw=st.floats(-math.pi, math.pi),
    exponent=st.integers(-1074, 1023),
)
def test_grid_from_msg_yaw_is_scale_free(yaw: float, exponent: int) -> None:
    q = (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))
    scale = math.ldexp(1.0, exponent)
    scaled = (q[0] * scale, q[1] * scale, q[2] * scale, q[3] * scale)
    theta = grid_from_msg(_msg(scaled)).origin.theta
    # A unit quaternion's largest component is at least 1/sqrt(2): no power of two takes
    # all four to zero, so a branch for ROS 1's zero quaternion here never ran (that case
    # is test_review26_lenient_map_origin_tilt's).
    assert any(scaled)
    expected = _reference_yaw(scaled)
    if expected <= -math.pi:
        expected = math.pi
    gap = abs(math.remainder(theta - expected, 2.0 * math.pi))
    # Sub-normal components keep only a few bits: compare with the yaw of what was given.
    assert gap <= 1e-9, (scaled, theta, expected)


test_grid_from_msg_yaw_is_scale_free_thoroughly = slow_twin(
    test_grid_from_msg_yaw_is_scale_free, max_examples=300
)


def test_grid_from_msg_pitched_a_quarter_turn_is_refused() -> None:
    # The map's x axis points straight up: no yaw places its cells (session 30: it read
    # as yaw 0; tests/mapping/test_review26_lenient_map_origin_tilt.py has the others).
    half = math.sqrt(0.5)
    with pytest.raises(ValueError, match=r"msg\.info\.origin\.orientation .* tilts the map"):
        grid_from_msg(_msg((0.0, half, 0.0, half)))


def test_grid_round_trips_through_message_fields_at_any_yaw() -> None:
    for theta in np.linspace(-math.pi, math.pi, 41)[1:]:
        grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1)
        grid = OccupancyGrid(grid.logodds, resolution=0.1, origin=(1.0, 2.0, float(theta)))
        fields = grid_to_msg_fields(grid, mode="trinary")
        ns = SimpleNamespace
        pos, ori = fields.origin_position, fields.origin_orientation
        msg = ns(
            info=ns(
                width=fields.width,
                height=fields.height,
                resolution=fields.resolution,
                origin=ns(
                    position=ns(x=pos[0], y=pos[1], z=pos[2]),
                    orientation=ns(x=ori[0], y=ori[1], z=ori[2], w=ori[3]),
                ),
            ),
            data=fields.data,
        )
        back = grid_from_msg(msg)
        gap = abs(math.remainder(back.origin.theta - theta, 2.0 * math.pi))
        assert gap < 1e-12
        np.testing.assert_array_equal(back.occupied(), grid.occupied())


def _log(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "log.txt"
    path.write_text(text)
    return path


_FLASER = "FLASER 3 1.0 2.0 {r} 0 0 0 0 0 0 1.0 host 1.0\n"


def test_carmen_flaser_reading_beyond_1e9_names_its_line_not_range_max(tmp_path: Path) -> None:
    text = _FLASER.format(r=5.0) + _FLASER.format(r=2e9) + _FLASER.format(r=3.0)
    with pytest.raises(ValueError, match=r"log\.txt:2: FLASER reading 2000000000\.0 m") as info:
        read_carmen(_log(tmp_path, text))
    assert "give range_max" in str(info.value)
    assert "range_max must be" not in str(info.value)
    # With range_max given, such a reading is merely "no return".
    log = read_carmen(_log(tmp_path, text), range_max=10.0)
    assert not log.scans[1].valid_mask()[2]


def test_carmen_flaser_readings_at_the_range_limit(tmp_path: Path) -> None:
    log = read_carmen(_log(tmp_path, _FLASER.format(r=1e9)))
    assert log.scans[0].range_max == 1e9
    with pytest.raises(ValueError, match=r"log\.txt:1: FLASER reading"):
        read_carmen(_log(tmp_path, _FLASER.format(r=repr(math.nextafter(1e9, 2e9)))))


def test_bag_record_times_equal_stamps_of_the_same_instant(tmp_path: Path) -> None:
    pytest.importorskip("rosbags")
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore

    from navkit.mapping.io import read_bag_imu

    store = get_typestore(Stores.ROS2_HUMBLE)
    types = store.types
    vec = types["geometry_msgs/msg/Vector3"]
    nanoseconds = [1432235498_028275834 + 99_419_766 * k for k in range(40)]
    with Writer(tmp_path / "bag", version=9) as writer:
        conn = writer.add_connection("/imu", "sensor_msgs/msg/Imu", typestore=store)
        for ns in nanoseconds:
            stamp = types["builtin_interfaces/msg/Time"](
                sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000
            )
            msg = types["sensor_msgs/msg/Imu"](
                header=types["std_msgs/msg/Header"](stamp=stamp, frame_id="imu"),
                orientation=types["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
                orientation_covariance=np.zeros(9),
                angular_velocity=vec(x=0.0, y=0.0, z=0.0),
                angular_velocity_covariance=np.zeros(9),
                linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
                linear_acceleration_covariance=np.zeros(9),
            )
            writer.write(conn, ns, store.serialize_cdr(msg, "sensor_msgs/msg/Imu"))
    imu = read_bag_imu(tmp_path / "bag")
    np.testing.assert_array_equal(imu.record_times, imu.times)
    # Both the float nearest the exact time (to the rounding of a sum of two floats).
    from fractions import Fraction

    exact = [float(Fraction(ns, 10**9)) for ns in nanoseconds]
    assert np.max(np.abs(imu.record_times - exact)) <= 2.0**-22  # one float at 1.4e9 s
