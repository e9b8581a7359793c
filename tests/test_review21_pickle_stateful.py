"""Stateful objects copied or pickled mid-run continue exactly as their originals.

A user branches a simulation with ``copy.deepcopy``, checkpoints a filter with
pickle, or sends a planner mid-replanning to a worker. For each stateful
public class, caught mid-run (a Field D* planner with queued cost changes, an
EKF and a fusion filter after steps, odometry after readings, a scan mapper
after scans, a map after a scan, trackers mid-path, the potential-field
controller with its integral and velocity, a tracker controller, a world with
a moving obstacle), each way of copying it (``copy.copy``, ``copy.deepcopy``,
pickle under protocols 2 to 5 and, where every class takes them, 0 and 1)
gives a twin that

* continues exactly (bit for bit) as an untouched object built the same way;
* shares no mutable state with the original: after the twin has run on, the
  original, run on too, still gives the same results (and the twin's are
  unchanged by it).
"""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from shapely.geometry import Point, box

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    OmniOdometry,
    PlanarFusion,
)
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, Path2D
from navkit.sim import (
    Circle,
    Lidar,
    MovingObstacle,
    Observation,
    Robot,
    Simulation,
    TrackerController,
    World,
)

Steps = Callable[[Any, int], Any]


@dataclass(frozen=True)
class Case:
    """A stateful object caught mid-run, and how to run it on one step at a time."""

    make: Callable[[], Any]
    step: Steps
    steps: int = 3
    shallow_shares: str = ""  # the attribute copy.copy shares by design, if any


def _room_scan(shift: float = 0.0, n: int = 90) -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, n, endpoint=False)
    ranges = (2.0 - shift) / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n,
                     range_min=0.1, range_max=10.0)  # fmt: skip


def _path(path: Path2D) -> tuple[bytes, float, float, int, str]:
    return path.points.tobytes(), path.cost, path.length, path.expanded, path.frame


# ------------------------------------------------------------------ planning


def _costs() -> np.ndarray:
    costs = np.ones((12, 15))
    costs[5, 1:12] = np.inf
    costs[8:, 7] = 3.0
    return costs


def _field_dstar() -> FieldDStar:
    planner = FieldDStar(_costs())
    planner.plan((0, 0), (12, 15))
    planner.update_costs([(10, 3), (11, 3)], np.inf)  # queued: the repair is still to come
    return planner


def _field_dstar_step(planner: FieldDStar, k: int) -> Any:
    if k == 1:
        planner.update_costs([(6, 12), (7, 12)], 5.0)
    if k == 2:
        return _path(planner.replan((1, 1))), planner.costs.tobytes()
    return _path(planner.replan()), planner.costs.tobytes()


def _map_grid() -> OccupancyGrid:
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:15, 14:16] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


_GOALS = [((0.55, 0.55), (2.55, 0.55)), ((2.55, 1.85), (0.35, 0.35)), ((1.0, 1.9), (2.9, 0.1))]


def _map_plan(planner: MapPlanner, k: int) -> Any:
    start, goal = _GOALS[k]
    return _path(planner.plan(start, goal))


def _astar_plan(planner: AStarPlanner, k: int) -> Any:
    start, goal = [((0, 0), (11, 14)), ((11, 0), (0, 14)), ((6, 6), (0, 0))][k]
    return _path(planner.plan(start, goal)), planner.distance_field(goal).tobytes()


# ---------------------------------------------------------------- estimation


def _ekf() -> ExtendedKalmanFilter:
    ekf = ExtendedKalmanFilter([0.0, 1.0, 3.0], np.eye(3), angle_states=[2])
    _ekf_step(ekf, -1)
    return ekf


