"""navkit against its peers, workload by workload, in one process: medians and ratios.

Usage (from the repository root, with the ``bench`` extra installed)::

    python benchmarks/compare_peers.py                 # every workload (< 10 min on 2 cores)
    python benchmarks/compare_peers.py --quick         # a subset, fewer repeats (< 2 min)
    python benchmarks/compare_peers.py --only astar-random20 'movingai-*'
    python benchmarks/compare_peers.py --list          # the workloads
    python benchmarks/compare_peers.py --json results.json

Each workload runs the same input through navkit and its peers (pyastar2d,
tcod, scikit-image ``MCP_Geometric`` and ``draw.line``, SciPy csgraph, filterpy,
ir-sim, KISS-ICP, NumPy, a pure-Python reference). The inputs and the peers'
calls are those of the pytest-benchmark files beside this script (imported from
them, not copied), so a row here and a group there time the same thing.

For every contestant:

1. the timed call is built (input conversion, graphs, environments: outside
   the timer);
2. its **first call** is timed on its own and reported separately: for navkit
   it includes loading the compiled kernels from numba's on-disk cache, or
   compiling them when the cache is cold;
3. the results are **checked** against navkit's where they are comparable
   (equal path costs for exact A*, equal fields, equal wheel speeds, poses,
   cells, ranges, filter states) before any timing; a mismatch is reported in
   the row, the contestant is not timed and the exit code is 1;
4. the call is timed ``timeit``-style: a warm call estimates its duration,
   calls are grouped so that one sample lasts at least ``--min-time``, and
   samples of all contestants of a workload are taken in turns (so that a
   change in the machine's load hits all of them alike) until each has
   ``--repeats`` samples or has used its ``--budget`` seconds. The median per
   call is reported; garbage collection is off while a sample runs. A call
   whose benchmark gives it new arguments every round (pytest-benchmark's
   ``pedantic(setup=...)``: new points, new scans, each round's answer checked
   in the next round's setup) gets them here too: its setup runs before every
   call, outside the timer (at most 200 calls a sample), and once more after
   the last, so every timed answer is checked; one that fails a check under
   the timer is reported as a mismatch, not timed further. Its times are per
   input when a round times several (``extra_info["calls_per_round"]``: the
   repulsion rows' 16 scans).

The table: workload, navkit's median and first call, the peer, the peer's
median and first call, and the **ratio peer time / navkit time (> 1: navkit is
faster)**, with the check's verdict. A peer that is not installed gives a row
saying so (the ``bench`` extra has pyastar2d, tcod, ir-sim and kiss-icp;
scikit-image and filterpy are in ``test``); workloads on ``../shared/data``
say "data not available" without it. The machine (CPU, cores, load, Python,
NumPy, numba and peer versions) and the date are printed above the table.
"""

from __future__ import annotations

import argparse
import fnmatch
import functools
import gc
import importlib
import importlib.metadata
import importlib.util
import math
import os
import platform
import statistics
import sys
import tempfile
import time
import timeit
import types
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

#: Peer libraries: table label -> (import name, distribution name).
PEERS: dict[str, tuple[str, str]] = {
    "pyastar2d": ("pyastar2d", "pyastar2d"),
    "tcod": ("tcod", "tcod"),
    "scikit-image": ("skimage", "scikit-image"),
    "SciPy": ("scipy", "scipy"),
    "filterpy": ("filterpy", "filterpy"),
    "ir-sim": ("irsim", "ir-sim"),
    "KISS-ICP": ("kiss_icp", "kiss-icp"),
}
#: Peers navkit itself imports: ``--without`` cannot hide them (navkit would not load).
NAVKIT_NEEDS = {"scipy"}

#: (min_time per sample s, repeats, budget per contestant s) of a full and a quick run.
FULL = (0.2, 7, 4.0)
QUICK = (0.05, 3, 1.0)

Call = Callable[[], Any]
Ready = tuple[Call, Any, float]  # the timed call, its first result, its first call in s


# ------------------------------------------------------------------ peers and modules
class _Absent(types.ModuleType):
    """Stands in for a peer that is not installed while a benchmark module imports it.

    The benchmark files import some peers at the top; with this placeholder their
    workload builders still load, and any use of the peer fails loudly.
    """

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.__path__: list[str] = []  # a package: its submodules get placeholders too

    def __getattr__(self, attr: str) -> Any:
        if attr.startswith("__"):
            raise AttributeError(attr)
        return _Absent(f"{self.__name__}.{attr}")

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        raise ModuleNotFoundError(f"{self.__name__.split('.')[0]} is not installed")


