"""Helpers (kernels without a Python wrapper) compile into lean code libraries.

Issue 17 (first use with an empty numba cache): numba optimised each helper's
module and made its machine code although only the kernels calling it use
its code, linked into their own modules and optimised there again.
:func:`navkit._shared.jit.helper_compiler` skips both for navkit's helpers.
These tests check that a helper makes no machine code while its callers
compute what they did, that numba's cache keeps a helper (as bitcode) so a
later process links it into a new caller, that ``LEAN_HELPERS = False``
gives numba's own libraries, and (slow, fresh processes with empty caches)
that the grid planners, ray casting and the simulator return bit-identical
results either way.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from navkit._shared import jit

_MODULE = """
from navkit._shared.jit import njit_helper, njit_no_refcount


@njit_helper
def scaled_sum(x, k):
    total = 0.0
    for i in range(k):
        total += x * (i + 1)
    return total


@njit_no_refcount
def first(x, k):
    return scaled_sum(x, k) + 1.0


@njit_no_refcount
def second(x, k):
    return 2.0 * scaled_sum(x, k)
"""


def _module(tmp_path: Path, name: str) -> ModuleType:
    """A kernel module written to ``tmp_path`` and imported (numba caches beside it)."""
    path = tmp_path / f"{name}.py"
    path.write_text(_MODULE, encoding="utf-8")
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _library(dispatcher: Any) -> Any:
    (sig,) = dispatcher.signatures
    return dispatcher.overloads[sig].library, dispatcher.overloads[sig].fndesc


def _engine_defines(library: Any, fndesc: Any) -> bool:
    return bool(library.codegen._engine.is_symbol_defined(fndesc.mangled_name))


def test_a_helper_makes_no_machine_code_and_its_callers_compute_as_before(
    tmp_path: Path,
) -> None:
    module = _module(tmp_path, "review21_cold_lean_a")
    assert module.first(1.5, 4) == 1.5 * (1 + 2 + 3 + 4) + 1.0
    assert module.second(0.25, 3) == 2.0 * 0.25 * 6
    helper, helper_desc = _library(module.scaled_sum)
    caller, caller_desc = _library(module.first)
    assert type(helper).__name__ == "HelperLibrary"
    assert type(caller).__name__ == "JITCodeLibrary"
    # The helper's own code never reached the JIT engine; the caller's did,
    # with the helper's IR linked into it.
    assert not _engine_defines(helper, helper_desc)
    assert _engine_defines(caller, caller_desc)
    assert helper in caller._linking_libraries
    assert not helper.has_dynamic_globals


def test_lean_helpers_off_gives_numbas_own_libraries(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(jit, "LEAN_HELPERS", False)
    assert jit.helper_compiler() is None
    module = _module(tmp_path, "review21_cold_lean_b")
    assert module.first(1.5, 4) == 1.5 * (1 + 2 + 3 + 4) + 1.0
    helper, helper_desc = _library(module.scaled_sum)
    assert type(helper).__name__ == "JITCodeLibrary"
    assert _engine_defines(helper, helper_desc)


def test_the_helper_compiler_is_made_once() -> None:
    compiler = jit.helper_compiler()
    assert compiler is not None and compiler is jit.helper_compiler()
    assert compiler.__name__ == "HelperCompiler"


_CHILD = """
import json, sys
sys.path.insert(0, sys.argv[1])
import review21_cold_lean_c as m
values = [m.first(1.5, 4)] if sys.argv[2] == "first" else []
values += [m.second(0.25, 3)] if sys.argv[2] in ("second", "both") else []
values += [m.first(1.5, 4)] if sys.argv[2] == "both" else []
hits = {name: [sum(getattr(m, name).stats.cache_hits.values()),
               sum(getattr(m, name).stats.cache_misses.values())]
        for name in ("scaled_sum", "first", "second")}
