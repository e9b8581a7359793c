"""A ROS 2 node's journey through navkit, with rclpy's message classes emulated.

``ros_fakes`` behaves as rosidl's generated classes do (``array.array`` sequences,
type-checking setters, float32 fields rounded on delivery): /map in, /scan in,
a plan and a map out as ``nav_msgs/Path`` and ``nav_msgs/OccupancyGrid``, a
``geometry_msgs/Twist`` command out.
"""

from __future__ import annotations

import array
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ros_fakes as ros
from navkit.control import FollowTheCarrot, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D, yaw_to_quaternion
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.mapping.io import (
    OccupancyGridMsgFields,
    grid_from_msg,
    grid_to_msg_fields,
    scan_from_msg,
)
from navkit.planning import FieldDStar, MapPlanner, Path2D

# ----------------------------------------------------------------------------- helpers


def map_msg(data: Any, width: int, height: int, *, x: float, y: float, yaw: float) -> Any:
    """A /map message as map_server publishes it, delivered (float32 resolution)."""
    msg = ros.OccupancyGrid()
    msg.header.frame_id = "map"
    msg.header.stamp = ros.stamp(1_700_000_000, 250_000_000)
    msg.info.map_load_time = ros.stamp(1_700_000_000, 0)
    msg.info.resolution = 0.05
    msg.info.width = width
    msg.info.height = height
    msg.info.origin = ros.pose_msg(x, y, yaw)
    msg.data = data
    return ros.deliver(msg)


def fill_map_msg(fields: OccupancyGridMsgFields, header: Any, load_time: Any) -> Any:
    """What a node writes to publish ``fields``: every setter checks its type."""
    msg = ros.OccupancyGrid()
    msg.header = header
    msg.info.map_load_time = load_time
    msg.info.width = fields.width
    msg.info.height = fields.height
    msg.info.resolution = fields.resolution
    px, py, pz = fields.origin_position
    msg.info.origin.position = ros.Point(x=px, y=py, z=pz)
    qx, qy, qz, qw = fields.origin_orientation
    msg.info.origin.orientation = ros.Quaternion(x=qx, y=qy, z=qz, w=qw)
    msg.data = array.array("b", fields.data.tobytes())  # as grid_to_msg_fields says
    return msg


def room_ranges(pose: tuple[float, float, float], angles: np.ndarray) -> np.ndarray:
    """Exact ranges from ``pose`` to the walls x = ±2.973, y = ±1.981 (off cell edges)."""
    x, y, theta = pose
    a = theta + angles
    c, s = np.cos(a), np.sin(a)
    with np.errstate(divide="ignore", over="ignore"):  # s or c near 0: that wall is at inf
        tx = np.where(c > 0, (2.973 - x) / c, np.where(c < 0, (-2.973 - x) / c, np.inf))
        ty = np.where(s > 0, (1.981 - y) / s, np.where(s < 0, (-1.981 - y) / s, np.inf))
    return np.asarray(np.minimum(tx, ty))


def scan_msg(
    ranges: np.ndarray, *, angle_min: float, angle_increment: float, range_max: float = 8.0
) -> Any:
    """A delivered /scan message (float32 fields, ``array.array('f')`` ranges)."""
    msg = ros.LaserScan()
    msg.header.frame_id = "base_scan"
    msg.header.stamp = ros.stamp(1_700_000_000, 1)
    msg.angle_min = float(angle_min)
    msg.angle_increment = float(angle_increment)
    msg.angle_max = float(angle_min + (len(ranges) - 1) * angle_increment)
    msg.time_increment = 1.0 / (10.0 * len(ranges))
    msg.scan_time = 0.1
    msg.range_min = 0.12
    msg.range_max = float(range_max)
    msg.ranges = [float(r) for r in ranges]  # the setter makes array.array('f')
    msg.intensities = []
    return ros.deliver(msg)


class NoPerElementAccess(array.array):  # type: ignore[type-arg]
    """An ``array.array`` that fails when read element by element (buffer reads only)."""

    def __iter__(self) -> Any:
        raise AssertionError("read element by element")

    def __getitem__(self, index: Any) -> Any:
        raise AssertionError("read element by element")


# ----------------------------------------------------------------------------- 1. /map in