@dataclass
class Run:
    """Options and state of one run of the script."""

    min_time: float = FULL[0]
    repeats: int = FULL[1]
    budget: float = FULL[2]
    missing: set[str] = field(default_factory=set)  # import names of absent peers
    folder: Path = Path(".")  # scratch folder (ir-sim world files)


RUN = Run()


def installed(label: str) -> bool:
    """Whether the peer ``label`` of :data:`PEERS` can be used in this run."""
    return PEERS[label][0] not in RUN.missing


def bench(name: str) -> Any:
    """Import the benchmark module ``name``, with placeholders for absent peers."""
    for _ in range(50):
        try:
            return importlib.import_module(name)
        except ModuleNotFoundError as exc:
            missing = exc.name or ""
            if missing.split(".")[0] not in RUN.missing:
                raise
            sys.modules[missing] = _Absent(missing)
    raise ImportError(f"could not import {name}")


class Staged:
    """A timed call whose arguments ``setup`` makes anew before every call, outside the timer.

    The ``setup=`` of pytest-benchmark's ``pedantic``: ``setup()`` returns
    ``(args, kwargs)`` for one call of ``fn``. A benchmark that gives each round
    new inputs (a cache on the input cannot stand in for the work) or checks the
    previous round's answer in its setup (``test_bench_astar.timed_fresh``) does
    both here too: :class:`Timer` calls ``setup`` before every timed call and
    once more after the last one.
    """

    def __init__(
        self,
        fn: Callable[..., Any],
        setup: Callable[[], tuple[Sequence[Any], dict[str, Any]]],
    ) -> None:
        self.fn = fn
        self.setup = setup
        # Calls of the measured operation in one call of fn (a benchmark timing several
        # inputs a round says so in extra_info["calls_per_round"]): times are per call.
        self.per = 1

    def timed(self, number: int) -> float:
        """Seconds of ``number`` calls, each after its own (untimed) setup, gc off, per
        call of the measured operation (``fn``'s time over :attr:`per`)."""
        total = 0.0
        enabled = gc.isenabled()
        gc.disable()
        try:
            for _ in range(number):
                args, kwargs = self.setup()
                t0 = time.perf_counter()
                self.fn(*args, **kwargs)
                total += time.perf_counter() - t0
        finally:
            if enabled:
                gc.enable()
        return total / self.per

    def finish(self) -> None:
        """One more setup, untimed: a check it makes of the last call's answer runs."""
        self.setup()

    def __call__(self) -> Any:
        args, kwargs = self.setup()
        return self.fn(*args, **kwargs)