print(json.dumps({"values": values, "hits": hits}))
"""


def _child(folder: Path, cache: Path, which: str) -> dict[str, Any]:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(_CHILD), str(folder), which],
        check=True, capture_output=True, text=True, env=env, timeout=300,
    )  # fmt: skip
    result: dict[str, Any] = json.loads(out.stdout.strip().splitlines()[-1])
    return result


def test_a_cached_helper_links_into_a_new_caller_in_a_later_process(tmp_path: Path) -> None:
    folder = tmp_path / "src"
    folder.mkdir()
    (folder / "review21_cold_lean_c.py").write_text(_MODULE, encoding="utf-8")
    cache = tmp_path / "cache"
    # [cache hits, cache misses] per kernel.
    one = _child(folder, cache, "first")
    assert one["values"] == [1.5 * 10 + 1.0]
    assert one["hits"] == {"scaled_sum": [0, 1], "first": [0, 1], "second": [0, 0]}
    # A new caller: the helper comes from the cache (bitcode) and is linked into it.
    two = _child(folder, cache, "second")
    assert two["values"] == [2.0 * 0.25 * 6]
    assert two["hits"] == {"scaled_sum": [1, 0], "first": [0, 0], "second": [0, 1]}
    # Both callers cached: the helper is not even loaded.
    three = _child(folder, cache, "both")
    assert three["values"] == [2.0 * 0.25 * 6, 1.5 * 10 + 1.0]
    assert three["hits"] == {"scaled_sum": [0, 0], "first": [1, 0], "second": [1, 0]}


_DIGESTS = r"""
import hashlib, json, sys
import numpy as np
if sys.argv[1] == "off":
    from navkit._shared import jit
    jit.LEAN_HELPERS = False
from shapely.geometry import box
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field
from navkit.sim import Lidar, Robot, Simulation, World
from navkit.geometry import Twist2D

def digest(*parts):
    h = hashlib.sha256()
    for p in parts:
        array = isinstance(p, np.ndarray)
        h.update(np.ascontiguousarray(p).tobytes() if array else repr(p).encode())
    return h.hexdigest()

rng = np.random.default_rng(21)
costs = np.where(rng.random((48, 56)) < 0.25, np.inf, rng.choice([1.0, 2.0, 7.5], (48, 56)))
costs[0, 0] = costs[-1, -1] = 1.0
ties = np.where(np.isfinite(costs), 1.0, np.inf)
out = {}
for name, grid in (("costs", costs), ("ties", ties)):
    for cut in (False, True):
        p = astar(grid, (0, 0), (47, 55), corner_cutting=cut)
        out[f"astar-{name}-{cut}"] = digest(p.points, p.cost, p.expanded)
    out[f"df-{name}"] = digest(distance_field(grid, (47, 55)))
    for interp in (True, False):
        planner = FieldDStar(grid, interpolate=interp)
        p = planner.plan((0, 0), (48, 56))
        planner.update_costs([(10, 10), (10, 11), (11, 10)], np.inf)
        q = planner.replan()
        out[f"fd-{name}-{interp}"] = digest(p.points, p.cost, p.expanded, q.points, q.cost)
for cut in (False, True):
    p = AStarPlanner(ties, method="jps", corner_cutting=cut).plan((0, 0), (47, 55))
    out[f"jps-{cut}"] = digest(p.points, p.cost)
angles = np.linspace(-np.pi, np.pi, 180, endpoint=False)
with np.errstate(divide="ignore"):
    ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
scan = LaserScan(ranges, angle_min=-np.pi, angle_increment=2 * np.pi / 180,
                 range_min=0.1, range_max=10.0)
room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.1, origin=(-4.0, -3.0, 0.0))
integrate_scan(room, scan, (0.1, -0.2, 0.3))
out["scan"] = digest(room.logodds)
world = World([box(0.0, 0.0, 4.0, 3.0).exterior])
robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,
              lidar=Lidar(n_beams=32), max_wheel_acceleration=40.0)
trace = Simulation(world, robot, lambda obs: Twist2D(0.4, 0.0, 0.3), start=(1.0, 1.0, 0.0),
                   goal=(3.5, 2.5), duration=1.0, seed=3, record_scans=True).run()
out["sim"] = digest(trace.poses, trace.scans[-1].scan.ranges)
print(json.dumps(out))
"""


def _digests(mode: str, cache: Path) -> dict[str, str]:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", _DIGESTS, mode],
        check=True, capture_output=True, text=True, env=env, timeout=600,
    )  # fmt: skip
    result: dict[str, str] = json.loads(out.stdout.strip().splitlines()[-1])
    return result


@pytest.mark.slow
def test_planners_ray_casting_and_the_simulator_agree_with_numbas_own_libraries(
    tmp_path: Path,
) -> None:
    lean = _digests("on", tmp_path / "lean")
    own = _digests("off", tmp_path / "own")
    assert len(lean) == 14
    assert lean == own
