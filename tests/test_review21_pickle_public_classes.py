"""Copies, pickles, equality and repr of every public class (a review through a new lens).

Users put navkit objects in multiprocessing queues, Dask tasks and joblib
caches, ``copy.deepcopy`` them to branch a simulation, save them with pickle
between runs, compare them and print them. For one representative instance of
each public class (each package's ``__all__``: planners mid-replanning, filters
and odometry mid-run, a mapper after scans, trackers mid-path, a simulation's
trace, maps, errors), this file pins that

* a pickle round trip under every protocol, ``copy.copy`` and
  ``copy.deepcopy`` give an object of the same class whose every attribute
  (slots and ``__dict__``, followed into nested objects) equals the
  original's: arrays with the same dtype, values and read-only flag, floats
  bit for bit (NaN and the sign of zero), random generators in the same state;
* deep copies and pickles share no array with the original (mutating one
  cannot change the other; ``test_review21_pickle_stateful.py`` runs the
  stateful ones on);
* a class defining ``__eq__`` compares its copies equal, NaN fields included,
  and hashes them alike;
* ``repr`` stays short for large objects (a trace of 600 scans printed
  1.3 MB, a bag of 2000 scans 20 MB);
* exceptions keep their message and attributes (``NoPathError.expanded``).

Nothing public is intentionally unpicklable. Protocols 0 and 1 refused every
class with ``__slots__`` that inherits ``object.__getstate__``; each now takes
``__getstate__ = slot_state`` (``navkit._shared.dunders``).
"""

from __future__ import annotations

import concurrent.futures
import copy
import enum
import importlib
import inspect
import math
import multiprocessing
import pickle
import struct
import types
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapely.geometry import Point, box
from shapely.geometry.base import BaseGeometry

from navkit.behaviours import BehaviourTarget, GameState
from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.errors import (
    DataNotFoundError,
    FilterError,
    KernelCacheWarning,
    NavkitError,
    NoPathError,
)
from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    FusionStatus,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
    UpdateResult,
)
from navkit.geometry import ImuInBase, Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import (
    LaserScan,
    LocalGrid,
    OccupancyGrid,
    ScanMapper,
    ScanMatcher,
    ScanMatchResult,
    integrate_scan,
)
from navkit.mapping.io import (
    BagImu,
    BagOdometry,
    BagScans,
    CarmenLog,
    MovingAIMap,
    MovingAIScenarios,
    OccupancyGridMsgFields,
)
from navkit.planning import (
    AStarPlanner,
    BlendedAttraction,
    ConicAttraction,
    FieldDStar,
    GreedyStep,
    KhatibRepulsion,
    MapPlanner,
    ParaboloidAttraction,
    Path2D,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    SampledField,
    astar,
)
from navkit.sim import (
    Circle,
    Compass,
    CompassReading,
    EncoderReading,
    Event,
    Imu,
    ImuReading,
    Lidar,
    MovingObstacle,
    Observation,
    RangeNoise,
    Robot,
    ScanReading,
    ScenarioResult,
    Scene,
    Simulation,
    Table,
    Trace,
    TrackerController,
    Trial,
    TrialResult,
    WarmupReport,
    WarmupStep,
    WheelEncoders,
    World,
)
from navkit.sim.scenarios import Demo, DiffAStar, Greedy, IndoorNav, OmniApf, Soccer

_PACKAGES = (
    "navkit", "navkit.errors", "navkit.geometry", "navkit.kinematics", "navkit.mapping",
    "navkit.mapping.io", "navkit.estimation", "navkit.planning", "navkit.planning.grid",
    "navkit.planning.reactive", "navkit.control", "navkit.behaviours", "navkit.sim",
    "navkit.sim.scenarios",
)  # fmt: skip

# Protocols and abstract bases: their concrete classes stand for them.
_ABSTRACT = {
    "AttractiveField", "CellPlanner", "Estimator", "PotentialField", "Scenario", "Tracker",
}  # fmt: skip


def _room_scan(n: int = 90) -> LaserScan:
    """A 4 m square room seen from its centre, ``n`` beams."""
    angles = np.linspace(-math.pi, math.pi, n, endpoint=False)
    ranges = 2.0 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n,
                     range_min=0.1, range_max=10.0)  # fmt: skip