class Capture:
    """Stands in for pytest-benchmark's fixture: keeps the call a benchmark test times.

    ``test_fn(capture, ...)`` runs the test's setup and one call of its timed
    function (the first call); the call itself is then :attr:`call`: a plain
    call, or a :class:`Staged` one when the test passed ``pedantic`` a
    ``setup`` (new arguments before every call, as pytest-benchmark does).
    """

    def __init__(self) -> None:
        self.group = ""
        self.extra_info: dict[str, Any] = {}
        self.call: Call | None = None
        self.result: Any = None
        self.first_s = math.nan

    def __call__(self, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        self.call = functools.partial(fn, *args, **kwargs)
        t0 = time.perf_counter()
        self.result = self.call()
        self.first_s = time.perf_counter() - t0
        return self.result

    def pedantic(
        self,
        fn: Callable[..., Any],
        args: Sequence[Any] = (),
        kwargs: dict[str, Any] | None = None,
        setup: Callable[[], Any] | None = None,
        **_: Any,
    ) -> Any:
        if setup is None:
            return self(fn, *args, **(kwargs or {}))
        if args or kwargs:
            # pytest-benchmark refuses both too: the setup's arguments would be ignored.
            raise TypeError("pedantic: setup= cannot be combined with args= or kwargs=")

        def arguments() -> tuple[Sequence[Any], dict[str, Any]]:
            made = setup()
            # pytest-benchmark's setup may return None: the call then takes no arguments.
            return ((), {}) if made is None else made

        staged = Staged(fn, arguments)
        self.call = staged
        args_now, kwargs_now = arguments()
        t0 = time.perf_counter()
        self.result = fn(*args_now, **kwargs_now)
        self.first_s = time.perf_counter() - t0
        return self.result

    @property
    def stats(self) -> Any:
        first = types.SimpleNamespace(mean=self.first_s, median=self.first_s)
        return types.SimpleNamespace(stats=first)


def captured(test_fn: Callable[..., Any], *args: Any) -> Ready:
    """The timed call of a pytest-benchmark test function, after its first call."""
    capture = Capture()
    test_fn(capture, *args)
    assert capture.call is not None, f"{test_fn.__name__} timed nothing"
    per = int(capture.extra_info.get("calls_per_round", 1))
    if isinstance(capture.call, Staged):
        capture.call.per = per
    elif per != 1:
        raise ValueError(f"{test_fn.__name__}: calls_per_round without a setup")
    return capture.call, capture.result, capture.first_s / per


def ready(call: Call) -> Ready:
    """``call`` after its first (timed) call."""
    t0 = time.perf_counter()
    result = call()
    return call, result, time.perf_counter() - t0


# ------------------------------------------------------------------ workloads
Check = Callable[[Any, Any], str]


@dataclass(frozen=True)
class Contestant:
    """One library's way through a workload."""

    label: str
    make: Callable[[], Ready]
    peer: str | None = None  # key of PEERS, None for navkit, NumPy, numba and pure Python
    check: Check | None = None  # (navkit's result, this result) -> verdict; raises on mismatch
    skip: str | None = None  # why it does not run here (stated in its row)


@dataclass(frozen=True)
class Workload:
    name: str
    title: str
    navkit: Contestant
    peers: tuple[Contestant, ...]
    quick: bool = False
    check: Callable[[Any], str] | None = None  # an extra check of navkit's own result


def _routes(
    name: str,
    costs_and_scenarios: Callable[[], tuple[np.ndarray, Sequence[Any]]],
    *,
    python: str | None,
    check: Callable[[Any], str] | None = None,
    quick: bool = False,
    title: str,
) -> Workload:
    """A* over routes on one map: navkit, tcod, MCP_Geometric, pyastar2d, pure Python."""

    def maker(who: str) -> Callable[[], Ready]:
        def make() -> Ready:
            mod = bench("test_bench_movingai")
            return ready(mod.ROUTE_MAKERS[who](*costs_and_scenarios()))

        return make

    def checker(who: str) -> Check:
        def check_one(ours: Any, theirs: Any) -> str:
            mod = bench("test_bench_movingai")
            costs, scenarios = costs_and_scenarios()
            verdict: str = mod.check_routes(costs, scenarios, ours, who, theirs)
            return verdict

        return check_one

    peers = (
        Contestant("tcod AStar", maker("tcod"), "tcod", checker("tcod")),
        Contestant("scikit-image MCP_Geometric", maker("mcp"), "scikit-image", checker("mcp")),
        Contestant("pyastar2d", maker("pyastar2d"), "pyastar2d", checker("pyastar2d")),
        Contestant(
            "pure-Python heapq A*", maker("pure_python"), None, checker("pure_python"), skip=python
        ),
    )
    return Workload(name, title, Contestant("navkit astar", maker("navkit")), peers, quick, check)


def _random_map(name: str) -> tuple[np.ndarray, Sequence[Any]]:
    astar_mod = bench("test_bench_astar")
    scenario = bench("test_bench_movingai").Scenario(astar_mod.START, astar_mod.GOAL, math.nan)
    return astar_mod.benchmark_map(name), (scenario,)


def _movingai_map(name: str) -> tuple[np.ndarray, Sequence[Any]]:
    mod = bench("test_bench_movingai")
    return mod.movingai(name)[0], mod.scenario_sample(name)


def _published(name: str) -> Callable[[Any], str]:
    def check(_: Any) -> str:
        verdict: str = bench("test_bench_movingai").check_published(*_movingai_map(name))
        return verdict

    return check


def _fields(name: str, quick: bool) -> Workload:
    def maker(who: str) -> Callable[[], Ready]:
        def make() -> Ready:
            mod = bench("test_bench_movingai")
            return ready(mod.FIELD_MAKERS[who](*mod.field_case(name)))

        return make

    def check(ours: Any, theirs: Any) -> str:
        verdict: str = bench("test_bench_movingai").check_field(ours, theirs)
        return verdict

    label = name.rsplit("/", 1)[-1]
    return Workload(
        f"distance-field-{label}",
        f"cost-to-go field over the whole {label} map (1024²), corner cutting",
        Contestant("navkit distance_field", maker("navkit")),
        (
            Contestant("SciPy csgraph dijkstra", maker("csgraph"), "SciPy", check),
            Contestant("scikit-image MCP_Geometric", maker("mcp"), "scikit-image", check),
        ),
        quick,
    )


def _module(
    module: str,
    name: str,
    title: str,
    contestants: Sequence[tuple[str, str, str | None]],
    *,
    quick: bool,
    args: tuple[Any, ...] = (),
) -> Workload:
    """A workload of a benchmark module with ``make_call(who, *args)`` and ``check_result``.

    ``contestants``: (label, who, peer library or None), navkit's first.
    """

    def maker(who: str) -> Callable[[], Ready]:
        return lambda: ready(bench(module).make_call(who, *args))

    def checker(who: str) -> Check:
        def check(ours: Any, theirs: Any) -> str:
            verdict: str = bench(module).check_result(who, ours, theirs)
            return verdict

        return check

    (label, who, _), *peers = contestants
    return Workload(
        name,
        title,
        Contestant(label, maker(who)),
        tuple(Contestant(lab, maker(w), peer, checker(w)) for lab, w, peer in peers),
        quick,
    )


def _repulsion(n_beams: int, quick: bool) -> Workload:
    def make(who: str) -> Callable[[], Ready]:
        def build() -> Ready:
            mod = bench("test_bench_fields")
            # The pytest groups' calls: every call on a scan of its own, its force checked.
            test = mod.test_public_call if who == "navkit" else mod.test_numpy_vectorised
            return captured(test, n_beams)

        return build

    def check(ours: Any, theirs: Any) -> str:
        np.testing.assert_allclose(theirs, ours, rtol=1e-9)
        return "same force (1e-9)"

    return Workload(
        f"repulsion-{n_beams}",
        f"per-beam repulsion of a {n_beams}-beam scan, a new scan every call "
        "(repulsive_force_from_scan)",
        Contestant("navkit", make("navkit")),
        (Contestant("NumPy vectorised", make("numpy"), None, check),),
        quick,
    )


def _ekf() -> Workload:
    """1000 predict + update steps of the unicycle EKF of ``test_bench_ekf``."""

    def navkit_call() -> Ready:
        mod = bench("test_bench_ekf")
        from navkit.estimation import PlanarFusion

        times = mod.DT * np.arange(1, mod.STEPS + 1)
        rows = [
            (float(t), float(v), float(w))
            for t, (v, w) in zip(times, mod.MEASUREMENTS, strict=True)
        ]

        def run() -> tuple[np.ndarray, np.ndarray]:
            fusion = PlanarFusion(mod.X0, mod.P0, process_noise=mod.Q_PER_S, t0=0.0)
            for t, v, w in rows:
                fusion.update_odometry(t, v, w, v_variance=1e-3, omega_variance=1e-3)
            return fusion.x, fusion.P

        return ready(run)

    def filterpy_call() -> Ready:
        mod = bench("test_bench_ekf")
        f, jac = mod.motion(mod.DT)

        class Model(mod.FilterpyEKF):  # type: ignore[misc, name-defined]
            x: np.ndarray

            def predict_x(self, u: object = 0) -> None:
                self.x = f(self.x)

        def run() -> tuple[np.ndarray, np.ndarray]:
            ekf = Model(dim_x=6, dim_z=2)
            ekf.x, ekf.P, ekf.Q = mod.X0.copy(), mod.P0.copy(), mod.Q_PER_S * mod.DT
            for z in mod.MEASUREMENTS:
                ekf.F = jac(ekf.x)
                ekf.predict()
                ekf.update(z, lambda x: mod.H_ODOM, lambda x: mod.H_ODOM @ x, R=mod.R_ODOM)
            return ekf.x, ekf.P

        return ready(run)

    def check(ours: Any, theirs: Any) -> str:
        mod = bench("test_bench_ekf")
        mod.assert_same_state(ours, theirs)
        return f"same state and covariance ({mod.SAME_STATE_RTOL:.0e})"

    return Workload(
        "ekf-step-x1000",
        "1000 EKF predict + odometry update steps, 6-state unicycle (PlanarFusion)",
        Contestant("navkit PlanarFusion", navkit_call),
        (Contestant("filterpy ExtendedKalmanFilter", filterpy_call, "filterpy", check),),
        quick=True,
    )


def _world_to_cell() -> Workload:
    def make(who: str) -> Callable[[], Ready]:
        return lambda: captured(bench("test_bench_mapping").test_world_to_cell, who)

    def check(ours: Any, theirs: Any) -> str:
        assert np.array_equal(ours, theirs), "different cells"
        return "same cells"

    return Workload(
        "world-to-cell-1e6",
        "world_to_cell of 10^6 points on a rotated grid, new points every call "
        "(OccupancyGrid.world_to_cell)",
        Contestant("navkit", make("navkit")),
        (Contestant("NumPy", make("numpy"), None, check),),
        quick=True,
    )


def _lidar(world: str, quick: bool) -> Workload:
    def navkit_call() -> Ready:
        mod = bench("test_bench_sim")
        from navkit.sim import Lidar

        scene = mod.scene(world)
        lidar = Lidar(noise=None, range_max=mod.RANGE_MAX)
        nxt = mod._cycle(scene["poses"])
        return ready(lambda: lidar.scan(scene["world"], nxt()))

    def irsim_call() -> Ready:
        mod = bench("test_bench_sim")
        env = _irsim_env(world)
        states = [mod._state(p) for p in mod.scene(world)["poses"]]
        k = {"i": 0}

        def step() -> None:
            k["i"] = (k["i"] + 1) % len(states)
            env.robot.lidar.step(states[k["i"]])

        return ready(step)

    def check(ours: Any, theirs: Any) -> str:
        bench("test_bench_sim").test_ranges_agree(world, _irsim_env)
        return "same ranges on 16 poses (1e-9 m)"

    return Workload(
        f"lidar-{world}",
        f"one simulated 360-beam LiDAR scan, 12 m, world '{world}' (sim.Lidar)",
        Contestant("navkit Lidar.scan", navkit_call),
        (Contestant("ir-sim lidar2d", irsim_call, "ir-sim", check),),
        quick,
    )


@functools.cache
def _irsim_env(world: str) -> Any:
    return bench("test_bench_sim").irsim_env(world, RUN.folder)


def _scan_matching() -> Workload:
    def make(who: str) -> Callable[[], Ready]:
        def build() -> Ready:
            mod = bench("test_bench_scan_matching")
            test = (
                mod.test_match_and_write_360_beams
                if who == "navkit"
                else (mod.test_kiss_icp_per_scan)
            )
            return captured(test)

        return build

    def check(ours: Any, theirs: Any) -> str:
        return "not compared: different algorithms (accuracy: carmen_eval.py)"

    return Workload(
        "scan-match-360",
        "match one 360-beam scan to the map and update it (ScanMapper.update)",
        Contestant("navkit ScanMapper", make("navkit")),
        (Contestant("KISS-ICP register_frame", make("kiss"), "KISS-ICP", check),),
        quick=True,
    )


def workloads() -> list[Workload]:
    """Every workload, in table order (built lazily: nothing is imported here)."""
    slow_python = "not run: 10-30 s per call here; see the astar-* rows"
    out = [
        _routes(
            f"astar-{name}",
            functools.partial(_random_map, name),
            python=None,
            quick=name == "random20",
            title=f"A* corner to corner on the 1024² {name} map, corner cutting",
        )
        for name in ("random20", "random35", "rooms")
    ]
    for name, python in (
        ("dao/arena2", None),
        ("maze/maze512-1-0", slow_python),
        ("random/random512-10-0", None),
        ("room/8room_000", slow_python),
        ("street/Berlin_0_1024", slow_python),
    ):
        short = name.rsplit("/", 1)[-1]
        out.append(
            _routes(
                f"movingai-{short}",
                functools.partial(_movingai_map, name),
                python=python,
                check=_published(name),
                quick=short == "arena2",
                title=f"A* on 10 MovingAI {short} scenarios (short to longest), corner cutting",
            )
        )
    out += [_fields("random20", True), _fields("street/Berlin_0_1024", False)]
    out.append(
        _module(
            "test_bench_kinematics",
            "omni-ik",
            "omni-wheel inverse kinematics of 10^6 twists (OmniDrive.inverse_batch)",
            [
                ("navkit", "navkit", None),
                ("NumPy matrix product", "numpy", None),
                ("pure Python", "pure_python", None),
            ],
            quick=True,
        )
    )
    out.append(
        _module(
            "test_bench_geometry",
            "rollout",
            "rollout of 10^5 body twists, exact SE(2) steps (geometry.rollout)",
            [
                ("navkit", "navkit", None),
                ("pure Python", "pure_python", None),
                ("NumPy prefix sums", "numpy", None),
            ],
            quick=True,
        )
    )
    out += [
        _module(
            "test_bench_raycast",
            f"raycast-{n}",
            f"one {n}-beam scan into a 600² grid (mapping.integrate_scan)",
            [
                ("navkit integrate_scan", "navkit", None),
                ("scikit-image draw.line loop", "skimage", "scikit-image"),
                ("bare numba Bresenham", "numba", None),
            ],
            quick=n == 360,
            args=(n,),
        )
        for n in (360, 3600)
    ]
    out += [_repulsion(360, True), _repulsion(3600, False), _ekf(), _world_to_cell()]
    out += [_lidar(w, w == "room") for w in ("room", "polygons100", "polygons500", "willow")]
    out.append(_scan_matching())
    return out


# ------------------------------------------------------------------ timing
@dataclass
class Timer:
    """Samples of one contestant's timed call."""

    call: Call
    number: int = 1
    target: int = 1
    samples: list[float] = field(default_factory=list)
    failed: str = ""  # a check under the timing that failed (a staged call's setup)

    def sample(self) -> None:
        try:
            self.samples.append(_seconds(self.call, self.number) / self.number)
        except AssertionError as exc:
            self.fail(exc)

    def finish(self) -> None:
        """A staged call's last setup, which checks the last timed answer."""
        if isinstance(self.call, Staged) and not self.failed:
            try:
                self.call.finish()
            except AssertionError as exc:
                self.fail(exc)

    def fail(self, exc: AssertionError) -> None:
        self.failed = str(exc).strip().splitlines()[0][:80] if str(exc).strip() else "failed"
        self.target = len(self.samples)  # no more samples: its times are not the work's

    @property
    def median(self) -> float:
        return statistics.median(self.samples)


#: Calls per sample of a :class:`Staged` call at most: each has its own setup (new
#: arguments, the previous answer's check), which can cost far more than the call.
STAGED_NUMBER = 200


def _seconds(call: Call, number: int) -> float:
    """Seconds of ``number`` calls of ``call`` (a staged call's setups untimed), gc off."""
    if isinstance(call, Staged):
        return call.timed(number)
    return timeit.Timer(call).timeit(number)


def calibrate(call: Call) -> Timer:
    """Time one warm call; choose calls per sample and the number of samples."""
    estimate = max(_seconds(call, 1), 1e-9)
    timer = Timer(call)
    if estimate >= RUN.min_time:
        timer.samples.append(estimate)
    else:
        most = STAGED_NUMBER if isinstance(call, Staged) else 10_000_000
        timer.number = min(math.ceil(RUN.min_time / estimate), most)
    timer.target = max(1, min(RUN.repeats, int(RUN.budget / (timer.number * estimate))))
    return timer


def measure(timers: Sequence[Timer]) -> None:
    """Sample the timers in turns until each has its target number of samples."""
    while True:
        due = [t for t in timers if len(t.samples) < t.target]
        if not due:
            return
        for timer in due:
            timer.sample()


# ------------------------------------------------------------------ running
@dataclass
class Row:
    workload: str
    peer: str
    navkit_median_s: float | None = None
    navkit_first_s: float | None = None
    peer_median_s: float | None = None
    peer_first_s: float | None = None
    status: str = ""  # "", "not installed", "skipped ...", "data not available", "mismatch", ...
    check: str = ""

    @property
    def ratio(self) -> float | None:
        if self.navkit_median_s and self.peer_median_s:
            return self.peer_median_s / self.navkit_median_s
        return None


def _attempt(make: Callable[[], Ready]) -> tuple[Ready | None, str]:
    """``make()``, or the reason it could not run."""
    import pytest

    try:
        return make(), ""
    except pytest.skip.Exception as exc:
        return None, f"data not available ({str(exc.msg).splitlines()[0][:60]})"
    except Exception as exc:  # a broken peer or workload: report it in the row
        return None, f"error: {type(exc).__name__}: {str(exc).splitlines()[0][:80]}"


def run_workload(work: Workload, log: Callable[[str], None]) -> list[Row]:
    """Check and time one workload; one row per peer."""
    log(f"{work.name}: {work.title}")
    ours, why = _attempt(work.navkit.make)
    if ours is None:
        return [Row(work.name, p.label, status=why) for p in work.peers]
    own_check = ""
    if work.check is not None:
        try:
            own_check = work.check(ours[1])
        except AssertionError as exc:
            own_check = f"MISMATCH navkit: {str(exc).strip().splitlines()[0][:80]}"
    rows: list[Row] = []
    timers: list[tuple[Row | None, Timer]] = [(None, calibrate(ours[0]))]
    for peer in work.peers:
        row = Row(work.name, peer.label)
        rows.append(row)
        if peer.peer is not None and not installed(peer.peer):
            row.status = f"not installed ({PEERS[peer.peer][1]})"
            continue
        if peer.skip is not None:
            row.status = peer.skip
            continue
        theirs, why = _attempt(peer.make)
        if theirs is None:
            row.status = why
            continue
        row.peer_first_s = theirs[2]
        try:
            row.check = peer.check(ours[1], theirs[1]) if peer.check is not None else ""
        except AssertionError as exc:
            row.status = "MISMATCH"
            row.check = str(exc).strip().splitlines()[0][:100]
            continue
        log(f"  {peer.label}: first call {_fmt(theirs[2])}, {row.check}")
        timers.append((row, calibrate(theirs[0])))
    measure([t for _, t in timers])
    for _, timer in timers:
        timer.finish()
    navkit_timer = timers[0][1]
    navkit_median = None if navkit_timer.failed else navkit_timer.median
    for peer_row, timer in timers[1:]:
        assert peer_row is not None
        if timer.failed:
            peer_row.status = "MISMATCH"
            peer_row.check = f"under the timer: {timer.failed}"
        else:
            peer_row.peer_median_s = timer.median
    if navkit_timer.failed:
        own_check = f"MISMATCH navkit under the timer: {navkit_timer.failed}"
    for row in rows:
        row.navkit_median_s = navkit_median
        row.navkit_first_s = ours[2]
    if not rows:
        rows.append(Row(work.name, "—", navkit_median, ours[2]))
    if own_check:
        rows[0].check = f"{own_check}; {rows[0].check}" if rows[0].check else own_check
    return rows


# ------------------------------------------------------------------ report
def _fmt(seconds: float | None) -> str:
    if seconds is None or not math.isfinite(seconds):
        return "—"
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds / 1e-9:.3g} ns"


