"""First use with an empty numba cache: CPU seconds per entry point, the whole library, peers.

Run with ``python -m pytest benchmarks/test_bench_cold_start.py --benchmark-only -s``
(``-k quick`` for a subset of a few cheap entry points and the peers, about a
minute) or as a script, which prints the table::

    python benchmarks/test_bench_cold_start.py            # every entry point, ~2-4 min
    python benchmarks/test_bench_cold_start.py --quick
    python benchmarks/test_bench_cold_start.py --only astar --only FieldDStar --kernels

Every entry point runs in its own fresh Python process with ``NUMBA_CACHE_DIR``
pointing at a new empty folder (cold: numba compiles every kernel it meets),
then in a second fresh process on the same, now filled, folder (warm: numba
loads the machine code). The figure is the child's CPU time
(``time.process_time()``) of the call alone, imports and input construction
excluded, so a loaded 2-core machine changes it little. ``import navkit.planning``
times the import itself; ``whole library`` is :func:`navkit.sim.warmup` in one
process (``workers=1``), which calls every entry point with every option that
selects another kernel. The peers, pyastar2d and tcod's A*, run their first
call in a fresh process the same way (they ship compiled code: nothing to
compile). ``--kernels`` also prints, per entry point, the navkit kernels it
compiled with their signature count and compile seconds (numba's own timers,
``dispatcher.get_metadata(sig)['timers']``: wall-clock seconds holding the
compiler lock, so on a busy machine more than the CPU, and a caller's time
includes the callees it typed). ``--breakdown`` prints where the cold run's CPU went,
each second counted once (:data:`_BREAKDOWN`): per phase (numba's passes,
LLVM's function and module optimisation and machine-code generation, the
Python wrappers, the cache writes, garbage collections) and per kernel (the
function whose pass or LLVM work ran, not the callers waiting on it).

Each child also counts the navkit kernel signatures numba compiled (cache
misses) and loaded from the cache (hits), and the files in the cache folder
when it started and after the call; the tests assert on those counts, never
on times (:func:`check_cold_and_warm`): a cold run that found a cache or
compiled nothing, or a warm run that compiled again, fails.

The issue 17 goal: whole library <= 8 s, any single entry point <= 3 s.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import textwrap
from typing import Any

import pytest

#: Code run before the clock starts (imports, inputs), per entry point.
_ROOM = """
import math
import numpy as np
from navkit.mapping import LaserScan, OccupancyGrid
angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
with np.errstate(divide="ignore"):
    ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                 range_min=0.1, range_max=10.0)