@pytest.mark.parametrize("yaw", [0.0, math.pi / 2, -2.5, math.pi])
def test_map_origin_with_yaw_places_every_cell_where_rviz_draws_it(yaw: float) -> None:
    data = [0, 100, -1, 0, 0, 0]  # 3 columns, 2 rows; row 0 first
    msg = map_msg(data, 3, 2, x=1.0, y=-2.0, yaw=yaw)
    grid = grid_from_msg(msg)
    res = msg.info.resolution
    assert grid.resolution == res == 0.05000000074505806  # the float32 as received
    assert grid.occupied().tolist() == [[False, True, False], [False, False, False]]
    assert grid.unknown().tolist() == [[False, False, True], [False, False, False]]
    # rviz: cell (row, col) centre = origin ⊕ ((col + ½) res, (row + ½) res).
    for row, col in [(0, 1), (0, 2), (1, 0)]:
        u, v = (col + 0.5) * res, (row + 0.5) * res
        expected = (
            1.0 + math.cos(yaw) * u - math.sin(yaw) * v,
            -2.0 + math.sin(yaw) * u + math.cos(yaw) * v,
        )
        np.testing.assert_allclose(grid.cell_to_world([row, col]), expected, atol=1e-12)
        assert grid.world_to_cell(np.array([expected])).tolist() == [[row, col]]


def reference_grid(values: np.ndarray, width: int, height: int) -> OccupancyGrid:
    prob = np.where(values < 0, 0.5, values / 100.0).reshape(height, width)
    return OccupancyGrid.from_probabilities(prob, resolution=0.05000000074505806)


DATA_FORMS: dict[str, Callable[[np.ndarray], Any]] = {
    "array.array('b') (rclpy)": lambda v: array.array("b", v.astype(np.int8).tobytes()),
    "list": lambda v: v.tolist(),
    "tuple (rospy)": lambda v: tuple(v.tolist()),
    "numpy int8 (rosbags)": lambda v: v.astype(np.int8),
    "bytes": lambda v: v.astype(np.int8).tobytes(),
    "bytearray": lambda v: bytearray(v.astype(np.int8).tobytes()),
}


@pytest.mark.parametrize("form", list(DATA_FORMS))
def test_every_form_of_the_data_field_gives_the_same_grid(form: str) -> None:
    values = np.arange(-1, 101)  # every value a message can hold, -1 (0xFF) included
    msg = map_msg(array.array("b", values.astype(np.int8).tobytes()), 102, 1, x=0, y=0, yaw=0)
    msg._data = DATA_FORMS[form](values)  # as another client library hands it over
    grid = grid_from_msg(msg)
    np.testing.assert_array_equal(grid.logodds, reference_grid(values, 102, 1).logodds)
    fields = OccupancyGridMsgFields(
        102, 1, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), DATA_FORMS[form](values)
    )
    np.testing.assert_array_equal(fields.data, values.astype(np.int8))


def test_bytes_with_values_out_of_range_are_refused_as_values() -> None:
    msg = map_msg(array.array("b", [0, 0]), 2, 1, x=0, y=0, yaw=0)
    msg._data = bytes([0, 101])
    with pytest.raises(ValueError, match=r"-1 \(unknown\) or 0\.\.100"):
        grid_from_msg(msg)
    msg._data = bytes([0, 0x80])  # int8 -128
    with pytest.raises(ValueError, match=r"-1 \(unknown\) or 0\.\.100"):
        grid_from_msg(msg)


def test_a_4000_by_4000_map_is_read_through_its_buffer_not_element_by_element() -> None:
    # 16 million cells: any per-cell Python work would take seconds to minutes.
    n = 4000
    values = np.zeros((n, n), dtype=np.int8)
    values[:, 0] = 100
    values[n - 1, :] = -1
    values[1234, 2345] = 73
    data = NoPerElementAccess("b", values.tobytes())
    msg = map_msg(array.array("b"), n, n, x=-100.0, y=-100.0, yaw=0.25)
    msg._data = data
    grid = grid_from_msg(msg)
    assert grid.shape == (n, n)
    assert grid.occupied()[:-1, 0].all() and not grid.occupied()[:, 1].any()
    assert grid.unknown()[n - 1].all() and int(grid.unknown().sum()) == n
    assert grid.probability()[1234, 2345] == pytest.approx(0.73, abs=1e-6)
    fields = grid_to_msg_fields(grid)
    np.testing.assert_array_equal(fields.data, values.ravel())