def _ratio(value: float | None) -> str:
    if value is None:
        return "—"
    return f"{value:.3g}" if value < 100 else f"{value:,.0f}"


def machine() -> dict[str, Any]:
    """The machine and the versions the run used."""
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count() or 0
    versions = {}
    for dist in ("navkit", "numpy", "numba", "scipy", *(d for _, d in PEERS.values())):
        try:
            versions[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            versions[dist] = "not installed"
    for module, dist in PEERS.values():
        if module in RUN.missing:
            versions[dist] = "not installed"
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "load_average_1_5_15": [round(v, 2) for v in load],
        "os": platform.platform(),
        "python": platform.python_version(),
        "versions": versions,
    }


def header(info: dict[str, Any], date: str, args: argparse.Namespace) -> str:
    v = info["versions"]
    peers = ", ".join(f"{d} {v[d]}" for _, d in PEERS.values() if d != "scipy")
    return "\n".join(
        [
            f"- date: {date}",
            f"- machine: {info['cpu']}, {info['cores']} cores ({info['usable_cores']} usable), "
            f"load average {info['load_average_1_5_15']} at the start, {info['os']}",
            f"- Python {info['python']}, NumPy {v['numpy']}, numba {v['numba']}, "
            f"SciPy {v['scipy']}, navkit {v['navkit']}",
            f"- peers: {peers}",
            f"- mode: {'--quick' if args.quick else 'full'}; at least {_fmt(RUN.min_time)} per "
            f"sample, up to {RUN.repeats} samples or {RUN.budget:g} s per contestant",
        ]
    )