room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.1, origin=(-4.0, -3.0, 0.0))
"""

_COSTS = """
import numpy as np
costs = np.ones((64, 64))
costs[10:50, 30] = np.inf
"""

#: name -> (setup code, timed code, in the quick subset).
ENTRIES: dict[str, tuple[str, str, bool]] = {
    "import navkit.planning": ("", "import navkit.planning", True),
    "rollout": (
        "import numpy as np\nfrom navkit.geometry import rollout",
        "rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5], [0.5, 0.1, 0.0]]), 0.5)",
        True,
    ),
    "integrate_scan": (
        _ROOM + "from navkit.mapping import integrate_scan",
        "integrate_scan(room, scan, (0.0, 0.0, 0.0))",
        False,
    ),
    "astar": (_COSTS + "from navkit.planning import astar", "astar(costs, (0, 0), (63, 63))", True),
    "distance_field": (
        _COSTS + "from navkit.planning import distance_field",
        "distance_field(costs, (63, 63))",
        False,
    ),
    "JPS": (
        _COSTS + "from navkit.planning import astar",
        "astar(costs, (0, 0), (63, 63), method='jps')",
        False,
    ),
    "JPS, corner cutting": (
        _COSTS + "from navkit.planning import astar",
        "astar(costs, (0, 0), (63, 63), method='jps', corner_cutting=True)",
        False,
    ),
    "MapPlanner.plan": (
        "import numpy as np\nfrom navkit.mapping import OccupancyGrid\n"
        "from navkit.planning import MapPlanner\n"
        "occupied = np.zeros((10, 12), dtype=bool)\noccupied[:6, 6] = True\n"
        "grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)",
        "MapPlanner(grid, robot_radius=0.05).plan((0.15, 0.15), (1.05, 0.15))",
        False,
    ),
    "ScanMatcher.match": (
        _ROOM + "from navkit.mapping import ScanMatcher, integrate_scan\n"
        "integrate_scan(room, scan, (0.0, 0.0, 0.0))",
        "ScanMatcher().match(room, scan, (0.05, -0.05, 0.02))",
        False,
    ),
    "ScanMapper": (
        _ROOM + "from navkit.mapping import ScanMapper",
        "mapper = ScanMapper(resolution=0.1)\nmapper.update(scan)\n"
        "mapper.update(scan, odometry=(0.5, 0.0, 0.95))",
        False,
    ),
    "FieldDStar": (
        "import numpy as np\nfrom navkit.planning import FieldDStar\n"
        "costs = np.ones((10, 10))\ncosts[3:7, 5] = 3.0",
        "planner = FieldDStar(costs)\nplanner.plan((0, 0), (10, 7))\n"
        "planner.update_costs([(3, 1), (3, 2)], np.inf)\nplanner.replan()",
        False,
    ),
    "PlanarFusion": (
        "import numpy as np\nfrom navkit.estimation import MeasurementLog, PlanarFusion\n"
        "t = np.linspace(0.0, 0.4, 5)\n"
        "log = MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5)))",
        "fusion = PlanarFusion()\nfusion.update_odometry(0.02, 1.0, 0.1, v_variance=1e-4,"
        " omega_variance=1e-4)\nPlanarFusion().update_batch(log)",
        False,
    ),
    "ExtendedKalmanFilter": (
        "import numpy as np\nfrom navkit.estimation import ExtendedKalmanFilter\n"
        "jac = np.eye(3)\njac[0, 1] = 0.1",
        "ekf = ExtendedKalmanFilter([0.0, 1.0, 0.0], np.eye(3), angle_states=(2,))\n"
        "ekf.predict(lambda x: jac @ x, jac, 0.01 * np.eye(3))\n"
        "ekf.update([0.1], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.01]])",
        False,
    ),
    "repulsion": (
        _ROOM + "from navkit.planning import repulsive_force_from_scan",
        "repulsive_force_from_scan(scan, influence_radius=2.5)",
        True,
    ),
    "Simulation.run": (
        "from shapely.geometry import box\nfrom navkit.geometry import Twist2D\n"
        "from navkit.kinematics import DiffDrive\n"
        "from navkit.sim import Circle, Lidar, Robot, Simulation, World\n"
        "walls = box(0.0, 0.0, 4.0, 3.0).exterior\n"
        "def forward(_obs):\n    return Twist2D(0.4, 0.0, 0.2)",
        "world = World([walls, Circle((2.5, 2.0), 0.2)])\n"
        "robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,\n"
        "              lidar=Lidar(n_beams=16), max_wheel_acceleration=40.0)\n"
        "Simulation(world, robot, forward, start=(1.0, 1.0, 0.0), goal=(1.5, 1.2),"
        " duration=0.3).run()",
        False,
    ),
    "whole library": ("from navkit.sim import warmup", "warmup(workers=1)", False),
}

#: Peers: their first call in a fresh process (compiled ahead, nothing to compile).
PEERS: dict[str, tuple[str, str]] = {
    "pyastar2d (peer)": (
        "import numpy as np\nimport pyastar2d\nw = np.ones((64, 64), dtype=np.float32)\n"
        "w[10:50, 30] = np.inf",
        "pyastar2d.astar_path(w, (0, 0), (63, 63), allow_diagonal=True)",
    ),
    "tcod AStar (peer)": (
        "import numpy as np\nimport tcod.path\ncost = np.ones((64, 64), dtype=np.int8)\n"
        "cost[10:50, 30] = 0",
        "tcod.path.AStar(cost, diagonal=1.41).get_path(0, 0, 63, 63)",
    ),
}

#: Peer -> the module it needs (from the ``bench`` extra); absent: skipped, saying so.
PEER_MODULES = {"pyastar2d (peer)": "pyastar2d", "tcod AStar (peer)": "tcod"}


def missing_peer(name: str) -> str | None:
    """Why entry ``name`` cannot run here (its peer is not installed), or None."""
    module = PEER_MODULES.get(name)
    if module is None or importlib.util.find_spec(module) is not None:
        return None
    return f"peer {module} is not installed (pip install -e '.[bench]')"


#: Instruments the child for ``--breakdown``: exclusive CPU per phase and per kernel.
#:
#: numba compiles a kernel's callees while it types the kernel, so its own timers
#: count a callee's time in every caller typing it. Here each numba pass, LLVM
#: step, wrapper, cache write and collection is timed with a stack, and its time
#: less that of what ran inside it is added to its phase and to the function
#: being compiled (the innermost pass's). Where the installed numba lacks a
#: method timed here, that phase is not split out ("other" keeps it).
_BREAKDOWN = """
import collections as _collections, gc as _gc
from navkit._shared.jit import load_numba as _load_numba
_load_numba()
_phases, _by_kernel = _collections.Counter(), _collections.Counter()
_stack = []  # [phase, kernel, seconds spent in nested entries]


