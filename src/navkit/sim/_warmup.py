"""Compiling every navkit kernel ahead of first use: :func:`warmup`.

numba compiles a kernel on its first call and caches the machine code on disk
(``cache=True``), so only the first process after an install pays for it.
:func:`warmup` pays it on purpose, at install or image-build time: it calls
every public entry point that runs a kernel once, on tiny inputs and with each
option that selects a different kernel, so that every kernel is compiled for
the argument types navkit passes (navkit converts its inputs to float64 /
int64 arrays first, so one compilation serves every later call). The work is
split into named steps (:data:`WARMUP_STEPS`) that may run in parallel worker
processes; each step reports the kernels it compiled and the ones it only
loaded from the cache.
"""

from __future__ import annotations

import concurrent.futures
import math
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from navkit._shared.cores import usable_cores
from navkit._shared.frozen import frozen_setattr
from navkit._shared.jit import load_numba
from navkit._shared.text import as_text
from navkit._shared.validation import bounded_int, positive_float
from navkit.sim._pool import process_pool

__all__ = ["WARMUP_STEPS", "WarmupReport", "WarmupStep", "warmup"]

# What it returns is ignored: a progress bar's ``update`` may return a value.
Progress = Callable[[int, int], object]

#: Most worker processes :func:`warmup` may be asked for.
MAX_WORKERS = 1024


def _geometry() -> None:
    from navkit.geometry import integrate, rollout

    rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5], [0.5, 0.1, 0.0]]), 0.5)
    integrate((0.0, 0.0, 0.0), (1.0, 0.0, 0.5), 0.1)


def _room_scan(n: int = 90) -> Any:
    """A LaserScan from the centre of a 6 m x 4 m room."""
    from navkit.mapping import LaserScan

    angles = np.linspace(-math.pi, math.pi, n, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    return LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n, range_min=0.1, range_max=10.0
    )


def _mapping() -> None:
    from navkit.mapping import (
        LocalGrid,
        OccupancyGrid,
        ScanMapper,
        ScanMatcher,
        costmap,
        integrate_scan,
        traversal_costs,
    )

    scan = _room_scan()
    room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.1, origin=(-4.0, -3.0, 0.0))
    integrate_scan(room, scan, (0.0, 0.0, 0.0), hit=2.2, miss=-0.4)
    integrate_scan(room.copy(), scan, (0.0, 0.0, 0.0), exact=True, range_max=2.5)
    ScanMatcher().match(room, scan, (0.05, -0.05, 0.02))
    ScanMatcher(search_distance=0.1, search_angle=0.05, translation_weight=1.0,
                rotation_weight=1.0).match(room, scan, (0.05, -0.05, 0.02))  # fmt: skip
    mapper = ScanMapper(resolution=0.1)
    mapper.update(scan)
    mapper.update(scan, odometry=(0.5, 0.0, 0.95))
    costmap(room, robot_radius=0.1, inflation_radius=0.3)
    traversal_costs(room, robot_radius=0.1, inflation_radius=0.3)
    room.world_to_cell(np.array([[0.0, 0.0], [1.0, 1.0]]))
    # Two points: one is computed in Python (no kernel), and a batch's first call in a
    # warmed-up install compiled world_to_continuous_kernel (0.1-0.3 s).
    room.world_to_cell(np.array([[0.0, 0.0], [1.0, 1.0]]), continuous=True)
    room.cell_to_world(np.array([[1, 1]]))
    room.cells_near(np.array([[0.0, 0.0], [1.0, 1.0]]), robot_radius=0.3)
    LocalGrid.from_points(np.array([[0.3, 0.0]])).world_to_cell(np.array([[0.1, 0.1]]))


def _astar() -> None:
    from navkit.mapping import OccupancyGrid
    from navkit.planning import AStarPlanner, MapPlanner, astar, distance_field

    costs = np.ones((8, 8))
    costs[2:6, 4] = np.inf
    costs[1, 1] = 2.0
    astar(costs, (0, 0), (7, 7), method="auto")
    uniform = np.ones((8, 8))
    uniform[2:6, 4] = np.inf
    for method in ("jps", "auto"):
        for corner_cutting in (False, True):  # two kernels: the jump rules differ
            astar(uniform, (0, 0), (7, 7), method=method, corner_cutting=corner_cutting)
    for connectivity in (4, 8):
        for corner_cutting in (False, True):
            astar(costs, (0, 0), (7, 7), connectivity=connectivity, corner_cutting=corner_cutting)
            distance_field(costs, (7, 7), connectivity=connectivity, corner_cutting=corner_cutting)
    astar(costs, (0, 0), (7, 7), heuristic_weight=1.5)
    AStarPlanner(costs).plan((0, 0), (7, 0))
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    MapPlanner(grid, robot_radius=0.05).plan((0.15, 0.15), (1.05, 0.15))