def table(rows: Sequence[Row]) -> str:
    lines = [
        "| workload | navkit median | navkit first call | peer | peer median | peer first call "
        "| ratio peer/navkit | check |",
        "| --- | ---: | ---: | --- | ---: | ---: | ---: | --- |",
    ]
    for row in rows:
        peer_median = (
            row.status if row.status and row.status != "MISMATCH" else _fmt(row.peer_median_s)
        )
        check = f"MISMATCH: {row.check}" if row.status == "MISMATCH" else row.check
        lines.append(
            f"| {row.workload} | {_fmt(row.navkit_median_s)} | {_fmt(row.navkit_first_s)} "
            f"| {row.peer} | {peer_median} | {_fmt(row.peer_first_s)} | {_ratio(row.ratio)} "
            f"| {check} |"
        )
    return "\n".join(lines)


def _json_float(value: float | None) -> float | None:
    return value if value is not None and math.isfinite(value) else None


# ------------------------------------------------------------------ command line
def parse(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="compare_peers.py",
        description="Time navkit and its peers on the same workloads; print medians and ratios "
        "(peer time / navkit time: > 1 means navkit is faster).",
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="a subset of the workloads with fewer repeats (< 2 min)",
    )
    parser.add_argument(
        "--only",
        nargs="+",
        metavar="NAME",
        help="workloads to run: names or shell patterns (see --list)",
    )
    parser.add_argument("--list", action="store_true", help="list the workloads and exit")
    parser.add_argument("--json", metavar="FILE", help="also write the results to FILE (JSON)")
    parser.add_argument(
        "--without",
        nargs="+",
        default=[],
        metavar="PEER",
        help="treat these peers as not installed (labels or import names)",
    )
    parser.add_argument("--min-time", type=float, help="seconds per sample at least")
    parser.add_argument("--repeats", type=int, help="samples per contestant at most")
    parser.add_argument(
        "--budget",
        type=float,
        help="seconds of timing per contestant at most (after the first call)",
    )
    return parser.parse_args(argv)