def _timed(_owner, _name, _phase_of):
    _inner = getattr(_owner, _name, None)
    if _inner is None:
        return

    def _wrapper(*_args, **_kwargs):
        _phase, _kernel = _phase_of(_args)
        if _kernel is None:
            _kernel = _stack[-1][1] if _stack else "(none)"
        _entry = [_phase, _kernel, 0.0]
        _stack.append(_entry)
        _t = time.process_time()
        try:
            return _inner(*_args, **_kwargs)
        finally:
            _spent = time.process_time() - _t
            _stack.pop()
            _phases[_phase] += _spent - _entry[2]
            _by_kernel[_kernel] += _spent - _entry[2]
            if _stack:
                _stack[-1][2] += _spent

    setattr(_owner, _name, _wrapper)


def _pass_of(_args):
    _pass, _state = _args[2], _args[3]
    _func = getattr(getattr(_state, "func_id", None), "func", None)
    _kernel = getattr(_func, "__module__", "?") + "." + getattr(_func, "__qualname__", "?")
    return "numba pass " + str(_pass.name()), _kernel


import numba.core.compiler_machinery as _machinery
import numba.core.codegen as _codegen
import numba.core.caching as _caching
import numba.core.lowering as _lowering
_timed(_machinery.PassManager, "_runPass", _pass_of)
_timed(_codegen.CPUCodeLibrary, "_optimize_functions", lambda a: ("LLVM function passes", None))
_timed(_codegen.CPUCodeLibrary, "_optimize_final_module", lambda a: ("LLVM module passes", None))
_timed(_codegen.JITCodeLibrary, "_finalize_specific", lambda a: ("LLVM machine code", None))
_timed(_caching.Cache, "save_overload", lambda a: ("cache write", None))
_timed(_lowering.Lower, "create_cpython_wrapper", lambda a: ("Python wrapper", None))
_gc_start = []


def _on_gc(_phase, _info):
    if _phase == "start":
        _gc_start.append(time.process_time())
    elif _gc_start:
        _spent = time.process_time() - _gc_start.pop()
        _phases["garbage collection"] += _spent
        _by_kernel["garbage collection"] += _spent
        if _stack:  # counted here, not in the pass it interrupted
            _stack[-1][2] += _spent


_gc.callbacks.append(_on_gc)
"""

_BREAKDOWN_REPORT = """
_gc.callbacks.remove(_on_gc)
_phases["other"] = _cpu - sum(_phases.values())
_breakdown = {{"phases": dict(_phases), "kernels": dict(_by_kernel)}}
"""

_CHILD = """
import json, os, sys, time


def _cache_files():
    return sum(len(files) for _, _, files in os.walk(os.environ["NUMBA_CACHE_DIR"]))


_files_before = _cache_files()
{setup}
{instrument}
_cpu, _wall = time.process_time(), time.perf_counter()
{timed}
_cpu, _wall = time.process_time() - _cpu, time.perf_counter() - _wall
_breakdown = None
{report}
_kernels = {{}}
_compiled = _loaded = 0
if "numba" in sys.modules:  # not imported by the call: nothing compiled or loaded
    import gc
    from numba.core.dispatcher import Dispatcher
    # Every navkit dispatcher, the closures made by kernel factories included
    # (not in any module's namespace; some entry points call only those when warm).
    for _value in gc.get_objects():
        if not isinstance(_value, Dispatcher):
            continue
        _name = getattr(_value.py_func, "__module__", None) or ""
        if not _name.startswith("navkit."):
            continue
        _misses = sum(_value.stats.cache_misses.values())
        _compiled += _misses
        _loaded += sum(_value.stats.cache_hits.values())
        if not {kernels} or not _misses:
            continue
        _secs = 0.0
        for _sig in _value.signatures:
            try:
                _t = _value.get_metadata(_sig)["timers"]
                _secs += _t.get("compiler_lock", 0.0)
            except Exception:
                pass
        _kernels[_name + "." + _value.py_func.__qualname__] = [len(_value.signatures), _secs]
