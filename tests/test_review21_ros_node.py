"""navkit inside a ROS 2 node as a user writes one, with threads standing in for rclpy.

A new review lens: the node subscribes to /odom (50 Hz) and /imu (200 Hz), which
feed one ``PlanarFusion``; to /scan (10 Hz), integrated into an ``OccupancyGrid``
whose snapshots other callbacks read; a 1 Hz timer replans with ``MapPlanner``
on the latest snapshot and a 20 Hz control loop steps a tracker. Messages are
``ros_fakes`` classes as rclpy delivers them (float32 fields, ``array.array``
ranges, ``sec``/``nanosec`` stamps at 1.7e9 s).

Two executors run the same messages: a single-threaded one (every callback in
time order in one thread) and a multi-threaded one (one thread per topic, each
callback group behind its own lock, as rclpy's ``MutuallyExclusiveCallbackGroup``
does). Checked: no callback raises; the map written by one thread and read as
snapshots by others ends bit-identical to the single-threaded map and every
snapshot a reader used is a whole one (the map after some number of scans,
never a scan half written); the fusion's only refusals under racing /odom and
/imu callbacks are ``OUT_OF_ORDER`` ones, reported by status, never an
exception or a corrupt state; epoch stamps built as ``sec + nanosec * 1e-9``
give the run from t = 0 to within 1e-6 m.
"""

from __future__ import annotations

import math
import queue
import sys
import threading
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import ros_fakes as ros
from navkit.control import RegulatedPurePursuit
from navkit.errors import NoPathError
from navkit.estimation import FusionStatus, PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.mapping import OccupancyGrid, integrate_scan
from navkit.mapping.io import grid_to_msg_fields, scan_from_msg
from navkit.planning import MapPlanner

EPOCH_SEC = 1_700_000_000
RADIUS, OMEGA = 1.0, 0.2  # the robot circles the room's centre at 0.2 m/s
BEAMS = 90
INC = 2 * math.pi / BEAMS
GOAL_XY = (-1.5, -1.0)


# ----------------------------------------------------------------------------- messages
def truth(t: float) -> tuple[float, float, float]:
    return (RADIUS * math.cos(OMEGA * t), RADIUS * math.sin(OMEGA * t), OMEGA * t + math.pi / 2)


def room_ranges(pose: tuple[float, float, float]) -> np.ndarray:
    """Ranges from ``pose`` to the walls x = ±2.973, y = ±1.981 (off cell edges)."""
    x, y, theta = pose
    a = theta - math.pi + INC * np.arange(BEAMS)
    c, s = np.cos(a), np.sin(a)
    with np.errstate(divide="ignore", over="ignore"):
        tx = np.where(c > 0, (2.973 - x) / c, np.where(c < 0, (-2.973 - x) / c, np.inf))
        ty = np.where(s > 0, (1.981 - y) / s, np.where(s < 0, (-1.981 - y) / s, np.inf))
    return np.asarray(np.minimum(tx, ty))