def _field_dstar() -> None:
    from navkit.planning import FieldDStar, field_dstar

    costs = np.ones((10, 10))
    costs[3:7, 5] = 3.0
    planner = FieldDStar(costs)
    planner.plan((0, 0), (10, 7))
    planner.update_costs([(3, 1), (3, 2)], np.inf)
    planner.replan()
    planner.replan((1, 0))
    world = FieldDStar(costs, resolution=0.1, origin=(1.0, 2.0, 0.0))
    world.plan_world((1.05, 2.05), (1.85, 2.65))
    world.replan_world((1.15, 2.05))
    field_dstar(costs, (0, 0), (10, 7), interpolate=False, lookahead=False, smooth=False)


def _reactive() -> None:
    from navkit.mapping import LocalGrid
    from navkit.planning import (
        greedy_step,
        piecewise_repulsive_force_from_scan,
        repulsive_force_from_scan,
    )

    scan = _room_scan(36)
    repulsive_force_from_scan(scan, influence_radius=2.5)
    piecewise_repulsive_force_from_scan(scan, spread=2.0)
    # A sensor off the robot's centre: each beam's end point pushes (two kernels more).
    repulsive_force_from_scan(scan, influence_radius=2.5, mount=(-0.1, 0.0, 0.0))
    piecewise_repulsive_force_from_scan(scan, spread=2.0, mount=(-0.1, 0.0, 0.0))
    greedy_step(LocalGrid.from_points(np.array([[0.2, 0.0]])), (2.0, 0.0))
    greedy_step(LocalGrid.from_points(np.array([[0.2, 0.0]])), (2.0, 0.0), require_progress=True)
    # A return in the robot's own cell: greedy_step frees that cell in a copy.
    greedy_step(LocalGrid.from_points(np.array([[0.0, 0.0]])), (2.0, 0.0))


def _control() -> None:
    from navkit.control import (
        FollowTheCarrot,
        OnOffTracker,
        PotentialFieldController,
        RegulatedPurePursuit,
        limit_velocity_change,
    )
    from navkit.geometry import Pose2D
    from navkit.mapping import OccupancyGrid

    path = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[10, 15] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(-0.5, -0.5, 0.0))
    pose = Pose2D(0.0, 0.05, 0.0)
    trackers: list[Any] = [
        RegulatedPurePursuit(clearance=grid),
        RegulatedPurePursuit(drive="omni"),
        FollowTheCarrot(),
        FollowTheCarrot(drive="omni"),
        OnOffTracker(),
        OnOffTracker(drive="omni"),
    ]
    for tracker in trackers:
        tracker.set_path(path, goal_yaw=1.0)
        tracker.step(pose, 0.05)
    for drive in ("omni", "diff"):
        PotentialFieldController(drive=drive).step(pose, Pose2D(1.0, 0.0, 0.0), dt=0.05)
    limit_velocity_change([0.0, 0.0, 0.0], [1.0, 0.0, 0.5], max_accel=1.0, max_decel=2.0, dt=0.1)