def _costs() -> np.ndarray:
    costs = np.ones((12, 15))
    costs[5, 1:12] = np.inf
    costs[8:, 7] = 3.0
    return costs


def _grid() -> OccupancyGrid:
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:15, 14:16] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(-1.0, -0.5, 0.0))
    integrate_scan(grid, _room_scan(), (0.5, 0.5, 0.0))  # log-odds of every kind
    return grid


def _field_dstar() -> FieldDStar:
    planner = FieldDStar(_costs(), resolution=0.5, origin=(1.0, 2.0, 0.0))
    planner.plan((0, 0), (12, 15))
    planner.update_costs([(10, 3), (11, 3)], np.inf)  # queued, not yet repaired
    return planner


def _ekf() -> ExtendedKalmanFilter:
    ekf = ExtendedKalmanFilter([0.0, 1.0, 3.0], np.eye(3), angle_states=[2])
    F = np.eye(3)
    F[0, 1] = 0.1
    ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(3))
    ekf.update([0.12], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.01]])
    return ekf


def _fusion() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0, gate_probability=0.999)
    for i in range(1, 21):
        fusion.update_odometry(0.05 * i, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
        fusion.update_yaw(0.05 * i + 0.01, 0.005 * i, variance=1e-3)
    return fusion


def _mapper() -> ScanMapper:
    mapper = ScanMapper(resolution=0.1)
    mapper.update(_room_scan())
    mapper.update(_room_scan(), odometry=(0.05, -0.04, 0.03))
    return mapper


def _omni_odometry() -> OmniOdometry:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    odometry = OmniOdometry(drive, pose=(1.0, 2.0, 0.5))
    odometry.update(drive.inverse(Twist2D(1.0, 0.0, 0.2)) * 0.1, 0.3)
    return odometry


def _diff_odometry() -> DiffOdometry:
    drive = DiffDrive(track=0.5, left_radius=0.1, right_radius=0.101)
    odometry = DiffOdometry(drive, ticks_per_rev=1000, bits=16)
    odometry.update(65000, 65000)
    odometry.update(464, 470)
    return odometry


def _compass() -> CompassCalibration:
    calibration = CompassCalibration(unwrap=True)
    for heading in (10.0, 200.0, 350.0):
        calibration(heading)
    return calibration


def _tracker(cls: type[FollowTheCarrot | OnOffTracker | RegulatedPurePursuit]) -> Any:
    tracker = cls()
    tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], goal_yaw=1.0)
    tracker.step(Pose2D(0.1, 0.05, 0.1), 0.05)
    return tracker


def _controller() -> PotentialFieldController:
    controller = PotentialFieldController(max_speed=0.5, ki=0.5)
    controller.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), 0.05, obstacles=[[1.0, 0.3]])
    return controller


def _world() -> World:
    moving = MovingObstacle.constant_velocity(0.1, start_xy=(1.0, 1.0), velocity_xy=(1.0, 0.5))
    world = World([box(0, 0, 10, 8).exterior, Circle((7.0, 4.0), 0.5), Point(3, 3).buffer(0.4)],
                  moving=[moving])  # fmt: skip
    world.raycast((2.0, 4.0, 0.0), [0.0, 1.0], range_max=20.0)  # builds its index
    return world


def _robot() -> Robot:
    return Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=0.1,
        lidar=Lidar(n_beams=8, dropout=0.2), compass=Compass(noise=0.1), imu=Imu(gyro_noise=0.1),
    )  # fmt: skip


def turn(_: Observation) -> Twist2D:
    """A controller pickle finds by name."""
    return Twist2D(0.3, 0.0, 0.2)


def _simulation(duration: float = 1.0) -> Simulation:
    world = World(box(-10.0, -10.0, 10.0, 10.0).exterior)
    return Simulation(world, _robot(), turn, start=(0.0, 0.0, 0.0), goal=(5.0, 5.0),
                      duration=duration, seed=7, record_scans=True)  # fmt: skip


def _trace() -> Trace:
    return _simulation().run()


def _tracker_controller() -> TrackerController:
    tracker = FollowTheCarrot(max_speed=0.5)
    tracker.set_path([[1.0, 1.0], [3.0, 1.0]])
    return TrackerController(tracker, control_rate=20.0, use_estimate=False)