def _ekf_step(ekf: ExtendedKalmanFilter, k: int) -> Any:
    F = np.eye(3)
    F[0, 1] = 0.1
    ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(3))
    first = ekf.update([0.1 * k], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.01]])
    second = ekf.update([3.1, 0.2], lambda x: x[[2, 1]], np.array([[0, 0, 1.0], [0, 1.0, 0]]),
                        np.diag([0.1, 0.2]), angle_measurements=[0])  # fmt: skip
    return ekf.x.tobytes(), ekf.P.tobytes(), first.nis, second.nis, second.accepted


def _fusion() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0, gate_probability=0.999)
    _fusion_step(fusion, -1)
    return fusion


def _fusion_step(fusion: PlanarFusion, k: int) -> Any:
    results = []
    for i in range(5):
        t = 0.5 * (k + 1) + 0.1 * i
        results.append(fusion.update_odometry(t, 0.5, 0.1, v_variance=0.01, omega_variance=0.01))
        results.append(fusion.update_yaw(t + 0.01, 0.05 * (k + i), variance=1e-3))
        results.append(fusion.update_yaw_rate(t + 0.02, 0.1, variance=1e-4))
    fusion.predict(0.5 * (k + 1) + 0.45)
    return fusion.x.tobytes(), fusion.P.tobytes(), fusion.t, [(r.accepted, r.nis) for r in results]


_OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


def _omni_odometry() -> OmniOdometry:
    odometry = OmniOdometry(_OMNI, pose=(1.0, 2.0, 0.5))
    _omni_step(odometry, -1)
    return odometry


def _omni_step(odometry: OmniOdometry, k: int) -> Any:
    pose = odometry.update(_OMNI.inverse(Twist2D(1.0, 0.1 * k, 0.2)) * 0.1, 0.3 + 0.1 * k)
    return pose.as_array().tobytes()


def _diff_odometry() -> DiffOdometry:
    drive = DiffDrive(track=0.5, left_radius=0.1, right_radius=0.101)
    odometry = DiffOdometry(drive, ticks_per_rev=1000, bits=16)
    odometry.update(65000, 65000)
    odometry.update(464, 470)  # both counters wrapped
    return odometry


def _diff_step(odometry: DiffOdometry, k: int) -> Any:
    return odometry.update(464 + 300 * (k + 1), 470 + 280 * (k + 1)).as_array().tobytes()


def _compass() -> CompassCalibration:
    calibration = CompassCalibration(unwrap=True)
    for heading in (10.0, 200.0, 350.0):
        calibration(heading)
    return calibration


def _compass_step(calibration: CompassCalibration, k: int) -> Any:
    return calibration(20.0 + 170.0 * k), calibration.initial_deg


# ------------------------------------------------------------------- mapping


def _mapper() -> ScanMapper:
    mapper = ScanMapper(resolution=0.1)
    mapper.update(_room_scan())
    mapper.update(_room_scan(), odometry=(0.05, -0.04, 0.03))
    return mapper


def _mapper_step(mapper: ScanMapper, k: int) -> Any:
    # Far enough (min_distance 0.4 m) to write, and past the map's edge to grow it.
    result = mapper.update(_room_scan(0.1 * k), odometry=(0.5 * (k + 1), 0.02, 0.05 * k))
    return (result.pose.as_array().tobytes(), mapper.trajectory.tobytes(),
            mapper.map.logodds.tobytes(), mapper.map.shape, len(mapper))  # fmt: skip


def _map() -> OccupancyGrid:
    grid = OccupancyGrid.empty(width=6.0, height=6.0, resolution=0.1, origin=(-3.0, -3.0, 0.0))
    integrate_scan(grid, _room_scan(), (0.0, 0.0, 0.0))
    return grid


def _map_step(grid: OccupancyGrid, k: int) -> Any:
    integrate_scan(grid, _room_scan(0.2), (0.1 * k, 0.0, 0.1 * k), hit=2.0, miss=-0.5)
    return grid.logodds.tobytes(), grid.occupied().tobytes()


def _matcher_step(matcher: ScanMatcher, k: int) -> Any:
    result = matcher.match(_map(), _room_scan(), (0.1, -0.05 * k, 0.05))
    return result.pose.as_array().tobytes(), result.covariance.tobytes(), result.iterations