def _estimation() -> None:
    from navkit.estimation import (
        DiffOdometry,
        ExtendedKalmanFilter,
        MeasurementLog,
        OmniOdometry,
        PlanarFusion,
    )
    from navkit.kinematics import DiffDrive, OmniDrive

    fusion = PlanarFusion(gate_probability=0.99)
    fusion.predict(0.01)
    fusion.update_odometry(0.02, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    fusion.update_speed(0.03, 1.0, variance=1e-4)
    fusion.update_yaw(0.04, 0.01, variance=1e-3)
    fusion.update_yaw_rate(0.05, 0.1, variance=1e-4)
    fusion.update_acceleration(0.06, 0.0, variance=1e-2)
    t = np.linspace(0.0, 0.4, 5)
    log = MeasurementLog.from_streams(
        odometry=(t, np.ones(5), np.zeros(5)), yaw=(t, np.zeros(5)), yaw_rate=(t, np.zeros(5)),
        acceleration=(t, np.zeros(5)),
    )  # fmt: skip
    PlanarFusion().update_batch(log)
    PlanarFusion(gate_probability=0.99).update_batch(log)
    ekf = ExtendedKalmanFilter([0.0, 1.0, 0.0], np.eye(3), angle_states=(2,))
    jac = np.eye(3)
    jac[0, 1] = 0.1
    ekf.predict(lambda x: jac @ x, jac, 0.01 * np.eye(3))
    # A positive definite Q that is not diagonally dominant (a constant-velocity
    # model's) is kept by a kernel of its own.
    ekf.predict(lambda x: jac @ x, jac, [[0.01, 0.012, 0.0], [0.012, 0.02, 0.0], [0.0, 0.0, 0.01]])
    ekf.update([0.1], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.01]])
    ekf.update([0.1, 0.0], lambda x: x[[0, 2]], np.array([[1.0, 0, 0], [0, 0, 1.0]]), np.eye(2))
    # A measurement of two components the gate rejects: its retry checks S in a
    # kernel of its own.
    ekf.update([1e3, 0.0], lambda x: x[[0, 2]], np.array([[1.0, 0, 0], [0, 0, 1.0]]), np.eye(2),
               gate=1.0)  # fmt: skip
    diff = DiffDrive(track=0.3, wheel_radius=0.05)
    for method in ("arc", "midpoint", "first_order"):
        odometry = DiffOdometry(diff, ticks_per_rev=1024.0, bits=16, method=method)
        odometry.update(10, 12)
        odometry.update_batch([20, 30], [22, 35])
    omni = OmniDrive([0.0, 2.0944, 4.1888], wheel_radius=0.05, base_radius=0.2)
    OmniOdometry(omni).update([0.1, 0.1, 0.1], 0.0)
    OmniOdometry(omni).update_batch(np.full((2, 3), 0.1), [0.0, 0.1])


def _simulation() -> None:
    from shapely.geometry import box

    from navkit.estimation import DiffOdometry, OmniOdometry, PlanarFusion
    from navkit.geometry import Twist2D
    from navkit.kinematics import DiffDrive, OmniDrive
    from navkit.mapping import OccupancyGrid
    from navkit.sim._lidar import Lidar
    from navkit.sim._robot import Robot
    from navkit.sim._sensors import Compass, Imu
    from navkit.sim._simulation import Simulation
    from navkit.sim._world import Circle, MovingObstacle, World

    def forward(_observation: Any) -> Twist2D:
        return Twist2D(0.4, 0.0, 0.2)

    def dash(_observation: Any) -> Twist2D:
        return Twist2D(4.0, 0.0, 0.0)

    occupied = np.zeros((30, 40), dtype=bool)
    occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    moving = MovingObstacle.constant_velocity(0.2, start_xy=(3.0, 2.0), velocity_xy=(-0.1, 0.0))
    # Segments and circles alone, and a grid with moving obstacles: a world of the
    # first kind runs kernels compiled without the grid's and moving obstacles' code.
    worlds = [
        World([box(0.0, 0.0, 4.0, 3.0).exterior, box(3.0, 0.5, 3.5, 1.0),
               Circle(np.array([2.5, 2.0]), 0.2)]),
        World(grid=grid, moving=[moving]),
    ]  # fmt: skip
    diff = DiffDrive(track=0.3, wheel_radius=0.05)
    omni = OmniDrive([0.0, 2.0944, 4.1888], wheel_radius=0.05, base_radius=0.2)
    sensors: dict[str, Any] = {"lidar": Lidar(n_beams=16), "compass": Compass(), "imu": Imu()}
    for world in worlds:
        robots: list[tuple[Robot, PlanarFusion | DiffOdometry | OmniOdometry]] = [
            (Robot(drive=diff, footprint=0.15, max_wheel_acceleration=40.0, **sensors),
             PlanarFusion()),
            (Robot(drive=diff, footprint=[[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]],
                   wheel_slip=0.01, **sensors),
             DiffOdometry(diff, ticks_per_rev=1024.0, bits=16)),
            (Robot(drive=omni, footprint=0.15, max_wheel_speed=20.0, **sensors),
             OmniOdometry(omni)),
        ]  # fmt: skip
        # A path of 2 vertices and one of over 32 segments: the cross-track distances
        # of short and long reference paths are two kernels.
        long_path = np.column_stack([np.linspace(1.0, 2.0, 40), np.ones(40)])
        short_path = np.array([[1.0, 1.0], [2.0, 1.0]])
        references = (short_path, long_path, short_path)
        for (robot, estimator), reference in zip(robots, references, strict=True):
            Simulation(
                world, robot, forward, start=(1.0, 1.0, 0.0), goal=(1.5, 1.2), estimator=estimator,
                duration=0.3, reference_path=reference,
            ).run()  # fmt: skip
        # Steps long for the footprint (0.4 m) run the kernels' variants that check
        # along each step.
        for footprint in (0.15, [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]):
            Simulation(
                world, Robot(drive=diff, footprint=footprint, encoders=None), dash,
                start=(1.0, 1.0, 0.0), rate=10.0, control_rate=10.0, duration=0.3,
            ).run()  # fmt: skip
        world.clearance(0.15, (1.0, 1.0, 0.0))
        world.collides(0.15, (1.0, 1.0, 0.0))
        world.raycast((1.0, 1.0, 0.0), np.linspace(-1.0, 1.0, 5), range_max=5.0)