@settings(max_examples=30)
@given(
    st.integers(1, 6),
    st.integers(1, 6),
    st.data(),
    st.floats(-math.pi, math.pi),
    st.floats(-1e3, 1e3),
    st.floats(-1e3, 1e3),
)
def test_map_round_trip_republishes_the_message_received(
    width: int, height: int, draw: st.DataObject, yaw: float, x: float, y: float
) -> None:
    # 50 is excluded: it is log-odds 0, as -1 is, and comes back as -1 (documented).
    value = st.integers(-1, 100).filter(lambda v: v != 50)
    data = draw.draw(st.lists(value, min_size=width * height, max_size=width * height))
    received = map_msg(data, width, height, x=x, y=y, yaw=yaw)
    fields = grid_to_msg_fields(grid_from_msg(received))
    published = ros.deliver(fill_map_msg(fields, received.header, received.info.map_load_time))
    assert list(published.data) == list(received.data)
    for name in ("width", "height", "resolution", "map_load_time"):
        assert getattr(published.info, name) == getattr(received.info, name)
    assert published.info.origin.position == received.info.origin.position
    q_in, q_out = (
        np.array([q.x, q.y, q.z, q.w])
        for q in (received.info.origin.orientation, published.info.origin.orientation)
    )
    # The same rotation: q and -q are one (yaw -π goes out as +π).
    np.testing.assert_allclose(q_out * np.sign(q_out @ q_in), q_in, atol=1e-15)


def test_fifty_percent_comes_back_as_unknown() -> None:
    received = map_msg([50, -1, 49, 51], 4, 1, x=0, y=0, yaw=0)
    assert grid_to_msg_fields(grid_from_msg(received)).data.tolist() == [-1, -1, 49, 51]


def test_fields_need_the_documented_conversion_for_an_rclpy_message() -> None:
    fields = grid_to_msg_fields(OccupancyGrid.from_occupancy(np.eye(2, dtype=bool), resolution=0.1))
    msg = ros.OccupancyGrid()
    with pytest.raises(AssertionError):
        msg.data = fields.data  # rclpy refuses a NumPy array, as the Notes say
    msg = fill_map_msg(fields, ros.Header(), ros.Time())  # every other field as it is
    assert msg.data == array.array("b", [100, 0, 0, 100])


# ----------------------------------------------------------------------------- 2. /scan in

N_BEAMS = 360
INC = 2.0 * math.pi / N_BEAMS
ANGLES = -math.pi + INC * np.arange(N_BEAMS)


def test_rep117_readings_clear_mark_or_skip_as_the_rep_says() -> None:
    # beam 0 → +x: +inf (nothing within range_max), the other beams probe one cell each.
    ranges = np.array([np.inf, -np.inf, np.nan, 0.0, 8.0, 0.05, 2.0, 9.0])
    angle_min, inc = 0.0, math.pi / 4
    scan = scan_from_msg(scan_msg(ranges, angle_min=angle_min, angle_increment=inc))
    assert scan.valid_mask().tolist() == [False] * 6 + [True, False]
    grid = OccupancyGrid.empty(width=20.0, height=20.0, resolution=0.1, origin=(-10, -10, 0))
    integrate_scan(grid, scan, (0.05, 0.05, 0.0))  # a cell centre: beams run along cells

    def along(k: int, dist: float) -> float:
        a = angle_min + k * inc
        point = [0.05 + dist * math.cos(a), 0.05 + dist * math.sin(a)]
        row, col = grid.world_to_cell([point])[0]
        return float(grid.logodds[row, col])

    assert along(0, 7.5) < 0.0 and along(0, 8.5) == 0.0  # +inf: free up to range_max only
    for k in (1, 2, 3):  # -inf (too close), NaN (invalid), 0 (below range_min): untouched
        assert along(k, 1.0) == 0.0
    assert along(4, 7.5) < 0.0  # a reading at range_max is "no return": cleared, not hit
    assert along(5, 1.0) == 0.0  # below range_min: skipped
    assert along(6, 2.0) > 0.0 and along(6, 1.0) < 0.0  # a real return
    assert along(7, 7.5) < 0.0 and along(7, 8.5) == 0.0  # beyond range_max: cleared to it