# ------------------------------------------------------------------- control


def _tracker(cls: type[Any], drive: str = "diff") -> Any:
    tracker = cls(drive=drive)
    tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], goal_yaw=1.0)
    tracker.step(Pose2D(0.1, 0.05, 0.1), 0.05)
    return tracker


def _tracker_step(tracker: Any, k: int) -> Any:
    # At the start, at the corner, up the second leg: the trackers switch waypoints.
    x, y = [(0.0, 0.0), (1.0, 0.0), (1.0, 0.6)][k]
    twists = [tracker.step(Pose2D(x, y + 0.02 * i, 0.05 * i + 0.5 * k), 0.05) for i in range(4)]
    return [t.as_array().tobytes() for t in twists], tracker.progress, tracker.done


def _controller() -> PotentialFieldController:
    controller = PotentialFieldController(max_speed=0.5, ki=0.5, stall_timeout=0.2)
    _controller_step(controller, -1)
    return controller


def _controller_step(controller: PotentialFieldController, k: int) -> Any:
    twists = [
        controller.step(
            Pose2D(0.1 * k, 0.01 * i, 0.0),
            Pose2D(2.0, 0.5, 0.3),
            0.05,
            obstacles=[[1.0, 0.3], [0.5, -0.4]],
        )
        for i in range(4)
    ]
    return [t.as_array().tobytes() for t in twists], controller.stalled


def _tracker_controller() -> TrackerController:
    tracker = RegulatedPurePursuit(max_speed=0.5)
    tracker.set_path([[1.0, 1.0], [3.0, 1.0], [3.0, 2.0]])
    follow = TrackerController(tracker, control_rate=20.0, use_estimate=False)
    _tracker_controller_step(follow, -1)
    return follow


def _tracker_controller_step(follow: TrackerController, k: int) -> Any:
    pose = Pose2D(1.0 + 0.3 * (k + 1), 1.02, 0.05)
    twist = follow(Observation(0.1 * k, None, None, None, None, (), None, pose))
    return twist.as_array().tobytes(), follow.done


# ----------------------------------------------------------------------- sim


def _world() -> World:
    moving = MovingObstacle.scripted(0.3, [(1.0, 1.0), (6.0, 1.0), (6.0, 6.0)], speed=1.0,
                                     after="loop")  # fmt: skip
    return World([box(0, 0, 10, 8).exterior, Circle((7.0, 4.0), 0.5), Point(3, 3).buffer(0.4)],
                 moving=[moving])  # fmt: skip


def _world_step(world: World, k: int) -> Any:
    # A moving obstacle's placement is cached per query time inside the world.
    pose = (2.0, 1.0 + 0.5 * k, 0.1 * k)
    beams = np.linspace(-math.pi, math.pi, 16, endpoint=False)
    ranges = world.raycast(pose, beams, range_max=20.0, t=1.5 * k)
    lidar = Lidar(n_beams=12, dropout=0.1, angle_jitter=0.01)
    scan = lidar.scan(world, pose, t=0.7 * k, seed=k)
    return ranges.tobytes(), scan.ranges.tobytes(), world.clearance(0.2, pose, t=2.0 * k)


def _turn(_: Observation) -> Twist2D:
    return Twist2D(0.3, 0.0, 0.2)


def _simulation() -> Simulation:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=0.1,
                  lidar=Lidar(n_beams=8, dropout=0.2))  # fmt: skip
    return Simulation(World(box(-5.0, -5.0, 5.0, 5.0).exterior), robot, _turn,
                      start=(0.0, 0.0, 0.0), duration=1.0, seed=7, record_scans=True)  # fmt: skip


def _simulation_step(simulation: Simulation, k: int) -> Any:
    if k > 0:  # a simulation runs once; later steps check that it stays spent
        with pytest.raises(RuntimeError, match="runs once"):
            simulation.run()
        return None
    trace = simulation.run()
    return trace.poses.tobytes(), [s.scan.ranges.tobytes() for s in trace.scans]