def _scenarios() -> None:
    # The scenarios' own kernels (navkit run): the diff-astar localiser's scan match,
    # compiled at its first scan (0.5 s of the house route matches a few).
    from navkit.sim.scenarios import DiffAStar

    scenario = DiffAStar(parts=("house",), building="corridor", noise=False, duration=0.5)
    scenario.run_trial(scenario.trials(1)[0])


#: The warm-up steps, ``name: (function, relative cost)``; costly steps start first.
_STEPS: dict[str, tuple[Callable[[], None], float]] = {
    "estimation": (_estimation, 7.5),
    "field_dstar": (_field_dstar, 7.0),
    "astar": (_astar, 6.0),
    "simulation": (_simulation, 5.5),
    "mapping": (_mapping, 4.0),
    "scenarios": (_scenarios, 2.0),
    "control": (_control, 1.5),
    "reactive": (_reactive, 0.5),
    "geometry": (_geometry, 0.5),
}

WARMUP_STEPS: tuple[str, ...] = tuple(_STEPS)
"""Names of the warm-up steps in starting order (``only=`` of :func:`warmup` takes a subset)."""


@frozen_setattr
@dataclass(frozen=True, slots=True)
class WarmupStep:
    """One step of :func:`warmup`: the kernels it compiled and what it cost.

    Attributes
    ----------
    name : str
        The step (one of :data:`WARMUP_STEPS`).
    compiled : tuple of str
        The kernels (``module.function``) this step compiled, sorted.
    loaded : tuple of str
        The kernels it loaded from numba's on-disk cache instead, sorted.
    seconds : float
        Wall-clock time of the step, s.
    cpu_seconds : float
        CPU time of the step in the process that ran it, s.

    Raises
    ------
    TypeError
        ``name`` not a str; ``compiled`` or ``loaded`` not a sequence of str;
        a time not a real number.
    ValueError
        ``seconds`` or ``cpu_seconds`` negative, NaN or infinite.

    Examples
    --------
    >>> step = WarmupStep("geometry", ("navkit.geometry._integrate_kernels.rollout_kernel",),
    ...                   ("navkit.geometry._integrate_kernels.integrate_kernel",), 0.9, 0.8)
    >>> len(step.compiled), len(step.loaded), step.seconds
    (1, 1, 0.9)
    >>> WarmupStep("geometry", (), (), -1.0, 0.0)
    Traceback (most recent call last):
    ...
    ValueError: seconds must be ...
    """

    name: str
    compiled: tuple[str, ...]
    loaded: tuple[str, ...]
    seconds: float
    cpu_seconds: float

    def __post_init__(self) -> None:
        # Plain str: an np.str_ printed as np.str_('astar') in the record's repr.
        object.__setattr__(self, "name", as_text(self.name, "name"))
        object.__setattr__(self, "compiled", _names(self.compiled, "compiled"))
        object.__setattr__(self, "loaded", _names(self.loaded, "loaded"))
        seconds = positive_float(self.seconds, "seconds", allow_zero=True)
        object.__setattr__(self, "seconds", seconds)
        cpu = positive_float(self.cpu_seconds, "cpu_seconds", allow_zero=True)
        object.__setattr__(self, "cpu_seconds", cpu)


