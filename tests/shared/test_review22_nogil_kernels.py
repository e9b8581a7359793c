"""Which kernels release the GIL, that they really do, and Ctrl-C beside them.

navkit's long kernels are compiled with ``nogil=True``
(``navkit._shared.jit.RELEASES_GIL``): a Field D* plan in one ROS 2 callback
held every other callback of the node up to 590 ms while it held the GIL.
Kernels of microseconds keep it (issue 17's small calls: releasing it costs
about 40 ns a call, and taking it back waits while another thread runs
Python). Checked here: the table of releasing kernels, that each carries the
option in its own source file (numba's cache keys machine code on that file
alone, so a kernel given the option through another file would keep loading
code compiled with the GIL held), that the public calls built on them let
another thread run Python meanwhile while small calls do not (without
timing anything: ``thread_runs.lines_beside_python``), and that Ctrl-C still
reaches the main thread during and beside a long plan.
"""

from __future__ import annotations

import importlib
import inspect
import math
import os
import pkgutil
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest

import navkit
from navkit._shared.jit import RELEASES_GIL, load_numba
from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, integrate_scan
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, distance_field
from navkit.sim import Lidar, World
from thread_runs import lines_beside_python

#: Every kernel Python calls that releases the GIL, by module (under navkit).
RELEASING = {
    "estimation._fusion_kernels": {"planar_run"},
    "mapping._cells_near_kernels": {"cells_near_kernel"},
    "mapping._edt_kernels": {"band_distances"},
    "mapping._raycast_kernels": {"integrate_beams"},
    "mapping._scan_matcher_kernels": {"match_level", "correlative_search_kernel"},
    "planning.grid._astar_kernels": {"grid_search"},
    "planning.grid._distance_field_kernels": {"pad_grid", "bucket_field"},
    "planning.grid._field_path_kernels": {"extract_path"},
    "planning.grid._jps_cut_kernels": {"jps_cut_search"},
    "planning.grid._jps_kernels": {"_build_tables", "jps_search"},
    "planning.grid._limits": {"_scan_cost_bits"},
    "planning.grid._polyline_kernels": {"_polyline"},
    "sim._lidar_kernels": {"cast_edge_rays", "cast_occupancy_rays"},
    "sim._polyline_distance_kernels": {
        "point_polyline_distances",
        "point_polyline_distances_chunked",
    },
}


def _dispatchers() -> dict[tuple[str, str], Any]:
    """Every numba dispatcher defined at module level in navkit, by (module, name)."""
    for info in pkgutil.walk_packages(navkit.__path__, "navkit."):
        if info.name.startswith(("navkit.cli", "navkit.plot")) or ".scenarios." in info.name:
            continue  # scenarios are imported below; the command line and plots have no kernels
        try:
            importlib.import_module(info.name)
        except ImportError:  # an optional dependency (the bag reader's rosbags, say)
            continue
    importlib.import_module("navkit.sim.scenarios._diff_astar_kernels")
    load_numba()
    from numba.core.dispatcher import Dispatcher

    found: dict[tuple[str, str], Any] = {}
    for name, module in list(sys.modules.items()):
        if not name.startswith("navkit."):
            continue
        for attr, value in vars(module).items():
            if isinstance(value, Dispatcher) and value.py_func.__module__ == name:
                found[(name.removeprefix("navkit."), attr)] = value
    return found


def test_the_long_kernels_release_the_gil_and_no_other_does() -> None:
    kernels = _dispatchers()
    assert len(kernels) > 100  # every kernel module was found
    releasing = {
        key
        for key, d in kernels.items()
        if d.targetoptions.get("nogil") and not d.targetoptions.get("no_cpython_wrapper")
    }
    expected = {(module, name) for module, names in RELEASING.items() for name in names}
    assert releasing == expected
    # A helper has no Python wrapper, where the GIL would be released: none asks.
    assert not [key for key, d in kernels.items() if d.targetoptions.get("nogil")
                and d.targetoptions.get("no_cpython_wrapper")]  # fmt: skip
    assert RELEASES_GIL == {"nogil": True}