CASES: dict[str, Case] = {
    "FieldDStar": Case(_field_dstar, _field_dstar_step),
    "AStarPlanner": Case(lambda: AStarPlanner(_costs()), _astar_plan),
    "MapPlanner": Case(lambda: MapPlanner(_map_grid(), robot_radius=0.2), _map_plan),
    "MapPlanner(field_dstar)": Case(
        lambda: MapPlanner(_map_grid(), robot_radius=0.2, planner="field_dstar"),
        _map_plan,
    ),
    "ExtendedKalmanFilter": Case(_ekf, _ekf_step),
    "PlanarFusion": Case(_fusion, _fusion_step),
    "OmniOdometry": Case(_omni_odometry, _omni_step),
    "DiffOdometry": Case(_diff_odometry, _diff_step),
    "CompassCalibration": Case(_compass, _compass_step),
    "ScanMapper": Case(_mapper, _mapper_step),
    "OccupancyGrid": Case(_map, _map_step),
    "ScanMatcher": Case(lambda: ScanMatcher(levels=2), _matcher_step),
    "FollowTheCarrot": Case(lambda: _tracker(FollowTheCarrot), _tracker_step),
    "OnOffTracker(omni)": Case(lambda: _tracker(OnOffTracker, "omni"), _tracker_step),
    "RegulatedPurePursuit": Case(lambda: _tracker(RegulatedPurePursuit), _tracker_step),
    "PotentialFieldController": Case(_controller, _controller_step),
    # Its tracker is the user's object (given its path before the run), shared
    # by a shallow copy as a Simulation's copy shares its controller.
    "TrackerController": Case(
        _tracker_controller, _tracker_controller_step, shallow_shares="tracker"
    ),
    "World": Case(_world, _world_step),
    "Simulation": Case(_simulation, _simulation_step, steps=2),
}


def _pickled(protocol: int) -> Callable[[Any], Any]:
    def clone(obj: Any) -> Any:
        return pickle.loads(pickle.dumps(obj, protocol=protocol))

    return clone


_CLONES: dict[str, Callable[[Any], Any]] = {
    "copy": copy.copy,
    "deepcopy": copy.deepcopy,
    **{f"pickle{p}": _pickled(p) for p in range(pickle.HIGHEST_PROTOCOL + 1)},
}


def _run(case: Case, obj: Any) -> list[Any]:
    return [case.step(obj, k) for k in range(case.steps)]


_TWINS = [pytest.param(name, how, id=f"{name}-{how}") for name in CASES for how in _CLONES]


@pytest.mark.parametrize(("name", "how"), _TWINS)
def test_a_twin_continues_as_the_original_and_apart_from_it(name: str, how: str) -> None:
    case = CASES[name]
    expected = _run(case, case.make())
    original = case.make()
    twin = _CLONES[how](original)
    assert type(twin) is type(original)
    if how == "copy" and case.shallow_shares:
        name = case.shallow_shares
        assert getattr(twin, name) is getattr(original, name)
        object.__setattr__(twin, name, copy.copy(getattr(twin, name)))
    assert _run(case, twin) == expected
    # The twin has run on: had it shared state with the original (a map, a
    # covariance, a heap, a random generator), the original would now differ.
    assert _run(case, original) == expected


@pytest.mark.parametrize("name", list(CASES))
def test_a_twin_taken_from_a_twin_continues_alike(name: str) -> None:
    # A checkpoint of a checkpoint (a deep copy of an unpickled object), with
    # the steps interleaved between the three.
    case = CASES[name]
    expected = _run(case, case.make())
    first = case.make()
    second = pickle.loads(pickle.dumps(first))
    third = copy.deepcopy(second)
    for k in range(case.steps):
        assert [case.step(obj, k) for obj in (third, first, second)] == [expected[k]] * 3