@frozen_setattr
@dataclass(frozen=True, slots=True)
class WarmupReport:
    """What :func:`warmup` compiled, and how long it took.

    Attributes
    ----------
    steps : tuple of WarmupStep
        One per step run, in :data:`WARMUP_STEPS` order.
    seconds : float
        Wall-clock time of the whole warm-up, s.
    workers : int
        Processes that ran the steps (1: the calling process).

    Raises
    ------
    TypeError
        ``steps`` not a sequence of WarmupStep; ``seconds`` not a real number,
        ``workers`` not an integer.
    ValueError
        ``seconds`` negative, NaN or infinite; ``workers`` outside [1, 1024].

    Examples
    --------
    >>> rollout = "navkit.geometry._integrate_kernels.rollout_kernel"
    >>> search = "navkit.planning.grid._astar_kernels.grid_search"
    >>> report = WarmupReport((WarmupStep("astar", (search,), (rollout,), 1.5, 1.4),
    ...                        WarmupStep("geometry", (rollout,), (), 0.5, 0.4)), 1.6, 2)
    >>> report.compiled, report.loaded  # compiled by a step: not counted as loaded
    (('navkit.geometry._integrate_kernels.rollout_kernel',
      'navkit.planning.grid._astar_kernels.grid_search'), ())
    >>> round(report.cpu_seconds, 6), report.seconds, report.workers  # CPU s of all steps
    (1.8, 1.6, 2)
    """

    steps: tuple[WarmupStep, ...]
    seconds: float
    workers: int

    def __post_init__(self) -> None:
        steps: object = self.steps
        if isinstance(steps, (str, bytes)) or not isinstance(steps, Sequence):
            raise TypeError(f"steps must be a sequence of WarmupStep, got {type(steps).__name__}")
        steps = tuple(steps)
        for step in steps:
            if not isinstance(step, WarmupStep):
                raise TypeError(f"steps must hold WarmupStep, got {type(step).__name__}")
        object.__setattr__(self, "steps", steps)
        seconds = positive_float(self.seconds, "seconds", allow_zero=True)
        object.__setattr__(self, "seconds", seconds)
        object.__setattr__(self, "workers", bounded_int(self.workers, "workers", 1, MAX_WORKERS))

    @property
    def compiled(self) -> tuple[str, ...]:
        """Every kernel compiled by some step, sorted (a kernel may be compiled by two)."""
        return tuple(sorted({k for s in self.steps for k in s.compiled}))

    @property
    def loaded(self) -> tuple[str, ...]:
        """Every kernel loaded from the cache and compiled by no step, sorted."""
        compiled = set(self.compiled)
        return tuple(sorted({k for s in self.steps for k in s.loaded} - compiled))

    @property
    def cpu_seconds(self) -> float:
        """CPU time of all steps together, s (the compilation's total cost)."""
        return math.fsum(s.cpu_seconds for s in self.steps)


def _names(value: object, name: str) -> tuple[str, ...]:
    """``value`` as a tuple of str (kernel names)."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
        raise TypeError(f"{name} must be a sequence of str, got {type(value).__name__}")
    out = tuple(value)
    for item in out:
        if not isinstance(item, str):
            raise TypeError(f"{name} must hold str, got {type(item).__name__}")
    # Plain str: np.str_ kernel names printed as np.str_('...') in the record's repr.
    return tuple(str.__str__(item) for item in out)


def _dispatchers() -> dict[str, Any]:
    """Every numba kernel defined in an imported navkit module, by ``module.function``."""
    load_numba()  # the kernels are stand-ins until then
    from numba.core.dispatcher import Dispatcher

    found: dict[str, Any] = {}
    for name, module in list(sys.modules.items()):
        if not name.startswith("navkit.") or module is None:
            continue
        for value in list(vars(module).values()):
            if isinstance(value, Dispatcher) and value.py_func.__module__ == name:
                found[f"{name}.{value.py_func.__name__}"] = value
    return found


def _cache_counts() -> dict[str, tuple[int, int]]:
    """``(cache hits, cache misses)`` of every navkit kernel so far in this process."""
    counts: dict[str, tuple[int, int]] = {}
    for key, dispatcher in _dispatchers().items():
        stats = dispatcher.stats
        counts[key] = (sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))
    return counts


def _run_step(name: str) -> WarmupStep:
    """Run one step and see, by numba's cache counters, what it compiled or loaded."""
    function = _STEPS[name][0]
    before = _cache_counts()
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    cpu = time.process_time() - cpu
    wall = time.perf_counter() - wall
    compiled: list[str] = []
    loaded: list[str] = []
    for key, (hits, misses) in _cache_counts().items():
        hits0, misses0 = before.get(key, (0, 0))
        if misses > misses0:
            compiled.append(key)
        elif hits > hits0:
            loaded.append(key)
    return WarmupStep(name, tuple(sorted(compiled)), tuple(sorted(loaded)), wall, cpu)