@pytest.mark.parametrize("module", sorted(RELEASING))
def test_each_releasing_kernel_has_the_option_in_its_own_file(module: str) -> None:
    """numba's cache is keyed on the kernel's own source file, not on its options."""
    source = inspect.getsource(importlib.import_module("navkit." + module))
    lines = source.splitlines()
    for name in RELEASING[module]:
        at = next(i for i, line in enumerate(lines) if line.startswith(f"def {name}("))
        decorator = lines[at - 1]
        assert decorator in ("@njit_released", "@njit_cached_released", "@_kernel"), name
        if decorator == "@_kernel":
            assert "_kernel = typed_njit(**KERNEL_OPTIONS, **RELEASES_GIL)" in lines


# ----------------------------------------------------------------------------- real releases
def _maze(n: int, seed: int) -> np.ndarray:
    costs = np.random.default_rng(seed).uniform(1.0, 3.0, (n, n))
    costs[n // 8 : n - n // 8, n // 2] = np.inf
    return costs


def _room_scan(beams: int = 720) -> LaserScan:
    return LaserScan(
        np.full(beams, 3.0), angle_min=-math.pi, angle_increment=2 * math.pi / beams,
        range_min=0.1, range_max=8.0,
    )  # fmt: skip


def _public_calls() -> dict[str, Callable[[], object]]:
    costs = _maze(500, 1)
    planner = AStarPlanner(costs)
    uniform = AStarPlanner(np.where(np.isinf(costs), np.inf, 1.0), method="jps")
    dstar = FieldDStar(costs)
    occupied = np.zeros((400, 400), dtype=bool)
    occupied[50:350, 200] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    wide = OccupancyGrid.from_occupancy(np.tile(occupied, (4, 4)), resolution=0.05)
    map_planner = MapPlanner(grid, robot_radius=0.2)
    empty = OccupancyGrid.empty(width=20.0, height=20.0, resolution=0.02)
    scan = _room_scan()
    room = OccupancyGrid.empty(width=8.0, height=8.0, resolution=0.05)
    for _ in range(3):
        integrate_scan(room, scan, (4.0, 4.0, 0.0))
    matcher = ScanMatcher(search_distance=0.3, search_angle=0.3)
    levels = matcher.pyramid(room)
    world = World(grid=grid)
    lidar = Lidar(n_beams=2000, range_max=30.0, noise=None)
    t = np.linspace(0.0, 200.0, 40_001)
    log = MeasurementLog.from_streams(odometry=(t, np.full(t.size, 0.5), np.full(t.size, 0.1)))
    return {
        "astar": lambda: planner.plan((0, 0), (499, 499)),
        "jps": lambda: uniform.plan((0, 0), (499, 499)),
        "distance_field": lambda: distance_field(costs, (0, 0)),
        "field_dstar": lambda: FieldDStar(costs).plan((0, 0), (499, 499)),
        "field_dstar_kept": lambda: dstar.plan((0, 0), (499, 499)),
        "map_planner": lambda: map_planner.plan((1.0, 1.0), (19.0, 1.0)),
        "integrate_scan": lambda: integrate_scan(empty.copy(), _room_scan(4000), (10.0, 10.0, 0.0)),
        "scan_matcher": lambda: matcher.match(levels, scan, (4.05, 3.95, 0.05)),
        "lidar": lambda: lidar.scan(world, (1.0, 1.0, 0.3)),
        "update_batch": lambda: PlanarFusion().update_batch(log),
        "inflate": lambda: wide.inflate(0.3),
        "obstacle_distance": wide.obstacle_distance,
    }


@pytest.fixture(scope="module")
def public_calls() -> dict[str, Callable[[], object]]:
    calls = _public_calls()
    for call in calls.values():
        call()  # compiled (or loaded) before anything is observed
    return calls


#: The kernel each public call is seen in while another thread runs Python.
PUBLIC = {
    "astar": "grid_search",
    "jps": " = search",  # jps_search, by the name plan gives it
    "distance_field": "bucket_field",
    "field_dstar": "extract_path",
    "field_dstar_kept": "extract_path",
    "map_planner": "grid_search",
    "integrate_scan": "integrate_beams",
    "scan_matcher": "match_level",
    "lidar": "cast_occupancy_rays",
    "update_batch": "planar_run",
    "inflate": "band_distances",
    "obstacle_distance": "band_distances",
}


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_long_public_calls_let_other_threads_run_during_their_kernels(
    public_calls: dict[str, Callable[[], object]], name: str
) -> None:
    # A short kernel (jump point search takes about a millisecond here) may
    # return before the woken main thread takes the GIL, on a busy machine at
    # every try of one round: a few rounds, until it is seen.
    for _ in range(8):
        lines = lines_beside_python(public_calls[name])
        if any(PUBLIC[name] + "(" in line for line in lines):
            break
    assert any(PUBLIC[name] + "(" in line for line in lines), lines


def test_small_calls_keep_the_gil() -> None:
    """The control: calls of small kernels are never seen inside their kernels."""
    grid = OccupancyGrid.empty(width=10.0, height=10.0, resolution=0.1)
    points = np.random.default_rng(0).uniform(0.0, 10.0, (1_000_000, 2))
    grid.world_to_cell(points)
    fusion = PlanarFusion()
    clock = iter(range(1, 10**9))

    def imu_messages() -> None:
        for _ in range(3000):
            fusion.update_yaw_rate(next(clock) * 0.005, 0.1, variance=1e-4)

    imu_messages()
    assert lines_beside_python(lambda: grid.world_to_cell(points)) == set()
    assert lines_beside_python(imu_messages) == set()


# ----------------------------------------------------------------------------- Ctrl-C
@pytest.fixture
def default_sigint() -> Iterator[None]:
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)