@settings(max_examples=15)
@given(st.floats(-1.5, 1.5), st.floats(-1.0, 1.0), st.floats(-math.pi, math.pi))
def test_a_scanner_sweeping_clockwise_maps_and_matches_as_one_sweeping_anticlockwise(
    x: float, y: float, theta: float
) -> None:
    # Off the cell edges (multiples of 0.05): a sensor on an edge may fall in either cell.
    pose = (x + 0.0117, y + 0.0133, theta)
    ranges = room_ranges(pose, ANGLES)
    ccw = LaserScan(ranges, angle_min=-math.pi, angle_increment=INC, range_min=0.1, range_max=8.0)
    cw = LaserScan(
        ranges[::-1],
        angle_min=float(ANGLES[-1]),
        angle_increment=-INC,
        range_min=0.1,
        range_max=8.0,
    )
    maps = []
    for scan in (ccw, cw):
        grid = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.05, origin=(-4, -3, 0))
        integrate_scan(grid, scan, pose)
        maps.append(grid)
    np.testing.assert_array_equal(maps[0].logodds, maps[1].logodds)
    guess = (pose[0] + 0.04, pose[1] - 0.03, theta + 0.03)
    found = [ScanMatcher().match(maps[0], scan, guess).pose for scan in (ccw, cw)]
    np.testing.assert_allclose(found[0].as_array(), found[1].as_array(), atol=1e-6)


def test_an_upside_down_scanner_is_its_scan_mirrored() -> None:
    # Rolled by π about x (laser frame upside down on base_link): beam angle a in
    # the laser frame points at -a in base_link; mirroring the angles is a scan
    # with angle_min -angle_min and a negative increment.
    ranges = room_ranges((0.3, 0.2, 0.5), ANGLES)
    upside_down = scan_from_msg(
        scan_msg(ranges[::-1] * 1.0, angle_min=math.pi - INC, angle_increment=-INC)
    )
    mirrored = LaserScan(
        upside_down.ranges,
        angle_min=-upside_down.angle_min,
        angle_increment=-upside_down.angle_increment,
        range_min=upside_down.range_min,
        range_max=upside_down.range_max,
    )
    points = upside_down.to_points()
    np.testing.assert_allclose(mirrored.to_points(), points * [1.0, -1.0], atol=1e-12)


def test_scan_mapper_follows_float32_scans_of_a_room() -> None:
    mapper = ScanMapper(resolution=0.05, pose=(0.0, 0.0, 0.0))
    truth = [(0.02 * k, 0.01 * k, 0.02 * k) for k in range(12)]
    for pose in truth:
        ranges = room_ranges(pose, ANGLES)
        ranges[::17] = np.inf  # dropouts: no return
        ranges[5::23] = np.nan
        mapper.update(scan_from_msg(scan_msg(ranges, angle_min=-math.pi, angle_increment=INC)))
    end = mapper.pose
    assert math.hypot(end.x - truth[-1][0], end.y - truth[-1][1]) < 0.03
    assert abs(end.theta - truth[-1][2]) < 0.02


# ----------------------------------------------------------------------------- 4. plan out


def path_msg(path: Path2D, frame_id: str, stamp: Any) -> Any:
    """``nav_msgs/Path`` of a world path, each pose facing the next point."""
    assert path.frame == "world"
    pts = path.points
    heading = np.arctan2(np.diff(pts[:, 1]), np.diff(pts[:, 0]))
    heading = np.append(heading, heading[-1] if len(heading) else 0.0)
    quats = yaw_to_quaternion(heading)
    msg = ros.Path()
    msg.header = ros.Header(stamp=stamp, frame_id=frame_id)
    poses = []
    for (px, py), (qx, qy, qz, qw) in zip(pts, quats, strict=True):
        pose = ros.Pose(
            position=ros.Point(x=float(px), y=float(py), z=0.0),
            orientation=ros.Quaternion(x=qx, y=qy, z=qz, w=qw),
        )
        poses.append(ros.PoseStamped(header=msg.header, pose=pose))
    msg.poses = poses
    return msg