def _no_path() -> NoPathError:
    costs = np.ones((3, 3))
    costs[:, 1] = np.inf
    try:
        astar(costs, (0, 0), (0, 2))
    except NoPathError as exc:
        return exc
    raise AssertionError("a wall must split the grid")


def _filter_error() -> FilterError:
    try:
        PlanarFusion(t0=0.0).update_yaw(1e300, 0.1, variance=1e-3)
    except FilterError as exc:
        return exc
    raise AssertionError("a 1e300 s gap must fail")


_INSTANCES: dict[str, Callable[[], Any]] = {
    # navkit.errors
    "NavkitError": lambda: NavkitError("x"),
    "NoPathError": _no_path,
    "FilterError": _filter_error,
    "DataNotFoundError": lambda: DataNotFoundError(2, "not found", "map.yaml"),
    "KernelCacheWarning": lambda: KernelCacheWarning("no cache"),
    # geometry, kinematics
    "ImuInBase": lambda: ImuInBase([0, 0, 0.2, 0.98], [0, 0, 0.1], [0, 0, 9.8]),
    "Pose2D": lambda: Pose2D(1.0, -0.0, 0.5),
    "Twist2D": lambda: Twist2D(0.5, 0.0, 0.1),
    "DiffDrive": lambda: DiffDrive(track=0.3, left_radius=0.05, right_radius=0.051),
    "OmniDrive": lambda: OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2),
    # mapping
    "LaserScan": _room_scan,
    "LocalGrid": lambda: LocalGrid.from_points([[0.5, -0.2]], half_width=1.0, resolution=0.1),
    "OccupancyGrid": _grid,
    "ScanMapper": _mapper,
    "ScanMatchResult": lambda: ScanMatchResult(
        Pose2D(1, 2, 0), np.eye(3), 4, 0.9, True, "converged"
    ),
    "ScanMatcher": lambda: ScanMatcher(levels=2, translation_weight=0.1),
    "BagImu": lambda: BagImu(
        "/imu",
        "imu_link",
        [0.0],
        [0.0],
        [[0, 0, 0, 1.0]],
        [[0, 0, 0.1]],
        [[0, 0, 9.8]],
        np.zeros((1, 3, 3)),
        np.zeros((1, 3, 3)),
        np.zeros((1, 3, 3)),
    ),
    "BagOdometry": lambda: BagOdometry(
        "/odom",
        "odom",
        "base_link",
        [0.0],
        [0.0],
        [[1.0, 2.0, 0.5]],
        [[0.0, 0.0, 0.247404, 0.968912]],
        [[0.3, 0.0, 0.1]],
        np.zeros((1, 6, 6)),
        np.eye(6)[None],
    ),
    "BagScans": lambda: BagScans("/scan", "laser", [1.5], [1.6], (_room_scan(),)),
    "CarmenLog": lambda: CarmenLog(
        (_room_scan(),), (Pose2D(0, 0, 0),), (Pose2D(0, 0, 0.1),), [12.5], [[0, 0, 0, 12.4]]
    ),
    "OccupancyGridMsgFields": lambda: OccupancyGridMsgFields(
        2, 1, 0.1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), np.array([0, 100], np.int8)
    ),
    "MovingAIMap": lambda: MovingAIMap(["..@", "T.S"]),
    "MovingAIScenarios": lambda: MovingAIScenarios(
        [0], ["t.map"], [[2, 3]], [[0, 0]], [[1, 2]], [2.5]
    ),
    # estimation
    "CompassCalibration": _compass,
    "DiffOdometry": _diff_odometry,
    "ExtendedKalmanFilter": _ekf,
    "FusionResult": lambda: PlanarFusion(t0=0.0).update_batch(
        MeasurementLog.from_streams(yaw=([0.1, 0.2, -1.0], [0.0, 0.01, 0.0]))
    ),
    "FusionStatus": lambda: FusionStatus(1),
    "MeasurementLog": lambda: MeasurementLog.from_streams(
        odometry=([0.0, 0.2], [1.0, 1.0]), yaw=([0.1], [0.5]), yaw_variance=1e-3
    ),
    "OmniOdometry": _omni_odometry,
    "PlanarFusion": _fusion,
    "UpdateResult": lambda: UpdateResult(
        False, 30.2, np.array([5.0]), "rejected by the gate", FusionStatus.GATED
    ),
    # planning
    "AStarPlanner": lambda: AStarPlanner(_costs(), heuristic_weight=1.5),
    "AStarPlanner(jps)": lambda: AStarPlanner(
        np.where(np.isfinite(_costs()), 1.0, np.inf), method="jps"
    ),
    "FieldDStar": _field_dstar,
    "MapPlanner": lambda: MapPlanner(_grid(), robot_radius=0.2),
    "MapPlanner(field_dstar)": lambda: MapPlanner(_grid(), robot_radius=0.2, planner="field_dstar"),
    "Path2D": lambda: Path2D([[0, 0], [1, 1], [1, 2]], "grid", cost=2.4, length=2.4, expanded=3),
    "BlendedAttraction": lambda: BlendedAttraction((0.0, 0.0), threshold_radius=1.0, width=0.1),
    "CompositeField": lambda: (
        ConicAttraction((5.0, 0.0)) + KhatibRepulsion([[1.0, 0.0]], influence_radius=2.0)
    ),
    "ConicAttraction": lambda: ConicAttraction((0.0, 0.0), m=0.5),
    "GreedyStep": lambda: GreedyStep((10, 12), (0.2, 0.0), g=0.2, h=1.8, candidates=440),
    "KhatibRepulsion": lambda: KhatibRepulsion([[0.0, 0.0]], influence_radius=1.0),
    "ParaboloidAttraction": lambda: ParaboloidAttraction((1.0, 0.0), k_att=2.0, b=2.0),
    "PiecewiseAttraction": lambda: PiecewiseAttraction((0.0, 0.0), alpha=2.0, goal_radius=0.5),
    "PiecewiseRepulsion": lambda: PiecewiseRepulsion([[0.0, 0.0]], delta=5.0, obstacle_radius=0.5),
    "SampledField": lambda: SampledField(
        [0.5, 1.5], [0.5], [[1.0, 2.0]], np.zeros((1, 2, 2)), resolution=1.0
    ),
    # control, behaviours
    "FollowTheCarrot": lambda: _tracker(FollowTheCarrot),
    "OnOffTracker": lambda: _tracker(OnOffTracker),
    "RegulatedPurePursuit": lambda: _tracker(RegulatedPurePursuit),
    "PotentialFieldController": _controller,
    "BehaviourTarget": lambda: BehaviourTarget((1.0, 0.0), [[2.0, 1.0], [np.nan, np.nan]]),
    "GameState": lambda: GameState(
        robot_xy=(0.0, 0.0),
        ball_xy=(1.0, 0.0),
        teammates_xy=[[-2.0, 1.0]],
        opponents_xy=[[3.0, 0.0]],
        own_goal_xy=(-4.5, 0.0),
        opponent_goal_xy=(4.5, 0.0),
    ),
    # sim
    "Circle": lambda: Circle((0.0, 0.0), 5.0, solid=False),
    "Compass": lambda: Compass(noise=0.01),
    "CompassReading": lambda: CompassReading(0.05, 90.0),
    "EncoderReading": lambda: EncoderReading(0.02, np.array([10, 12])),
    "Event": lambda: Event(1.5, "collision", "touched"),
    "Imu": lambda: Imu(gyro_noise=0.01, accel_noise=0.05),
    "ImuReading": lambda: ImuReading(0.01, 0.2, 0.5, 0.0),
    "Lidar": lambda: Lidar(n_beams=4, noise=RangeNoise(), angle_jitter=0.01),
    "Metrics": lambda: _trace().metrics,  # NaN time_to_goal, estimate errors
    "MovingObstacle": lambda: MovingObstacle.scripted(
        0.2, [(0, 0), (2, 0)], speed=0.5, after="loop"
    ),
    "Observation": lambda: Observation(0.0, None, None, None, None, (), None, Pose2D(0, 0, 0)),
    "RangeNoise": lambda: RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0, 0.005)),
    "Robot": _robot,
    "ScanReading": lambda: ScanReading(0.1, _room_scan()),
    "ScenarioResult": lambda: ScenarioResult(
        "x",
        0,
        (TrialResult(Trial("a", 0, 0, 1), {"e": math.nan}),),
        (Table("t", ("a",), ((math.nan,),)),),
        {"a": 1.0},
        Scene("s"),
    ),
    "Scene": lambda: Scene("s", grid=_grid(), paths=(("p", np.zeros((2, 2))),)),
    "Simulation": _simulation,
    "Table": lambda: Table("errors", ("target", "navkit (mm)"), (("(0, 3)", math.nan),)),
    "Trace": _trace,
    "TrackerController": _tracker_controller,
    "Trial": lambda: Trial("t", 0, 2, 5),
    "TrialResult": lambda: TrialResult(Trial("a", 0, 0, 1), {"error": 0.02}, _trace()),
    "WarmupReport": lambda: WarmupReport((WarmupStep("a", ("a.b",), ("c.d",), 1.5, 1.4),), 2.0, 1),
    "WarmupStep": lambda: WarmupStep("g", ("a.b",), (), 1.0, 0.5),
    "WheelEncoders": lambda: WheelEncoders(ticks_per_rev=2048, bits=16),
    "World": _world,
    # scenarios
    "Demo": lambda: Demo(map="office", duration=0.5),
    "DiffAStar": lambda: DiffAStar(parts=("house",)),
    "Greedy": lambda: Greedy(noise=False),
    "IndoorNav": lambda: IndoorNav(targets=1, paths=1, map_source="plan"),
    "OmniApf": lambda: OmniApf(noise=False, obstacles=False, targets=[(0.0, 1.0)]),
    "Soccer": lambda: Soccer(duration=20.0),
}