print("@@" + json.dumps({{"cpu": _cpu, "wall": _wall, "kernels": _kernels,
                          "breakdown": _breakdown, "compiled": _compiled, "loaded": _loaded,
                          "cache_files_before": _files_before,
                          "cache_files_after": _cache_files()}}))
"""


def run_child(
    setup: str, timed: str, cache_dir: str, *, kernels: bool = False, breakdown: bool = False
) -> dict[str, Any]:
    """Run ``timed`` after ``setup`` in a fresh process with numba's cache in ``cache_dir``.

    ``breakdown``: also split the call's CPU by phase and kernel (:data:`_BREAKDOWN`).
    Its totals are not those of the plain runs: numba is imported before the
    clock starts (to be instrumented) and the instruments cost a little.
    """
    code = _CHILD.format(
        setup=setup, timed=timed, kernels=kernels,
        instrument=_BREAKDOWN if breakdown else "",
        report=_BREAKDOWN_REPORT.format() if breakdown else "",
    )  # fmt: skip
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, env=env,
    )  # fmt: skip
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("@@"))
    result: dict[str, Any] = json.loads(line[2:])
    return result


def measure(name: str, *, kernels: bool = False, breakdown: bool = False) -> dict[str, Any]:
    """Cold (empty cache) and warm (cache filled by the cold run) CPU seconds of one entry."""
    setup, timed = ENTRIES[name][:2] if name in ENTRIES else PEERS[name]
    breakdown = breakdown and name in ENTRIES and name != "import navkit.planning"
    with tempfile.TemporaryDirectory(prefix="navkit-cold-") as cache_dir:
        cold = run_child(setup, timed, cache_dir, kernels=kernels, breakdown=breakdown)
        warm = run_child(setup, timed, cache_dir)
    counts = {
        f"{run}_{key}": child[key]
        for run, child in (("cold", cold), ("warm", warm))
        for key in ("compiled", "loaded", "cache_files_before", "cache_files_after")
    }
    return {"cold_cpu_s": cold["cpu"], "cold_wall_s": cold["wall"], "warm_cpu_s": warm["cpu"],
            "kernels": cold["kernels"], "breakdown": cold["breakdown"], **counts}  # fmt: skip


def check_cold_and_warm(name: str, result: dict[str, Any]) -> None:
    """That the two runs of entry ``name`` measured what they claim (:func:`measure`).

    Signatures count navkit's kernels (every numba dispatcher of a navkit
    module): ``compiled`` those numba compiled (cache misses), ``loaded``
    those it read from the cache (hits).

    * Cold, every navkit entry point: the child started with an empty cache
      folder, compiled navkit kernels, loaded none, and left the folder filled.
    * Warm: the child started on that filled folder, loaded kernels from it,
      compiled none and wrote nothing (a kernel compiling again in every
      process, one numba cannot cache, fails here; so does a kernel source
      file edited between the two runs, which numba's cache keys on).
    * ``import navkit.planning`` and the peers: nothing compiled, the folder
      left empty (issue 17: importing compiles nothing; the peers ship
      compiled code).
    """
    assert result["cold_cache_files_before"] == 0, f"{name}: the cold cache was not empty"
    if name in PEERS or name == "import navkit.planning":
        for run in ("cold", "warm"):
            assert result[f"{run}_compiled"] == 0, f"{name}: {run} run compiled navkit kernels"
            assert result[f"{run}_loaded"] == 0, f"{name}: {run} run loaded navkit kernels"
        assert result["cold_cache_files_after"] == 0, f"{name}: wrote to the numba cache"
        return
    assert result["cold_compiled"] > 0, f"{name}: the cold run compiled nothing"
    assert result["cold_loaded"] == 0, f"{name}: the cold run loaded kernels from a cache"
    assert result["cold_cache_files_after"] > 0, f"{name}: the cold run cached nothing"
    assert result["warm_cache_files_before"] > 0, f"{name}: the warm run had no cache"
    assert result["warm_loaded"] > 0, f"{name}: the warm run loaded nothing from the cache"
    assert result["warm_compiled"] == 0, f"{name}: the warm run compiled again"
    assert result["warm_cache_files_after"] == result["warm_cache_files_before"], (
        f"{name}: the warm run wrote to the cache"
    )


def print_breakdown(breakdown: dict[str, dict[str, float]], *, top: int = 15) -> None:
    """Print a ``--breakdown``: CPU s per phase, then the ``top`` kernels."""
    total = sum(breakdown["phases"].values())
    print(f"    where the {total:.2f} s went (each second once):")
    small = [0, 0.0]  # phases under 1 %, summed
    for phase, secs in sorted(breakdown["phases"].items(), key=lambda kv: -kv[1]):
        if secs < 0.01 * total:
            small[0] += 1
            small[1] += secs
            continue
        print(f"    {secs:7.2f} s  {100 * secs / total:4.1f} %  {phase}")
    share = 100 * small[1] / total
    print(f"    {small[1]:7.2f} s  {share:4.1f} %  {small[0]} phases under 1 % each")
    print(f"    the {top} kernels taking most (their own passes and LLVM work):")
    for kernel, secs in sorted(breakdown["kernels"].items(), key=lambda kv: -kv[1])[:top]:
        print(f"    {secs:7.2f} s  {kernel}")


def _names(quick: bool) -> list[str]:
    return [name for name, entry in ENTRIES.items() if entry[2] or not quick] + list(PEERS)


def _table(results: dict[str, dict[str, Any]]) -> str:
    lines = [
        "| entry point | cold CPU s | warm CPU s | cold wall s |",
        "| --- | ---: | ---: | ---: |",
    ]
    for name, r in results.items():
        lines.append(f"| {name} | {r['cold_cpu_s']:.4f} | {r['warm_cpu_s']:.4f} "
                     f"| {r['cold_wall_s']:.2f} |")  # fmt: skip
    return "\n".join(lines)


_RESULTS: dict[str, dict[str, Any]] = {}


@pytest.fixture(scope="module", autouse=True)
def _print_table() -> Any:
    yield
    if _RESULTS:
        print("\n\nfirst use with an empty numba cache (CPU s of the call, fresh process each)")
        print(_table(_RESULTS))


def _bench(benchmark: Any, name: str) -> None:
    reason = missing_peer(name)
    if reason is not None:
        pytest.skip(reason)
    results: list[dict[str, Any]] = []
    benchmark.group = "cold start"
    benchmark.pedantic(lambda: results.append(measure(name)), rounds=1, iterations=1)
    result = results[0]
    benchmark.extra_info.update({k: v for k, v in result.items() if k != "kernels"})
    _RESULTS[name] = result
    check_cold_and_warm(name, result)


@pytest.mark.parametrize("name", [n for n, e in ENTRIES.items() if e[2]] + list(PEERS))
def test_cold_start_quick(benchmark: Any, name: str) -> None:
    _bench(benchmark, name)


@pytest.mark.parametrize("name", [n for n, e in ENTRIES.items() if not e[2]])
def test_cold_start(benchmark: Any, name: str) -> None:
    _bench(benchmark, name)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a few cheap entry points + peers")
    parser.add_argument("--only", action="append", help="entry point name (repeatable)")
    parser.add_argument("--kernels", action="store_true", help="per-kernel compile seconds")
    parser.add_argument("--breakdown", action="store_true",
                        help="cold CPU per phase and kernel, each second once")  # fmt: skip
    parser.add_argument("--json", help="write the results to this file")
    parser.add_argument("--list", action="store_true", help="list the entry points")
    args = parser.parse_args(argv)
    if args.list:
        print("\n".join(_names(False)))
        return
    names = args.only or _names(args.quick)
    for name in names:
        if name not in ENTRIES and name not in PEERS:
            parser.error(f"unknown entry point {name!r}; see --list")
    results: dict[str, dict[str, Any]] = {}
    for name in names:
        reason = missing_peer(name)
        if reason is not None:
            print(f"{name:24s} skipped: {reason}", flush=True)
            continue
        results[name] = measure(name, kernels=args.kernels, breakdown=args.breakdown)
        r = results[name]
        print(f"{name:24s} cold {r['cold_cpu_s']:8.4f} s  warm {r['warm_cpu_s']:7.4f} s",
              flush=True)  # fmt: skip
        if args.kernels:
            for kernel, (sigs, secs) in sorted(r["kernels"].items(), key=lambda kv: -kv[1][1]):
                print(f"    {secs:7.2f} s  {sigs} sig  {kernel}")
        if r["breakdown"] is not None:
            print_breakdown(r["breakdown"])
    print()
    print(_table(results))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