def corridor_map_msg(yaw: float) -> Any:
    occupied = np.zeros((20, 30), dtype=np.int8)
    occupied[[0, -1], :] = occupied[:, [0, -1]] = 100
    occupied[0:14, 15] = 100
    occupied[15:, 25] = -1  # unknown: not planned through by default
    return map_msg(array.array("b", occupied.tobytes()), 30, 20, x=1.0, y=2.0, yaw=yaw)


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
@pytest.mark.parametrize("yaw", [0.0, math.pi / 2, -2.5])
def test_plan_on_a_received_map_and_publish_the_path(planner: str, yaw: float) -> None:
    grid = grid_from_msg(corridor_map_msg(yaw))
    start, goal = grid.cell_to_world([[3, 3], [3, 26]])
    path = MapPlanner(grid, robot_radius=0.1, planner=planner).plan(start, goal)
    cells = grid.world_to_cell(path.points)
    assert not grid.occupied()[cells[:, 0], cells[:, 1]].any()
    assert not grid.unknown()[cells[:, 0], cells[:, 1]].any()
    assert cells[:, 0].max() >= 14  # round the wall's end, in map rows, whatever the yaw
    msg = ros.deliver(path_msg(path, "map", ros.stamp(1_700_000_000, 0)))
    first, last = msg.poses[0].pose.position, msg.poses[-1].pose.position
    np.testing.assert_allclose([first.x, first.y, last.x, last.y], [*start, *goal], atol=1e-9)


def test_field_dstar_in_world_coordinates_of_a_yawed_map() -> None:
    grid = grid_from_msg(corridor_map_msg(math.pi / 2))
    costs = np.where(grid.occupied() | grid.unknown(), np.inf, 1.0)
    planner = FieldDStar(costs, resolution=grid.resolution, origin=grid.origin)
    start, goal = grid.cell_to_world([[3, 3], [3, 26]])
    path = planner.plan_world(start, goal)
    assert path.frame == "world"
    np.testing.assert_allclose(path.points[[0, -1]], [start, goal], atol=1e-9)
    cells = grid.world_to_cell(path.points)
    assert np.isfinite(costs[cells[:, 0], cells[:, 1]]).all()


# ----------------------------------------------------------------------------- 5. cmd_vel out


def twist_msg(command: Twist2D) -> Any:
    return ros.Twist(
        linear=ros.Vector3(x=command.vx, y=command.vy, z=0.0),
        angular=ros.Vector3(x=0.0, y=0.0, z=command.omega),
    )


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("tracker_class", [RegulatedPurePursuit, FollowTheCarrot])
def test_controller_commands_fill_a_twist_in_the_robot_frame(
    drive: str, tracker_class: type[RegulatedPurePursuit] | type[FollowTheCarrot]
) -> None:
    # Robot at the origin facing +y (yaw π/2); the path runs along +y, then to its left (-x).
    tracker = tracker_class(drive=drive)  # type: ignore[arg-type]
    tracker.set_path(np.array([[0.0, 0.0], [0.0, 1.0], [-1.0, 1.0]]))
    msg = ros.deliver(twist_msg(tracker.step(Pose2D(0.0, 0.0, math.pi / 2), 0.05)))
    assert msg.linear.x > 0.0  # forward along the robot's own x, i.e. world +y
    assert abs(msg.linear.y) < 1e-9 or drive == "omni"
    assert msg.linear.z == msg.angular.x == msg.angular.y == 0.0
    # Facing -y, the path is behind: a diff robot turns in place; both stop driving away.
    tracker = tracker_class(drive=drive)  # type: ignore[arg-type]
    tracker.set_path(np.array([[0.0, 0.0], [0.0, 1.0]]))
    msg = ros.deliver(twist_msg(tracker.step(Pose2D(0.0, 0.0, -math.pi / 2), 0.05)))
    assert msg.linear.x <= 1e-9
    if drive == "diff":
        assert msg.angular.z != 0.0 and msg.linear.y == 0.0


def test_omni_command_to_the_left_is_positive_linear_y() -> None:
    # REP 103: y is to the robot's left. Robot facing +x, path straight to its left (+y).
    tracker = RegulatedPurePursuit(drive="omni", rotate_to_heading=False)
    tracker.set_path(np.array([[0.0, 0.0], [0.0, 2.0]]))
    msg = ros.deliver(twist_msg(tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)))
    assert msg.linear.y > 0.0
