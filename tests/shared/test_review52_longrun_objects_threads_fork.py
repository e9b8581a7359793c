"""A long-running node's objects in threads, after a fork, in numba's heap (review 52, LONGRUN).

A ROS 2 node with a ``MultiThreadedExecutor`` gives each callback thread its own
planner, grid, mapper, filter, tracker and controller; a process forked from it
(multiprocessing's ``fork``) after their first use, while other threads plan,
makes its own. Different objects in different threads must never interfere (no
shared scratch or memo between them): each thread's answers are those of the
same calls made alone, bit for bit, with Python switching threads every
microsecond and the long kernels running at once without the GIL; a child
forked meanwhile answers as its parent. And nothing a call allocates in numba's
own heap (invisible to ``tracemalloc``, which review 48's long runs measured) is
left behind: after hundreds of calls of each entry a node calls at its rates,
refused calls included, numba's allocation counters balance.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

_SRC = str(Path(__file__).resolve().parents[2] / "src")
_ROOM = str(Path(__file__).resolve().parents[1] / "mapping")

# One thread's work: its own objects of every kind, each used as a node uses it.
_JOB = """
import hashlib, math, sys
import numpy as np
sys.path.insert(0, ROOM)
from room_scans import room_scan
from navkit.control import PotentialFieldController, RegulatedPurePursuit
from navkit.errors import NoPathError
from navkit.estimation import PlanarFusion
from navkit.mapping import OccupancyGrid, ScanMapper, integrate_scan
from navkit.planning import FieldDStar, astar, distance_field, repulsive_force_from_scan

def digest(*arrays):
    h = hashlib.sha1()
    for a in arrays:
        h.update(np.ascontiguousarray(np.asarray(a, dtype=float)).tobytes())
    return h.hexdigest()[:16]

def job(seed, reps):
    rng = np.random.default_rng(seed)
    n = 40 + 10 * seed
    costs = rng.uniform(1.0, 4.0, (n, n))
    costs[rng.random((n, n)) < 0.1] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    planner = FieldDStar(costs)
    grid = OccupancyGrid.empty(width=10.0, height=10.0, resolution=0.05, origin=(-5.0, -5.0, 0.0))
    mapper = ScanMapper(resolution=0.1)
    fusion = PlanarFusion(history=0.5 * seed)
    tracker, controller = RegulatedPurePursuit(), PotentialFieldController()
    out, t = [], 0.0
    for r in range(reps):
        try:
            path = planner.plan((0, 0), (n, n)) if r == 0 else planner.replan((r % n, 0))
            out.append(digest(path.points, [path.cost]))
        except (NoPathError, ValueError) as error:
            out.append(type(error).__name__)
        cells = rng.integers(0, n, (4, 2))
        planner.update_costs(cells, rng.choice([1.0, 2.0, np.inf], 4))
        try:
            found = astar(costs, (0, 0), (n - 1, n - 1))
            out.append(digest(found.points, [found.cost]))
        except NoPathError:
            out.append("NoPathError")
        out.append(digest(distance_field(costs, (n - 1, n - 1))))
        pose = (0.1 * math.sin(r + seed), 0.1 * math.cos(r), 0.01 * r)
        scan = room_scan(*pose, beams=180 + 20 * seed)
        integrate_scan(grid, scan, pose)
        mapper.update(scan, odometry=pose)
        force = repulsive_force_from_scan(scan, k_rep=0.1, influence_radius=1.0)
        out.append(digest(mapper.pose.as_array(), force))
        for k in range(20):
            t += 0.01
            fusion.update_odometry(t, 0.5, 0.1 * seed, v_variance=1e-3, omega_variance=1e-3)
            fusion.update_yaw(t - 0.003, 0.001 * k, variance=1e-3)
        out.append(digest(fusion.x, fusion.P))
        s = np.linspace(0.0, 3.0, 30)
        tracker.set_path(np.column_stack([5.0 / 3.0 * s, 0.2 * seed * np.sin(s)]))
        out.append(digest(tracker.step((0.1 * r % 5, 0.0, 0.0), 0.05).as_array()))
        command = controller.step((0.0, 0.0, 0.0), (2.0, 1.0 + seed, 0.0), 0.05, obstacles=scan)
        out.append(digest(command.as_array()))
    out.append(digest(grid.logodds, mapper.map.logodds))
    return out