def _public_classes() -> dict[str, type]:
    found: dict[str, type] = {}
    for package in _PACKAGES:
        module = importlib.import_module(package)
        for name in module.__all__:
            value = getattr(module, name)
            if inspect.isclass(value) and name not in _ABSTRACT:
                found[name] = value
    return found


def test_every_public_class_has_an_instance_here() -> None:
    # A class added to an __all__ must be added to _INSTANCES (and so checked).
    covered = {type(factory()) for factory in _INSTANCES.values()}
    missing = sorted(name for name, cls in _public_classes().items() if cls not in covered)
    assert missing == []


# ----------------------------------------------------------- structural equality


def _bits(value: float) -> bytes:
    return struct.pack("<d", value)


# Caches and scratch space copies rebuild by design (compared through what
# they compute in test_review21_pickle_stateful.py): the EKF's compiled-kernel
# entries and buffers per measurement size, the mapper's spare trajectory rows.
_SCRATCH: dict[type, set[str]] = {
    ExtendedKalmanFilter: {
        "_entry",
        "_gate",
        "_kp",
        "_ku",
        "_m",
        "_meas_angles",
        "_options",
        "_rbuf",
        "_rbufs",
    },
    ScanMapper: {"_path"},
}


def _attributes(obj: object) -> Iterator[tuple[str, Any]]:
    """Every set attribute of ``obj``: its slots along the MRO, then its ``__dict__``."""
    for cls in type(obj).__mro__:
        slots = cls.__dict__.get("__slots__", ())
        for name in (slots,) if isinstance(slots, str) else slots:
            if name in ("__dict__", "__weakref__") or name in _SCRATCH.get(cls, ()):
                continue
            try:
                yield name, object.__getattribute__(obj, name)
            except AttributeError:
                yield name, AttributeError  # unset: must be unset in the copy too
    instance = getattr(obj, "__dict__", None)
    if isinstance(instance, dict):  # not a mapping proxy or a foreign object's attribute
        yield from instance.items()