def select(all_work: Sequence[Workload], args: argparse.Namespace) -> list[Workload]:
    if not args.only:
        return [w for w in all_work if w.quick or not args.quick]
    names = [w.name for w in all_work]
    for pattern in args.only:
        if not fnmatch.filter(names, pattern):
            raise SystemExit(
                f"compare_peers.py: no workload matches {pattern!r}; "
                f"choose from: {', '.join(names)}"
            )
    return [w for w in all_work if any(fnmatch.fnmatch(w.name, p) for p in args.only)]


def main(argv: Sequence[str] | None = None) -> int:
    args = parse(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")  # ir-sim imports matplotlib: no GUI probing
    defaults = QUICK if args.quick else FULL
    RUN.min_time = args.min_time if args.min_time is not None else defaults[0]
    RUN.repeats = args.repeats if args.repeats is not None else defaults[1]
    RUN.budget = args.budget if args.budget is not None else defaults[2]
    modules = {label: module for label, (module, _) in PEERS.items()}
    for name in args.without:
        module = modules.get(name, name)
        if module not in modules.values():
            raise SystemExit(
                f"compare_peers.py: unknown peer {name!r}; choose from: {', '.join(PEERS)}"
            )
        if module in NAVKIT_NEEDS:
            raise SystemExit(
                f"compare_peers.py: --without {name}: navkit itself needs {module}, "
                "so it cannot be treated as not installed"
            )
        sys.modules[module] = None  # type: ignore[assignment]  # imports of it now fail
        RUN.missing.add(module)
    RUN.missing |= {m for m in modules.values() if importlib.util.find_spec(m) is None}
    all_work = workloads()
    if args.list:
        for work in all_work:
            print(f"{work.name:26} {'quick ' if work.quick else '      '}{work.title}")
        return 0
    chosen = select(all_work, args)
    date = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    info = machine()
    started = time.perf_counter()

    def log(text: str) -> None:
        print(f"[{time.perf_counter() - started:6.1f} s] {text}", file=sys.stderr, flush=True)

    rows: list[Row] = []
    with tempfile.TemporaryDirectory(prefix="navkit-compare-") as folder:
        RUN.folder = Path(folder)
        for work in chosen:
            rows += run_workload(work, log)
            gc.collect()
    load_end = [round(v, 2) for v in os.getloadavg()] if hasattr(os, "getloadavg") else []
    print(header(info, date, args))
    print(f"- load average {load_end} at the end; {time.perf_counter() - started:.0f} s in all")
    print()
    print(table(rows))
    print()
    for work in chosen:
        print(f"- `{work.name}`: {work.title}")
    failed = any(
        r.status == "MISMATCH" or r.status.startswith("error") or r.check.startswith("MISMATCH")
        for r in rows
    )
    if args.json:
        from navkit.cli._files import write_json

        write_json(
            {
                "date": date,
                "machine": info,
                "load_average_end": load_end,
                "options": {
                    "quick": args.quick,
                    "min_time_s": RUN.min_time,
                    "repeats": RUN.repeats,
                    "budget_s": RUN.budget,
                },
                "workloads": {w.name: w.title for w in chosen},
                "rows": [
                    {
                        "workload": r.workload,
                        "peer": r.peer,
                        "status": r.status,
                        "check": r.check,
                        "navkit_median_s": _json_float(r.navkit_median_s),
                        "navkit_first_s": _json_float(r.navkit_first_s),
                        "peer_median_s": _json_float(r.peer_median_s),
                        "peer_first_s": _json_float(r.peer_first_s),
                        "ratio": _json_float(r.ratio),
                    }
                    for r in rows
                ],
            },
            args.json,
        )
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