"""

_THREADS = """
import threading
sys.setswitchinterval(1e-6)
alone = [job(seed, 12) for seed in range(3)]
for trial in range(2):
    got = [None] * 3
    def run(i):
        got[i] = job(i, 12)
    threads = [threading.Thread(target=run, args=(i,)) for i in range(3)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert got == alone, [i for i in range(3) if got[i] != alone[i]]
print("ok")
"""

_FORK = """
import os, pickle, threading, time
sys.setswitchinterval(1e-5)
alone = [job(seed, 8) for seed in range(2)]
stop = []
def busy(i):
    while not stop:
        job(i, 3)
threads = [threading.Thread(target=busy, args=(i,), daemon=True) for i in (1, 2)]
for thread in threads:
    thread.start()
time.sleep(0.5)
for _ in range(2):
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        try:
            answer = [job(seed, 8) for seed in range(2)] == alone
        except BaseException as error:
            answer = repr(error)
        os.write(write, pickle.dumps(answer))
        os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        answer = pickle.loads(pipe.read())
    os.waitpid(pid, 0)
    assert answer is True, answer
    time.sleep(0.2)
stop.append(True)
for thread in threads:
    thread.join()
print("ok")
"""

_HEAP = """
import gc
from numba.core.runtime import rtsys
from navkit.estimation import DiffOdometry, ExtendedKalmanFilter
from navkit.kinematics import DiffDrive
from navkit.geometry import Pose2D, rollout
from navkit.mapping import ScanMatcher
from navkit.planning import MapPlanner, piecewise_repulsive_force_from_scan
rng = np.random.default_rng(0)
costs = rng.uniform(1.0, 4.0, (40, 40))
costs[rng.random((40, 40)) < 0.1] = np.inf
costs[0, 0] = costs[-1, -1] = 1.0
planner = FieldDStar(costs)
planner.plan((0, 0), (40, 40))
grid = OccupancyGrid.empty(width=6.0, height=6.0, resolution=0.05, origin=(-3.0, -3.0, 0.0))
scan = room_scan(0.1, 0.2, 0.1, half=2.5)
integrate_scan(grid, scan, (0.1, 0.2, 0.1))
plans = [MapPlanner(grid, unknown_cost=2.0, planner=kind) for kind in ("astar", "field_dstar")]
fusion = PlanarFusion(history=1.0)
odometry = DiffOdometry(DiffDrive(track=0.4, wheel_radius=0.05), ticks_per_rev=1000, bits=16)
ekf = ExtendedKalmanFilter(np.zeros(3), np.eye(3))
matcher, mapper = ScanMatcher(), ScanMapper(resolution=0.1)
tracker, controller = RegulatedPurePursuit(), PotentialFieldController()
tracker.set_path(np.column_stack([np.linspace(0.0, 5.0, 40), np.zeros(40)]))
clock = [0.0]
def tick():
    clock[0] += 0.01
    return clock[0]
def refused(call):
    try:
        call()
    except (ValueError, TypeError):
        pass
calls = [
    lambda: planner.replan((int(clock[0] * 100) % 40, 0)),
    lambda: (planner.update_costs([[3, 3]], [1.0 + int(tick() * 100) % 3]), planner.replan()),
    lambda: [plan.plan((0.1, 0.1), (1.5, 1.5)) for plan in plans],
    lambda: integrate_scan(grid, scan, (0.1, 0.2, 0.1)),
    lambda: grid.cells_near(np.array([[0.1, 0.2], [0.3, 0.4]]), robot_radius=0.2),
    lambda: grid.traversal_costs(robot_radius=0.2),
    lambda: piecewise_repulsive_force_from_scan(scan),
    lambda: matcher.match(grid, scan, (0.1, 0.2, 0.1)),
    lambda: mapper.update(scan, odometry=(0.1, 0.2, 0.1)),
    lambda: (lambda t: (fusion.update_odometry(t, 0.5, 0.1, v_variance=1e-3, omega_variance=1e-3),
                        fusion.update_yaw(t - 0.005, 0.1, variance=1e-3)))(tick()),
    lambda: refused(lambda: fusion.update_yaw(math.nan, 0.1, variance=1e-3)),
    lambda: odometry.update(int(tick() * 700) % 65536, int(clock[0] * 900) % 65536),
    lambda: (ekf.predict(lambda x: x, np.eye(3), np.eye(3) * 1e-3),
             ekf.update([1e3], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.1]], gate=9.0)),
    lambda: refused(lambda: ekf.update([math.nan], lambda x: x[:1], np.eye(3)[:1], [[0.1]])),
    lambda: tracker.step((0.1, 0.0, 0.0), 0.05),
    lambda: controller.step((0.0, 0.0, 0.0), (2.0, 1.0, 0.0), 0.05, obstacles=scan),
    lambda: rollout(Pose2D(0.0, 0.0, 0.0), np.tile([1.0, 0.0, 0.2], (10, 1)), 0.1),
]
for call in calls:
    for _ in range(5):
        call()
gc.collect()
before = rtsys.get_allocation_stats()
for call in calls:
    for _ in range(150):
        call()
gc.collect()
after = rtsys.get_allocation_stats()
assert after.alloc > before.alloc, "numba allocated nothing: are its statistics on?"
left = (after.alloc - after.free) - (before.alloc - before.free)
meminfos = (after.mi_alloc - after.mi_free) - (before.mi_alloc - before.mi_free)
assert left == 0 and meminfos == 0, (left, meminfos)
print("ok")
"""


def _run(script: str, **env: str) -> None:
    done = subprocess.run(
        [sys.executable, "-c", f"ROOM = {_ROOM!r}\n" + _JOB + script],
        capture_output=True, text=True, timeout=600, check=False,
        env={**os.environ, "PYTHONPATH": _SRC, **env},
    )  # fmt: skip
    assert done.returncode == 0 and done.stdout.strip().endswith("ok"), done.stderr[-3000:]


def test_objects_of_different_threads_never_interfere() -> None:
    _run(_THREADS)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="fork: POSIX only")
def test_a_child_forked_while_threads_plan_answers_as_its_parent() -> None:
    _run(_FORK)


def test_numba_heap_balances_over_a_nodes_calls() -> None:
    _run(_HEAP, NUMBA_NRT_STATS="1")