posix_only = pytest.mark.skipif(
    sys.platform == "win32" or not hasattr(signal, "pthread_kill"),
    reason="needs POSIX signals sent to a thread",
)


@posix_only
@pytest.mark.usefixtures("default_sigint")
def test_ctrl_c_during_a_long_plan_in_the_main_thread() -> None:
    """Sent by another thread (which runs meanwhile); arrives once the kernel returns."""
    costs = _maze(400, 2)
    planner = AStarPlanner(costs, method="astar")
    reference = planner.plan((0, 0), (399, 399))
    main = threading.get_ident()
    entering, sent = threading.Event(), threading.Event()

    def interrupt() -> None:
        entering.wait()
        signal.pthread_kill(main, signal.SIGINT)
        sent.set()

    killer = threading.Thread(target=interrupt)
    killer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            entering.set()
            for _ in range(50):
                planner.plan((0, 0), (399, 399))
            sent.wait()  # the plans ended first: the interrupt lands here
            threading.Event().wait(60.0)
    finally:
        killer.join()
    again = planner.plan((0, 0), (399, 399))
    assert again.cells.tobytes() == reference.cells.tobytes() and again.cost == reference.cost


@posix_only
@pytest.mark.usefixtures("default_sigint")
def test_ctrl_c_in_the_main_thread_while_a_worker_plans() -> None:
    """The main thread gets its KeyboardInterrupt; the worker's plans are whole."""
    costs = _maze(400, 3)
    planner = AStarPlanner(costs, method="astar")
    reference = planner.plan((0, 0), (399, 399)).cells.tobytes()
    started = threading.Event()
    paths: list[bytes] = []
    errors: list[BaseException] = []

    def work() -> None:
        started.set()
        try:
            for _ in range(20):
                paths.append(planner.plan((0, 0), (399, 399)).cells.tobytes())
        except BaseException as exc:
            errors.append(exc)

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        worker.join()  # interrupted: the handler runs in the main thread
        threading.Event().wait(60.0)
    worker.join()
    assert errors == [] and paths == [reference] * 20