def _assert_same(a: Any, b: Any, where: str = "obj", seen: set[int] | None = None) -> None:
    """``b`` is a faithful copy of ``a``, attribute by attribute, into nested objects."""
    seen = set() if seen is None else seen
    assert type(a) is type(b), f"{where}: {type(a).__name__} became {type(b).__name__}"
    if isinstance(a, (type, types.FunctionType, types.BuiltinFunctionType, enum.Enum)):
        assert a is b, where  # by reference, as pickle stores them
        return
    if isinstance(a, (float, np.floating)):
        assert _bits(float(a)) == _bits(float(b)), f"{where}: {a!r} became {b!r}"
        return
    if a is None or isinstance(a, (bool, int, str, bytes, np.integer, np.bool_, np.dtype)):
        assert a == b, f"{where}: {a!r} became {b!r}"
        return
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, where
        assert a.flags.writeable == b.flags.writeable, f"{where}: writeable flag changed"
        if a.dtype.kind == "O":
            for i, (x, y) in enumerate(zip(a.ravel(), b.ravel(), strict=True)):
                _assert_same(x, y, f"{where}[{i}]", seen)
        else:
            assert a.tobytes() == b.tobytes(), f"{where}: values changed"
        return
    if id(a) in seen:
        return
    seen.add(id(a))
    if isinstance(a, BaseGeometry):
        assert a.wkb == b.wkb, where
        return
    if isinstance(a, np.random.Generator):
        assert a.bit_generator.state == b.bit_generator.state, where
        return
    if isinstance(a, (tuple, list)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _assert_same(x, y, f"{where}[{i}]", seen)
        return
    if isinstance(a, Mapping):
        assert list(a) == list(b), where
        for key in a:
            _assert_same(a[key], b[key], f"{where}[{key!r}]", seen)
        return
    if isinstance(a, BaseException):
        _assert_same(a.args, b.args, f"{where}.args", seen)
        assert str(a) == str(b), where
    attributes_a, attributes_b = dict(_attributes(a)), dict(_attributes(b))
    assert attributes_a.keys() == attributes_b.keys(), where
    for name, value in attributes_a.items():
        _assert_same(value, attributes_b[name], f"{where}.{name}", seen)


def _arrays(obj: Any, seen: set[int] | None = None) -> Iterator[np.ndarray]:
    """Every array reachable from ``obj`` through attributes, items and values."""
    seen = set() if seen is None else seen
    if id(obj) in seen or isinstance(obj, (type, str, bytes, int, float, types.FunctionType)):
        return
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        yield obj
        if obj.dtype.kind == "O":
            for item in obj.ravel():
                yield from _arrays(item, seen)
        return
    if isinstance(obj, (tuple, list)):
        items: Any = obj
    elif isinstance(obj, Mapping):
        items = list(obj.values())
    elif isinstance(obj, (BaseGeometry, np.random.Generator, enum.Enum)):
        return
    else:
        items = [value for _, value in _attributes(obj)]
    for item in items:
        yield from _arrays(item, seen)


def _pickled(protocol: int) -> Callable[[Any], Any]:
    def clone(obj: Any) -> Any:
        return pickle.loads(pickle.dumps(obj, protocol=protocol))

    return clone


def _compares(obj: object) -> bool:
    """Whether ``obj``'s class defines its own equality (exceptions compare by identity)."""
    return type(obj).__eq__ is not object.__eq__ and not isinstance(obj, BaseException)


_PROTOCOLS = list(range(pickle.HIGHEST_PROTOCOL + 1))
_CASES = [
    pytest.param(name, protocol, id=f"{name}-protocol{protocol}")
    for name in _INSTANCES
    for protocol in _PROTOCOLS
]


@pytest.mark.parametrize(("name", "protocol"), _CASES)
def test_a_pickle_round_trip_restores_every_attribute(name: str, protocol: int) -> None:
    original = _INSTANCES[name]()
    loaded = _pickled(protocol)(original)
    _assert_same(original, loaded)
    if _compares(original):
        assert loaded == original
        assert hash(loaded) == hash(original)


_COPIERS = {"copy": copy.copy, "deepcopy": copy.deepcopy}


@pytest.mark.parametrize("how", list(_COPIERS))
@pytest.mark.parametrize("name", list(_INSTANCES))
def test_copies_restore_every_attribute(name: str, how: str) -> None:
    original = _INSTANCES[name]()
    twin = _COPIERS[how](original)
    assert type(twin) is type(original)
    _assert_same(original, twin)
    if _compares(original):
        assert twin == original
        assert hash(twin) == hash(original)


@pytest.mark.parametrize("how", ["deepcopy", "pickle"])
@pytest.mark.parametrize("name", list(_INSTANCES))
def test_deep_copies_share_no_array_with_the_original(name: str, how: str) -> None:
    # Writing into a deep copy (a map the copy integrates scans into, a filter's
    # covariance) must leave the original alone, and the other way round.
    original = _INSTANCES[name]()
    twin = copy.deepcopy(original) if how == "deepcopy" else _pickled(5)(original)
    mine = list(_arrays(original))
    for array in _arrays(twin):
        shared = [i for i, other in enumerate(mine) if np.shares_memory(array, other)]
        assert shared == [], f"a {array.shape} {array.dtype} array is shared"


# ------------------------------------------------------------------ equality


def test_records_with_nan_figures_equal_their_copies_and_reruns() -> None:
    # Tables hold NaN where a figure does not apply (IndoorNav's "paper" row);
    # the dataclass's equality compared NaN by identity: a table and its pickle,
    # or the same table built twice, were unequal.
    table = Table("t", ("a", "b"), (("x", math.nan), ("y", np.float64("nan"))))
    again = Table("t", ("a", "b"), (("x", float("nan")), ("y", math.nan)))
    assert table == again and hash(table) == hash(again)
    assert table == pickle.loads(pickle.dumps(table))
    assert table != Table("t", ("a", "b"), (("x", math.nan), ("y", 0.0)))
    assert table != Table("t", ("a", "c"), (("x", math.nan), ("y", math.nan)))
    assert len({table, again}) == 1
    assert Table("t", ("a",), ((1,),)) == Table("t", ("a",), ((1.0,),))  # as tuples compare
    assert table.__eq__(("t",)) is NotImplemented


_CELLS = st.one_of(
    st.none(), st.text(max_size=3), st.integers(-3, 3), st.sampled_from([0.0, -0.0, 1.0]),
    st.floats(allow_nan=True, allow_infinity=True), st.just(np.float64("nan")),
)  # fmt: skip


@given(
    st.lists(st.tuples(_CELLS, _CELLS), max_size=4), st.lists(st.tuples(_CELLS, _CELLS), max_size=4)
)
def test_tables_are_equal_exactly_when_their_cells_are(
    rows: list[tuple[Any, Any]], others: list[tuple[Any, Any]]
) -> None:
    def same(x: Any, y: Any) -> bool:
        nan = [isinstance(v, float) and math.isnan(v) for v in (x, y)]
        return all(nan) or (not any(nan) and x == y)

    table, other = Table("t", ("a", "b"), tuple(rows)), Table("t", ("a", "b"), tuple(others))
    assert table == pickle.loads(pickle.dumps(table)) == copy.deepcopy(table)
    assert hash(pickle.loads(pickle.dumps(table))) == hash(table)
    expected = len(rows) == len(others) and all(
        same(x, y)
        for row, twin in zip(rows, others, strict=False)
        for x, y in zip(row, twin, strict=True)
    )
    assert (table == other) is expected
    assert (table != other) is not expected
    if expected:
        assert hash(table) == hash(other)


def test_metrics_of_two_identical_runs_compare_equal() -> None:
    # time_to_goal, final errors and the estimate errors are NaN where they do
    # not apply; two runs with the same seed gave unequal Metrics.
    first, second = _trace().metrics, _trace().metrics
    assert math.isnan(first.time_to_goal)
    assert first == second
    assert first == pickle.loads(pickle.dumps(first))


# ---------------------------------------------------------------------- repr


@pytest.mark.parametrize("name", list(_INSTANCES))
def test_repr_and_str_work_and_stay_short(name: str) -> None:
    obj = _INSTANCES[name]()
    if name not in ("Trace", "TrialResult"):  # 101 rows in four arrays: 11.7 kB
        assert len(repr(obj)) < 4000
    assert len(str(obj)) < 20_000


def _many_scans(n: int) -> tuple[LaserScan, ...]:
    scan = _room_scan(720)
    return (scan,) * n


_LARGE: dict[str, Callable[[], Any]] = {
    "BagScans": lambda: BagScans(
        "/scan", "laser", np.arange(2000.0), np.arange(2000.0), _many_scans(2000)
    ),
    "CarmenLog": lambda: CarmenLog(
        _many_scans(5000),
        (Pose2D(0, 0, 0),) * 5000,
        (Pose2D(1, 0, 0),) * 5000,
        np.arange(5000.0),
        np.zeros((5000, 4)),
    ),
    "Table": lambda: Table("t", ("a", "b"), tuple((str(i), float(i)) for i in range(10_000))),
    "ScenarioResult": lambda: ScenarioResult(
        "x", 0, tuple(TrialResult(Trial("a", 0, i, i), {"e": 0.1}) for i in range(10_000)), ()
    ),
    "Scene": lambda: Scene("s", paths=tuple((str(i), np.zeros((2, 2))) for i in range(1000))),
    "LocalGrid": lambda: LocalGrid.from_points([[0.5, -0.2]], half_width=50.0, resolution=0.05),
    "OccupancyGrid": lambda: OccupancyGrid.empty(width=100.0, height=100.0, resolution=0.05),
    "LaserScan": lambda: LaserScan(
        np.ones(100_000), angle_min=0.0, angle_increment=1e-5, range_min=0.1, range_max=10.0
    ),
    "Path2D": lambda: Path2D(np.zeros((100_000, 2)), "world", cost=1.0, length=1.0, expanded=1),
    "World": lambda: World([Point(i, 0).buffer(0.1) for i in range(1000)]),
    "FieldDStar": lambda: FieldDStar(np.ones((500, 500))),
    "Trace": lambda: _simulation(duration=60.0).run(),
}


@pytest.mark.parametrize("name", list(_LARGE))
def test_repr_of_a_large_object_stays_short(name: str) -> None:
    # A trace recording 600 scans printed 1.3 MB; a bag of 2000 scans 20 MB. Now
    # at most three items of a tuple: three 720-beam scans are 30 kB.
    obj = _LARGE[name]()
    text = repr(obj)
    assert len(text) < 40_000, len(text)
    assert text.startswith(type(obj).__name__ + "(")


def test_a_shortened_repr_names_what_it_left_out() -> None:
    log = _LARGE["CarmenLog"]()
    text = repr(log)
    assert text.count("LaserScan(") == 3 and "... 4997 more ..." in text
    assert "laser_poses=(Pose2D(x=0.0, y=0.0, theta=0.0), Pose2D(" in text
    short = Table("t", ("a",), ((1.0,), (2.0,), (3.0,)))
    expected = "Table(title='t', columns=('a',), rows=((1.0,), (2.0,), (3.0,)), notes=())"
    assert repr(short) == expected


# -------------------------------------------------------------------- errors


@pytest.mark.parametrize("protocol", _PROTOCOLS)
def test_errors_cross_process_boundaries_whole(protocol: int) -> None:
    # A sweep's worker raising sends the exception back pickled.
    no_path = _pickled(protocol)(_no_path())
    assert type(no_path) is NoPathError and no_path.expanded == 3
    assert str(no_path) == "no path from start_cell (0, 0) to goal_cell (0, 2) (expanded 3 cells)"
    missing = _pickled(protocol)(DataNotFoundError(2, "not found", "map.yaml"))
    assert isinstance(missing, FileNotFoundError)
    assert (missing.errno, missing.strerror, missing.filename) == (2, "not found", "map.yaml")
    failed = _pickled(protocol)(_filter_error())
    assert type(failed) is FilterError and str(failed) == str(_filter_error())


def _plan_across_a_wall(note: str) -> None:
    """A sweep's trial failing in a worker process."""
    try:
        _no_path_raise()
    except NoPathError as exc:
        exc.add_note(note)
        raise


def _no_path_raise() -> None:
    raise _no_path()


@pytest.mark.skipif(
    "fork" not in multiprocessing.get_all_start_methods(), reason="needs the fork start method"
)
def test_a_worker_process_error_arrives_with_its_attributes_and_notes() -> None:
    context = multiprocessing.get_context("fork")  # inherits NUMBA_CACHE_DIR and the kernels
    with concurrent.futures.ProcessPoolExecutor(max_workers=1, mp_context=context) as pool:
        future = pool.submit(_plan_across_a_wall, "trial 3 of case 'wall'")
        with pytest.raises(NoPathError) as caught:
            future.result(timeout=120)
    assert caught.value.expanded == 3
    assert caught.value.__notes__ == ["trial 3 of case 'wall'"]
    assert str(caught.value).startswith("no path from start_cell (0, 0)")


def test_what_does_not_pickle_is_the_users_own_function_named_by_pickle() -> None:
    # Nothing of navkit's refuses pickling. A simulation (or MapPlanner, EKF step)
    # holding a lambda or a local function as its controller cannot be pickled,
    # as any object holding one: pickle names the function; deep copies work.
    simulation = Simulation(World(), _robot(), lambda obs: Twist2D(0.1, 0.0, 0.0),
                            start=(0.0, 0.0, 0.0), duration=0.1)  # fmt: skip
    with pytest.raises((pickle.PicklingError, AttributeError), match="lambda"):
        pickle.dumps(simulation)
    assert copy.deepcopy(simulation).run().poses.shape == (11, 3)
