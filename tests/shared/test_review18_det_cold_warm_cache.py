"""Kernels freshly compiled, loaded from numba's cache, or compiled without navkit's
compile shortcuts give bit-identical results.

Each run is a fresh interpreter (its own ``PYTHONHASHSEED``) on a given
``NUMBA_CACHE_DIR``: empty (every kernel compiled), then the same folder again
(every kernel loaded), then another empty folder with
``compile_shortcuts.ENABLED = False``. Each prints digests of the answers of
planners, mapping, estimation, reactive fields and a noisy simulated run.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

_DIGESTS = r"""
import hashlib, json, sys
import numpy as np
if sys.argv[1] == "off":
    from navkit._shared import compile_shortcuts
    compile_shortcuts.ENABLED = False
from shapely.geometry import box
from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, costmap, integrate_scan
from navkit.planning import (AStarPlanner, FieldDStar, distance_field,
                             piecewise_repulsive_force_from_scan, repulsive_force_from_scan)
from navkit.sim import Imu, Lidar, Robot, Simulation, World

def digest(*parts):
    h = hashlib.sha256()
    for p in parts:
        array = isinstance(p, np.ndarray)
        h.update(np.ascontiguousarray(p).tobytes() if array else repr(p).encode())
    return h.hexdigest()

rng = np.random.default_rng(7)
costs = np.where(rng.random((40, 50)) < 0.25, np.inf, rng.choice([1.0, 2.0, 7.5], (40, 50)))
costs[0, 0] = costs[-1, -1] = 1.0
ties = np.where(np.isfinite(costs), 1.0, np.inf)
out = {}
for name, grid in (("costs", costs), ("ties", ties)):
    for conn in (4, 8):
        p = AStarPlanner(grid, connectivity=conn).plan((0, 0), (39, 49))
        out[f"astar{conn}-{name}"] = digest(p.points, p.cost)
    p = FieldDStar(grid).plan_cells((0, 0), (39, 49))
    out[f"fd-{name}"] = digest(p.points, p.cost)
    out[f"df-{name}"] = digest(distance_field(grid, (39, 49)))
p = AStarPlanner(ties, method="jps").plan((0, 0), (39, 49))
out["jps"] = digest(p.points, p.cost)
n = 720
angles = np.linspace(-np.pi, np.pi, n, endpoint=False)
with np.errstate(divide="ignore"):
    ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
ranges = ranges + rng.normal(0.0, 0.01, n)
scan = LaserScan(ranges, angle_min=-np.pi, angle_increment=2 * np.pi / n, range_min=0.1,
                 range_max=10.0)
room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.05, origin=(-4.0, -3.0, 0.0))
integrate_scan(room, scan, (0.0, 0.0, 0.0))
out["map"] = digest(room.logodds)
out["costmap"] = digest(costmap(room, robot_radius=0.2, inflation_radius=0.6))
m = ScanMatcher().match(room, scan, (0.07, -0.04, 0.03))
out["match"] = digest(m.pose.x, m.pose.y, m.pose.theta, m.covariance, m.score)
out["khatib"] = digest(repulsive_force_from_scan(scan, influence_radius=2.5))
out["piecewise"] = digest(piecewise_repulsive_force_from_scan(scan, spread=2.0))
t = np.arange(1, 201) * 0.02
log = MeasurementLog.from_streams(odometry=(t, 1.0 + 0.1 * np.sin(t), 0.3 * np.cos(t)),
                                  yaw_rate=(t + 0.01, 0.3 * np.cos(t)))
r = PlanarFusion(t0=0.0).update_batch(log)
out["fusion"] = digest(r.states, r.covariances)
world = World(box(-1.0, -1.0, 4.0, 2.0).exterior)
robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=0.1,
              lidar=Lidar(n_beams=90), imu=Imu())
trace = Simulation(world, robot, lambda obs: Twist2D(0.3, 0.0, 0.4), start=(0.0, 0.0, 0.0),
                   duration=2.0, seed=3).run()
out["sim"] = digest(trace.poses, trace.estimates, trace.commands)
print(json.dumps(out, sort_keys=True))
"""


def _digests(cache: Path, shortcuts: str, hash_seed: str) -> dict[str, str]:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONHASHSEED": hash_seed}
    done = subprocess.run(
        [sys.executable, "-c", _DIGESTS, shortcuts],
        capture_output=True, text=True, timeout=900, env=env, check=True,
    )  # fmt: skip
    digests: dict[str, str] = json.loads(done.stdout)
    return digests


@pytest.mark.slow
def test_cold_warm_and_unshortcut_compiles_give_the_same_bits(tmp_path: Path) -> None:
    cold = _digests(tmp_path / "one", "on", "1")
    assert any((tmp_path / "one").rglob("*.nbi"))  # the kernels were cached
    warm = _digests(tmp_path / "one", "on", "2")
    plain = _digests(tmp_path / "two", "off", "3")
    assert len(cold) >= 15
    assert warm == cold
    assert plain == cold