def stamp_of(k: int, *, epoch: int) -> Any:
    """Step ``k`` of the 200 Hz clock (5 ms) as a ROS stamp from ``epoch`` seconds."""
    ns = k * 5_000_000
    return ros.stamp(epoch + ns // 1_000_000_000, ns % 1_000_000_000)


def seconds(msg: Any) -> float:
    """A header stamp as float64 seconds, as a node author writes it."""
    return float(msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9)


def odom_msg(k: int, *, epoch: int = EPOCH_SEC) -> Any:
    msg = ros.Odometry()
    msg.header.stamp = stamp_of(k, epoch=epoch)
    msg.twist.twist.linear.x = RADIUS * OMEGA
    msg.twist.twist.angular.z = OMEGA
    return ros.deliver(msg)


def imu_msg(k: int, *, epoch: int = EPOCH_SEC) -> Any:
    msg = ros.Imu()
    msg.header.stamp = stamp_of(k, epoch=epoch)
    msg.angular_velocity.z = OMEGA
    return ros.deliver(msg)


def scan_msg(k: int) -> Any:
    msg = ros.LaserScan()
    msg.header.stamp = stamp_of(k, epoch=EPOCH_SEC)
    msg.angle_min = -math.pi
    msg.angle_increment = INC
    msg.angle_max = -math.pi + (BEAMS - 1) * INC
    msg.range_min = 0.12
    msg.range_max = 8.0
    msg.ranges = [float(r) for r in room_ranges(truth(k * 0.005))]
    return ros.deliver(msg)


def topics(steps: int) -> dict[str, list[tuple[int, Any]]]:
    """Each topic's messages in publication order, keyed by the 200 Hz step."""
    return {
        "imu": [(k, imu_msg(k)) for k in range(steps)],
        "odom": [(k, odom_msg(k)) for k in range(0, steps, 4)],
        "scan": [(k, scan_msg(k)) for k in range(0, steps, 20)],
        "timer": [(k, None) for k in range(100, steps, 200)],
        "control": [(k, None) for k in range(105, steps, 10)],
    }


# ----------------------------------------------------------------------------- the node
class Node:
    """The node: callback groups are locks; the map is published as snapshots."""

    def __init__(self, *, history: float = 0.0) -> None:
        self.fusion = PlanarFusion(pose=truth(0.0), history=history)
        self.grid = OccupancyGrid.empty(
            width=6.4, height=4.4, resolution=0.1, origin=(-3.2, -2.2, 0)
        )
        self.tracker = RegulatedPurePursuit(drive="diff")
        self.fusion_group = threading.Lock()  # /odom and /imu
        self.plan_group = threading.Lock()  # timer and control loop share the tracker
        self.snapshot_lock = threading.Lock()
        self.snapshot = self.grid.copy()
        self.statuses: list[FusionStatus | None] = []
        self.used_snapshots: list[np.ndarray] = []
        self.commands: list[Twist2D] = []
        self.map_msgs = 0
        self.warm_up()

    def warm_up(self) -> None:
        """Compile (or load) every kernel the callbacks use, as docs/compilation.md says."""
        fusion = PlanarFusion()
        fusion.update_odometry(0.0, 0.1, 0.0, v_variance=1e-4, omega_variance=1e-4)
        fusion.update_yaw_rate(0.01, 0.0, variance=1e-4)
        spare = self.grid.copy()
        integrate_scan(spare, scan_from_msg(scan_msg(0)), (0.0, 0.0, 0.0))
        grid_to_msg_fields(spare)
        MapPlanner(spare, unknown_cost=1.0).plan((0.0, 0.0), (0.5, 0.0))

    def pose(self) -> Pose2D:
        with self.fusion_group:
            return self.fusion.pose

    def on_odom(self, msg: Any) -> None:
        tw = msg.twist.twist
        with self.fusion_group:
            res = self.fusion.update_odometry(
                seconds(msg), tw.linear.x, tw.angular.z, v_variance=1e-4, omega_variance=1e-4
            )
            self.statuses.append(res.status)

    def on_imu(self, msg: Any) -> None:
        with self.fusion_group:
            res = self.fusion.update_yaw_rate(seconds(msg), msg.angular_velocity.z, variance=1e-5)
            self.statuses.append(res.status)

    def on_scan(self, k: int, msg: Any) -> None:
        # The scan's pose from "tf" (the ground truth here), so the map depends on
        # the scans alone and both executors must build the same one.
        integrate_scan(self.grid, scan_from_msg(msg), truth(k * 0.005))
        snapshot = self.grid.copy()  # taken by the only writer: whole
        with self.snapshot_lock:
            self.snapshot = snapshot

    def on_timer(self) -> None:
        with self.snapshot_lock:
            grid = self.snapshot
        self.used_snapshots.append(grid.logodds.copy())
        grid_to_msg_fields(grid)  # publish /map
        self.map_msgs += 1
        try:
            route = MapPlanner(grid, robot_radius=0.15, unknown_cost=1.0).plan(
                self.pose(), GOAL_XY, start_tolerance=0.3
            )
        except NoPathError:
            return
        with self.plan_group:
            self.tracker.set_path(route.points)

    def on_control(self) -> None:
        with self.plan_group:
            if self.tracker.path_xy is None:
                return
            self.commands.append(self.tracker.step(self.pose(), 0.05))

    def callback(self, topic: str) -> Callable[[int, Any], None]:
        return {
            "imu": lambda k, m: self.on_imu(m),
            "odom": lambda k, m: self.on_odom(m),
            "scan": self.on_scan,
            "timer": lambda k, m: self.on_timer(),
            "control": lambda k, m: self.on_control(),
        }[topic]


def spin_single(node: Node, msgs: dict[str, list[tuple[int, Any]]]) -> list[BaseException]:
    """SingleThreadedExecutor: every callback in time order (ties by topic order)."""
    order = ["odom", "imu", "scan", "timer", "control"]
    events = sorted(
        (k, order.index(topic), topic, m) for topic, items in msgs.items() for k, m in items
    )
    for k, _, topic, m in events:
        node.callback(topic)(k, m)
    return []


def spin_multi(
    node: Node, msgs: dict[str, list[tuple[int, Any]]], *, paced: bool
) -> list[BaseException]:
    """MultiThreadedExecutor stand-in: one thread per topic, each draining its queue.

    ``paced``: the messages of each 5 ms step are released together once the
    previous step's callbacks have returned, as messages arriving at their rates
    to callbacks that keep up. Otherwise every queue is full from the start and
    each thread runs as fast as it can, as after a long stall (a backlog).
    """
    errors: list[BaseException] = []
    queues: dict[str, queue.Queue[tuple[int, Any]]] = {topic: queue.Queue() for topic in msgs}

    def run(topic: str) -> None:
        q, cb = queues[topic], node.callback(topic)
        while True:
            k, m = q.get()
            try:
                if k < 0:
                    return
                cb(k, m)
            except BaseException as exc:  # every failure is a finding
                errors.append(exc)
            finally:
                q.task_done()

    threads = [threading.Thread(target=run, args=(topic,)) for topic in msgs]
    for th in threads:
        th.start()
    if paced:
        steps: dict[int, list[tuple[str, Any]]] = {}
        for topic, items in msgs.items():
            for k, m in items:
                steps.setdefault(k, []).append((topic, m))
        for k in sorted(steps):
            for topic, m in steps[k]:
                queues[topic].put((k, m))
            for q in queues.values():
                q.join()
    else:
        for topic, items in msgs.items():
            for item in items:
                queues[topic].put(item)
    for q in queues.values():
        q.put((-1, None))
    for th in threads:
        th.join()
    return errors


@pytest.fixture(scope="module")
def messages() -> dict[str, list[tuple[int, Any]]]:
    return topics(1000)  # 5 s of the node's life


@pytest.fixture(scope="module")
def single(messages: dict[str, list[tuple[int, Any]]]) -> tuple[Node, list[np.ndarray]]:
    node = Node()
    maps = [node.grid.logodds.copy()]
    for k, m in messages["scan"]:  # the map after each number of scans
        integrate_scan(node.grid, scan_from_msg(m), truth(k * 0.005))
        maps.append(node.grid.logodds.copy())
    node = Node()
    assert spin_single(node, messages) == []
    return node, maps


# ----------------------------------------------------------------------------- tests
def test_single_threaded_node_fuses_maps_plans_and_tracks(
    single: tuple[Node, list[np.ndarray]],
) -> None:
    node, maps = single
    assert set(node.statuses) == {FusionStatus.ACCEPTED}
    assert len(node.statuses) == 1000 + 250
    x, y, theta = truth(999 * 0.005)
    pose = node.fusion.pose
    assert math.hypot(pose.x - x, pose.y - y) < 1e-3
    assert abs(math.remainder(pose.theta - theta, 2 * math.pi)) < 1e-3
    np.testing.assert_array_equal(node.grid.logodds, maps[-1])
    assert node.grid.occupied().sum() > 40  # the walls the scans saw
    assert node.map_msgs == 5 and len(node.commands) == 90
    assert all(np.isfinite([c.vx, c.vy, c.omega]).all() for c in node.commands)
    assert any(c.omega != 0 for c in node.commands)  # turning towards the path


def run_multi(
    messages: dict[str, list[tuple[int, Any]]],
    switch_interval: float,
    *,
    paced: bool,
    history: float = 0.0,
) -> Node:
    old = sys.getswitchinterval()
    sys.setswitchinterval(switch_interval)  # short: threads switch often, between kernels
    try:
        node = Node(history=history)
        errors = spin_multi(node, messages, paced=paced)
    finally:
        sys.setswitchinterval(old)
    assert errors == []
    return node


def check_map(node: Node, reference: Node, maps: list[np.ndarray]) -> None:
    # One writer: the same scans in the same order, bit for bit.
    np.testing.assert_array_equal(node.grid.logodds, reference.grid.logodds)
    # Every snapshot a reader planned on is the map after some whole number of scans.
    assert len(node.used_snapshots) == 5
    for used in node.used_snapshots:
        assert any(np.array_equal(used, m) for m in maps)


@pytest.mark.parametrize("switch_interval", [1e-5, 5e-3])
def test_multi_threaded_node_keeping_up_matches_the_single_threaded_one(
    single: tuple[Node, list[np.ndarray]],
    messages: dict[str, list[tuple[int, Any]]],
    switch_interval: float,
) -> None:
    reference, maps = single
    node = run_multi(messages, switch_interval, paced=True)
    check_map(node, reference, maps)
    # /odom and /imu of one step may run in either order: equal stamps, both taken.
    assert node.statuses == reference.statuses
    np.testing.assert_allclose(node.fusion.x, reference.fusion.x, rtol=0, atol=1e-9)
    assert len(node.commands) == len(reference.commands)


@pytest.mark.parametrize("switch_interval", [1e-5, 5e-3])
def test_multi_threaded_node_with_a_backlog_refuses_late_messages_by_status(
    single: tuple[Node, list[np.ndarray]],
    messages: dict[str, list[tuple[int, Any]]],
    switch_interval: float,
) -> None:
    """Each topic drains its own backlog: /odom runs behind /imu and is refused."""
    reference, maps = single
    node = run_multi(messages, switch_interval, paced=False)
    check_map(node, reference, maps)
    # A message older than the filter's time is refused by status, never by an
    # exception or a corrupt state; which ones depends on the threads' timing.
    assert set(node.statuses) <= {FusionStatus.ACCEPTED, FusionStatus.OUT_OF_ORDER}
    assert len(node.statuses) == 1000 + 250
    assert np.isfinite(node.fusion.x).all()
    assert node.fusion.t == seconds(messages["imu"][-1][1])


def test_epoch_stamps_from_sec_and_nanosec_match_a_run_from_zero() -> None:
    """60 s of 200 Hz IMU and 50 Hz odometry stamped at 1.7e9 s and at 0 s."""

    def run(epoch: int) -> np.ndarray:
        fusion = PlanarFusion()
        for k in range(12_000):
            if k % 4 == 0:
                msg = odom_msg(k, epoch=epoch)
                tw = msg.twist.twist
                fusion.update_odometry(
                    seconds(msg), tw.linear.x, tw.angular.z, v_variance=1e-4, omega_variance=1e-4
                )
            imu = imu_msg(k, epoch=epoch)
            res = fusion.update_yaw_rate(seconds(imu), imu.angular_velocity.z, variance=1e-5)
            assert res.status == FusionStatus.ACCEPTED
        return np.asarray(fusion.x)

    at_epoch, at_zero = run(EPOCH_SEC), run(0)
    # Each dt is off by up to one float spacing at 1.7e9 s (2.4e-7 s of 5 ms);
    # the filter time is the stamp itself, so the error does not accumulate.
    np.testing.assert_allclose(at_epoch, at_zero, rtol=0, atol=1e-6)
    assert not np.array_equal(at_epoch, at_zero)  # the rounding is real, only small


@pytest.mark.parametrize("switch_interval", [1e-5, 5e-3])
def test_multi_threaded_node_with_a_backlog_and_history_takes_every_message(
    single: tuple[Node, list[np.ndarray]],
    messages: dict[str, list[tuple[int, Any]]],
    switch_interval: float,
) -> None:
    """With ``history=`` covering the backlog, late messages go back where their stamps belong."""
    reference, maps = single
    node = run_multi(messages, switch_interval, paced=False, history=5.0)
    check_map(node, reference, maps)
    assert node.statuses == [FusionStatus.ACCEPTED] * (1000 + 250)
    # The same measurements fused in stamp order; equal stamps may come either way.
    np.testing.assert_allclose(node.fusion.x, reference.fusion.x, rtol=0, atol=1e-9)
    assert node.fusion.t == seconds(messages["imu"][-1][1])