def _step_names(only: Iterable[str] | None) -> list[str]:
    if only is None:
        return list(WARMUP_STEPS)
    if isinstance(only, (str, bytes)) or not isinstance(only, Iterable):
        raise TypeError(f"only must be an iterable of step names or None, got {only!r:.60}")
    chosen: set[str] = set()
    for item in only:
        if not isinstance(item, str):
            raise TypeError(f"only must hold step names (str), got {type(item).__name__}")
        if item not in _STEPS:
            raise ValueError(f"only: unknown step {item!r:.40}; the steps are "
                             f"{', '.join(WARMUP_STEPS)}")  # fmt: skip
        chosen.add(item)
    return [name for name in WARMUP_STEPS if name in chosen]


def _worker_count(workers: object, steps: int) -> int:
    if workers is None:
        return max(1, min(usable_cores(), steps))
    return max(1, min(bounded_int(workers, "workers", 1, MAX_WORKERS, or_none=True), steps))


def warmup(
    *,
    workers: int | None = None,
    progress: Progress | None = None,
    only: Iterable[str] | None = None,
) -> WarmupReport:
    """Compile every navkit kernel now, so that no later call waits for numba.

    Calls each public entry point that runs a numba kernel once on tiny inputs
    (planning, mapping, estimation, control, the simulator and the scenarios of
    ``navkit run``, with every option that selects another kernel). numba caches
    the machine code on disk (``cache=True``, see ``docs/compilation.md``), so
    every later process, including this one, loads it in milliseconds instead of
    compiling. Kernels already cached are only loaded, which takes a second or
    two in all. Run it once at install or image-build time (``navkit warmup`` on
    the command line) or in a long-running program's start-up.

    One family of kernels is compiled per size: :class:`~navkit.estimation.ExtendedKalmanFilter`
    specialises its predict for the state's size n and its update for each
    (n, measurement size m). The warm-up compiles n = 3 with m = 1 and 2; a
    filter of other sizes compiles its own at its first predict and update
    (0.6-0.7 s CPU for n = 4 or 5, once per cache): warm those by building the
    filter and calling both once at start-up.

    Parameters
    ----------
    workers : int, optional
        Processes to compile in: the steps are shared among a pool of this many
        worker processes (each step in one process, costly steps first). 1 runs
        everything in this process. Default: every core this process may use
        (at most one per step). A ``KeyboardInterrupt`` (Ctrl-C, which the
        workers leave to this process) kills the workers at once, and they end
        when this process dies. Under the ``spawn`` and ``forkserver`` start
        methods (macOS and Windows; Linux from Python 3.14) the workers start
        afresh: a script must call ``warmup`` under
        ``if __name__ == "__main__":``, as for :func:`sweep`.
    progress : callable, optional
        ``progress(done, total)``, called with ``done = 0`` first and after
        every step, in this process.
    only : iterable of str, optional
        Run only these steps (names from :data:`WARMUP_STEPS`), e.g.
        ``only=["astar"]`` for a program that only plans with A*. Default: all.

    Returns
    -------
    WarmupReport
        The steps run (kernels compiled and loaded, wall and CPU seconds each),
        the total wall time and the number of processes.

    Raises
    ------
    TypeError
        ``workers`` is not an integer, ``progress`` not callable, ``only`` not
        an iterable of str.
    ValueError
        ``workers`` outside [1, 1024]; an unknown step name in ``only``.

    Examples
    --------
    >>> report = warmup(workers=1, only=["geometry"])
    >>> [step.name for step in report.steps], report.workers
    (['geometry'], 1)
    >>> set(report.compiled) <= {k for k in report.steps[0].compiled}  # kernel names
    True
    >>> report.seconds >= report.steps[0].seconds >= 0.0
    True
    """
    names = _step_names(only)
    n = _worker_count(workers, len(names))
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable or None, got {type(progress).__name__}")
    total = len(names)
    start = time.perf_counter()
    if progress is not None:
        progress(0, total)
    results: dict[str, WarmupStep] = {}
    if n == 1:
        for name in names:
            results[name] = _run_step(name)
            if progress is not None:
                progress(len(results), total)
    else:
        by_cost = sorted(names, key=lambda name: -_STEPS[name][1])
        with process_pool(n) as pool:
            futures = {pool.submit(_run_step, name): name for name in by_cost}
            for future in concurrent.futures.as_completed(futures):
                results[futures[future]] = future.result()
                if progress is not None:
                    progress(len(results), total)
    seconds = time.perf_counter() - start
    return WarmupReport(tuple(results[name] for name in names), seconds, n)
