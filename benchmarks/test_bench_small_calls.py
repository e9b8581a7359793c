"""Small public calls against the numba kernels they wrap (issue 17).

Run with ``python -m pytest benchmarks/test_bench_small_calls.py --benchmark-only``.

Each group times a public call and, in the same run, a bare call of the kernel it
ends in with the same arguments (validation, result objects and copies left out);
the issue's goal is the public call within 1.5x of the kernel.

* ``update_odometry``: :meth:`PlanarFusion.update_odometry` at 100 Hz against
  ``planar_step`` on the filter's buffer (``kernel``, through numba's dispatcher,
  the issue's row; ``entry``, its compiled float64 entry, the same code as the
  entry the public call uses, ``planar_step_plain_entry``, which also takes
  the place of the public call's type checks; ``floor``, the entry plus the
  result the public call builds);
* ``world_to_cell``: :meth:`OccupancyGrid.world_to_cell` on 10 points against
  ``world_to_cell_kernel`` into a preallocated array: the kernel the public
  call ends in. Since session 39 the public fast path is one compiled entry
  (``navkit.mapping._new_cells_kernel``) that tests the points in C, makes the
  new (10, 2) result with NumPy's own ``PyArray_Empty`` and runs that kernel's
  code, so the public call costs less than ``floor`` (``np.empty`` from Python
  and the kernel through the dispatcher, no checks; about 1.6x the kernel).
  numba's own allocation and boxing of a result (a kernel returning a new
  array) remain slower: about 0.33 µs against 0.09 µs for ``np.empty`` from
  Python (session 27);
* ``repulsion``: :func:`repulsive_force_from_scan` on a 360-beam scan against
  ``khatib_beam_force`` with the cached beam tables (and ``khatib_beam_force_into``,
  the variant writing into an array with the (2, N) direction table, which the
  public call ends in);

The last two groups also time the floors of any Python wrapper: a bare function
that allocates the result and calls the kernel (``floor``), one that only calls
it (``noop_wrapper``), and the compiled kernel without numba's per-call type
dispatch (``entry``, which the repulsion's fast path and ``world_to_cell``'s general path call).
* ``DiffOdometry.update``: one encoder reading (was a one-row batch, ~0.2 ms),
  against a Python function doing the same arithmetic with no checks.
* ``quaternion_to_yaw``: one quaternion (plain floats, session 37's fast path)
  against the general array way and the bare formula with ``math``.

Every contestant's ``extra_info`` holds, once the others of its group have run,
the ratios of the group's ``public`` median to theirs (``public_over_kernel``,
``public_over_floor`` and so on): saved with ``--benchmark-json``, a run
reports its ratios without arithmetic by hand.
Medians of calls this short move by tens of percent on a loaded machine;
compare ratios from one run.

Those table ratios overstate the public calls' share. pytest-benchmark calls
each contestant as ``fn(*args, **kwargs)`` (keywords cost about 85 ns more
than a call written with them), and it picks the iterations per round from the
first call it times. The public contestants got one iteration per round (the
first ``world_to_cell`` call fetched its compiled entry; the repulsion call,
already warm, got one too), so each of their rounds also timed the timer and
the loop, which the kernels' rounds spread over 10-100 calls. The
``world_to_cell`` and ``repulsion`` groups therefore calibrate on the fastest
of 2,000 warm-up calls (``warmup=True``: 10 iterations per round; the public
medians went from 641 to 546 ns and from 711 to 604 ns in one run), and their
``paired`` contestant gives the issue's number: the public call and the
others, each written as a plain call in a loop of its own, timed alternately
in one loop (41 rounds, the order reversed every other round, this thread's
CPU time, the median per-round ratio) as ``test_bench_ekf.py``'s ratio test
does. After every round each loop's last answer is checked against the
kernel's (the filters' states; the cells and forces of the round's last
arguments), and ``world_to_cell`` and ``repulsion`` get new arguments every
round (new points for every call; eight new range sets, each call on a scan
object of its own), the same for every loop: a public call answering from a
cache under the timer either fails or is timed at its honest cost (before, the
same arguments every call and no check let one report 0.26-0.46). Its
``extra_info`` holds ``paired_public_over_kernel`` (repulsion:
``paired_public_over_kernel_into``, the kernel the public call ends in) and
the like, and each loop's median per call (``paired_<name>_ns``).
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np
import pytest

from navkit.estimation import DiffOdometry, PlanarFusion
from navkit.estimation._fusion_kernels import BUF_TIME, planar_step, planar_step_entry
from navkit.estimation._result import UpdateResult, new_result
from navkit.geometry import Pose2D, quaternion_to_yaw
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.mapping._grid_kernels import world_to_cell_entry, world_to_cell_kernel
from navkit.planning import repulsive_force_from_scan
from navkit.planning.reactive._limits import MIN_DISTANCE
from navkit.planning.reactive._scan_repulsion import _beam_directions, _beam_table
from navkit.planning.reactive._scan_repulsion_kernels import (
    khatib_beam_force,
    khatib_beam_force_into,
    khatib_entry,
)

# Per group, each contestant's benchmark fixture, in run order: the ratios are
# filled in as the group's contestants finish (pytest-benchmark writes
# extra_info at the end of the session).
_GROUPS: dict[str, dict[str, Any]] = {}


def _record(benchmark: Any, group: str, contestant: str) -> None:
    """Store this contestant's fixture and refresh its group's public/other ratios."""
    members = _GROUPS.setdefault(group, {})
    members[contestant] = benchmark
    medians = {
        name: bench.stats.stats.median
        for name, bench in members.items()
        # stats is None with --benchmark-disable; "paired" times a loop of its own.
        if getattr(bench, "stats", None) is not None and name != "paired"
    }
    public = medians.get("public")
    if public is None:
        return
    ratios = {f"public_over_{name}": public / m for name, m in medians.items() if name != "public"}
    for bench in members.values():
        bench.extra_info.update(ratios)


@pytest.fixture(autouse=True)
def _ratios(request: pytest.FixtureRequest, benchmark: Any) -> Iterator[None]:
    """After each contestant: record it in its group (see :func:`_record`)."""
    yield
    marker = request.node.get_closest_marker("benchmark")
    _record(benchmark, marker.kwargs["group"], request.node.callspec.params["contestant"])


_PAIRED_ROUNDS = 41


def _paired(
    loops: dict[str, Callable[[Sequence[Any]], object]],
    calls: int,
    check: Callable[[dict[str, object], Any], None],
    inputs: Callable[[int], Sequence[Any]] | None = None,
) -> dict[str, float]:
    """``paired_public_over_<name>``: the median per-round ratio of ``loops["public"]``'s
    CPU time to each other loop's, all run in every round (order reversed every other
    round), each making ``calls`` calls. See the module docstring.

    ``inputs(round)``, when given, makes that round's argument sets (new objects,
    outside the timers); every loop cycles through the same ones, so neither side
    can answer from a cache keyed on its arguments from round to round. Else each
    loop gets ``range(calls)``. After each round, outside the timers,
    ``check(answers, last)`` gets each loop's returned answer (its last call's)
    and the round's last argument set (``None`` without ``inputs``), and asserts
    it is the kernel's: a loop right on its untimed warm-up and wrong (say,
    cached) under the timer fails instead of reporting its ratio.
    """
    names = list(loops)
    times: dict[str, list[float]] = {name: [] for name in names}

    def todo(round_: int) -> Sequence[Any]:
        if inputs is None:
            return range(calls)
        sets = inputs(round_)
        return [sets[k % len(sets)] for k in range(calls)]

    warm = todo(-1)[:10]
    for name in names:
        loops[name](warm)
    for i in range(_PAIRED_ROUNDS):
        args = todo(i)
        answers: dict[str, object] = {}
        for name in names if i % 2 == 0 else names[::-1]:
            t0 = time.thread_time()
            answers[name] = loops[name](args)
            times[name].append(time.thread_time() - t0)
        check(answers, None if inputs is None else args[-1])
    public = np.array(times["public"])
    ratios = {
        f"paired_public_over_{name}": float(np.median(public / np.array(times[name])))
        for name in names
        if name != "public"
    }
    ratios.update(
        {f"paired_{name}_ns": float(np.median(times[name])) / calls * 1e9 for name in names}
    )
    return ratios


class _Clock:
    """Increasing measurement times, 100 Hz."""

    def __init__(self) -> None:
        self.t = 0.0

    def __call__(self) -> float:
        self.t += 0.01
        return self.t


@pytest.mark.benchmark(group="update_odometry", warmup=True, warmup_iterations=2000)
@pytest.mark.parametrize("contestant", ["public", "kernel", "entry", "floor", "paired"])
def test_update_odometry(benchmark: Any, contestant: str) -> None:
    """``kernel``: ``planar_step`` through numba's dispatcher (the issue's row); ``entry``:
    the compiled entry without type dispatch, which the public call uses.

    ``floor``: a bare function calling the entry and building the result as the
    public call does (``new_result``: an :class:`UpdateResult` by plain
    slot stores, a copy of the residual), without its type checks, method call
    and keyword arguments. ``paired``: the public call (with its keywords, as
    written by a user) against ``kernel``, ``entry`` and ``floor`` in one timing
    loop, each on a filter of its own at 100 Hz (the issue's number; module
    docstring).
    """
    fusion = PlanarFusion(t0=0.0)
    clock = _Clock()
    if contestant == "public":

        def call() -> Any:
            return fusion.update_odometry(clock(), 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)

        call()
        assert benchmark(call).accepted
        return
    # planar_step takes the absolute time: the same clock as the public
    # call, so every step predicts 10 ms ahead as the public one does.
    buf = fusion._buf
    # The bare call does the public call's work: the same filter after 3 steps.
    public = PlanarFusion(t0=0.0)
    for t in (0.01, 0.02, 0.03):
        public.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
        assert planar_step(buf, t, 1, 2, 1.0, 0.1, 1e-4, 1e-4, math.inf)[0] == 0
    np.testing.assert_array_equal(buf, public._buf)
    clock.t = 0.03
    entry = planar_step_entry()
    residual = fusion._odometry_residual
    if contestant == "paired":
        # Four filters stepped alike from t0 = 0: after every round their states
        # are the kernel's (check), so a public call that skipped or cached the
        # step under the timer fails.
        paired = PlanarFusion(t0=0.0)
        update = paired.update_odometry
        kernel_buf = PlanarFusion(t0=0.0)._buf
        entry_buf = PlanarFusion(t0=0.0)._buf
        floor_fusion = PlanarFusion(t0=0.0)
        floor_buf, floor_residual = floor_fusion._buf, floor_fusion._odometry_residual
        inf = math.inf
        # Each loop's clock, carried over from round to round.
        clocks = {"public": 0.0, "kernel": 0.0, "entry": 0.0, "floor": 0.0}

        def public_loop(todo: Sequence[Any]) -> np.ndarray:
            t = clocks["public"]
            for _ in todo:
                t += 0.01
                update(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
            clocks["public"] = t
            return paired._buf

        def kernel_loop(todo: Sequence[Any]) -> np.ndarray:
            t = clocks["kernel"]
            for _ in todo:
                t += 0.01
                planar_step(kernel_buf, t, 1, 2, 1.0, 0.1, 1e-4, 1e-4, inf)
            clocks["kernel"] = t
            return kernel_buf

        def entry_loop(todo: Sequence[Any]) -> np.ndarray:
            t = clocks["entry"]
            for _ in todo:
                t += 0.01
                entry(entry_buf, t, 1, 2, 1.0, 0.1, 1e-4, 1e-4, inf)
            clocks["entry"] = t
            return entry_buf

        def floor_loop(todo: Sequence[Any]) -> np.ndarray:
            t = clocks["floor"]
            for _ in todo:
                t += 0.01
                new_result(True, entry(floor_buf, t, 1, 2, 1.0, 0.1, 1e-4, 1e-4, inf)[1],
                           floor_residual.copy(), None)  # fmt: skip
            clocks["floor"] = t
            return floor_buf

        def check(states: dict[str, object], last: object) -> None:
            assert len(set(clocks.values())) == 1, clocks
            for name, state in states.items():
                assert isinstance(state, np.ndarray)
                assert state.tobytes() == kernel_buf.tobytes(), name

        loops = {"public": public_loop, "kernel": kernel_loop, "entry": entry_loop,
                 "floor": floor_loop}  # fmt: skip
        ratios = benchmark.pedantic(_paired, (loops, 4000, check), rounds=1, iterations=1)
        benchmark.extra_info.update(ratios)
        # Every loop stepped its filter to its clock (a refused step leaves the time).
        assert paired.t == clocks["public"]
        for name, stepped in (("kernel", kernel_buf), ("entry", entry_buf), ("floor", floor_buf)):
            assert stepped[BUF_TIME] == clocks[name]
        return
    step = planar_step if contestant == "kernel" else entry
    if contestant == "floor":

        def floor() -> UpdateResult:
            nis = step(buf, clock(), 1, 2, 1.0, 0.1, 1e-4, 1e-4, math.inf)[1]
            return new_result(True, nis, residual.copy(), None)

        want = public.update_odometry(0.04, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
        got = floor()
        assert type(got) is UpdateResult and got.accepted and got.nis == want.nis
        assert got.residual.tobytes() == want.residual.tobytes()
        benchmark(floor)
        return

    def kernel() -> Any:
        return step(buf, clock(), 1, 2, 1.0, 0.1, 1e-4, 1e-4, math.inf)

    kernel()
    benchmark(kernel)


@pytest.mark.benchmark(group="world_to_cell 10 points", warmup=True, warmup_iterations=2000)
@pytest.mark.parametrize(
    "contestant", ["public", "kernel", "floor", "noop_wrapper", "entry", "paired"]
)
def test_world_to_cell_10(benchmark: Any, contestant: str) -> None:
    """``kernel``: ``world_to_cell_kernel`` through numba's dispatcher into a
    preallocated array (the issue's row).

    ``floor``: a bare function allocating the result and calling the kernel.
    ``noop_wrapper`` only calls the kernel (into the preallocated array) from a
    Python function; ``entry`` is the compiled kernel without numba's type
    dispatch (the general path's; the fast path runs its code in an entry of its
    own that also checks and allocates). ``paired``: the public call
    against ``kernel``, ``floor``, ``entry`` and ``np.empty`` of the result
    alone (``empty``) in one timing loop (the issue's number; module docstring).
    """
    grid = OccupancyGrid.empty(
        width=50.0, height=40.0, resolution=0.05, origin=Pose2D(-20.0, -15.0, 0.4)
    )
    pts = np.random.default_rng(0).uniform(-30, 30, size=(10, 2))
    out = np.empty((10, 2), dtype=np.int64)
    o = grid.origin
    x, y, yaw, res = o.x, o.y, o.theta, grid.resolution
    world_to_cell_kernel(pts, x, y, yaw, res, out)
    # Warm: the first public call fetches the compiled entry (milliseconds), which
    # would make pytest-benchmark time one call per round.
    assert np.array_equal(grid.world_to_cell(pts), out)
    entry = world_to_cell_entry()
    if contestant == "public":
        assert np.array_equal(benchmark(grid.world_to_cell, pts), out)
    elif contestant == "kernel":
        benchmark(world_to_cell_kernel, pts, x, y, yaw, res, out)
    elif contestant == "floor":

        def floor(points: np.ndarray) -> np.ndarray:
            cells = np.empty((points.shape[0], 2), dtype=np.int64)
            world_to_cell_kernel(points, x, y, yaw, res, cells)
            return cells

        assert np.array_equal(benchmark(floor, pts), out)
    elif contestant == "noop_wrapper":

        def noop_wrapper(points: np.ndarray) -> bool:
            return world_to_cell_kernel(points, x, y, yaw, res, out)

        benchmark(noop_wrapper, pts)
    elif contestant == "entry":
        benchmark(entry, pts, x, y, yaw, res, out)
    else:
        cells = grid.world_to_cell
        empty, int64, shape = np.empty, np.dtype(np.int64), pts.shape
        kernel_out, entry_out = np.empty_like(out), np.empty_like(out)

        def inputs(round_: int) -> list[np.ndarray]:
            # New points for every call of the round (0.6 MB: both sides read
            # them from the L2 cache): a cache on the points cannot help.
            rng = np.random.default_rng(round_ + 1)
            return list(rng.uniform(-30.0, 30.0, size=(4000, *shape)))

        def public_loop(todo: Sequence[np.ndarray]) -> object:
            got = None
            for p in todo:
                got = cells(p)
            return got

        def kernel_loop(todo: Sequence[np.ndarray]) -> object:
            for p in todo:
                world_to_cell_kernel(p, x, y, yaw, res, kernel_out)
            return kernel_out

        def floor_loop(todo: Sequence[np.ndarray]) -> object:
            got = None
            for p in todo:
                got = empty(shape, int64)
                world_to_cell_kernel(p, x, y, yaw, res, got)
            return got

        def entry_loop(todo: Sequence[np.ndarray]) -> object:
            for p in todo:
                entry(p, x, y, yaw, res, entry_out)
            return entry_out

        def empty_loop(todo: Sequence[np.ndarray]) -> object:
            for _ in todo:
                empty(shape, int64)
            return None

        def check(answers: dict[str, object], last: np.ndarray) -> None:
            want = np.empty_like(out)
            world_to_cell_kernel(last, x, y, yaw, res, want)
            for name, got in answers.items():
                if name != "empty":
                    assert isinstance(got, np.ndarray) and np.array_equal(got, want), name

        loops = {"public": public_loop, "kernel": kernel_loop, "floor": floor_loop,
                 "entry": entry_loop, "empty": empty_loop}  # fmt: skip
        ratios = benchmark.pedantic(_paired, (loops, 4000, check, inputs), rounds=1, iterations=1)
        benchmark.extra_info.update(ratios)


def _scan() -> LaserScan:
    n = 360
    th = -math.pi + 2.0 * math.pi * np.arange(n) / n
    ranges = 0.6 + 0.4 * np.abs(np.sin(3 * th))
    return LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2.0 * math.pi / n, range_min=0.12, range_max=3.5
    )


@pytest.mark.benchmark(group="repulsion 360 beams", warmup=True, warmup_iterations=2000)
@pytest.mark.parametrize(
    "contestant",
    ["public", "public_call", "kernel", "kernel_into", "floor", "noop_wrapper", "entry",
     "paired"],
)  # fmt: skip
def test_repulsion_360(benchmark: Any, contestant: str) -> None:
    """``kernel``: the tuple-returning sum; ``kernel_into`` the one the public call ends in.

    ``public`` goes through pytest-benchmark's ``fn(*args, **kwargs)``, which
    costs about 85 ns more than a call written with keywords; ``public_call``
    is such a call in a closure (which adds about 15 ns).

    ``floor`` allocates the result and calls ``kernel_into`` from a bare Python
    function; ``noop_wrapper`` only calls ``kernel``; ``entry`` is
    ``kernel_into`` without numba's type dispatch. ``paired``: the public call
    against ``kernel_into`` (the issue's number), ``kernel``, ``floor`` and
    ``entry`` in one timing loop (module docstring).
    """
    scan = _scan()
    cos_t, sin_t = _beam_table(scan)
    directions = _beam_directions(scan)
    rest = (scan.range_min, scan.range_max, 0.5, 1.0, MIN_DISTANCE)
    args = (scan.ranges, cos_t, sin_t, *rest)
    args_into = (scan.ranges, directions, *rest)
    want = np.array(khatib_beam_force(*args))
    out = np.empty(2)
    got = repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.0)
    assert got.tobytes() == want.tobytes()
    if contestant == "public":
        benchmark(repulsive_force_from_scan, scan, k_rep=0.5, influence_radius=1.0)
    elif contestant == "public_call":
        benchmark(lambda: repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.0))
    elif contestant == "kernel":
        benchmark(khatib_beam_force, *args)
    elif contestant == "kernel_into":
        khatib_beam_force_into(*args_into, out)
        benchmark(khatib_beam_force_into, *args_into, out)
    elif contestant == "floor":

        def floor() -> np.ndarray:
            force = np.empty(2)
            khatib_beam_force_into(*args_into, force)
            return force

        assert floor().tobytes() == want.tobytes()
        benchmark(floor)
    elif contestant == "noop_wrapper":

        def noop_wrapper() -> tuple[float, float]:
            return khatib_beam_force(*args)

        benchmark(noop_wrapper)
    elif contestant == "entry":
        entry = khatib_entry()
        entry(*args_into, out)
        benchmark(entry, *args_into, out)
    else:
        entry = khatib_entry()
        rmin, rmax = scan.range_min, scan.range_max
        empty = np.empty
        into_out, entry_out = np.empty(2), np.empty(2)

        def inputs(round_: int) -> list[tuple[LaserScan, np.ndarray]]:
            # Eight new range sets a round (the same beams), each call on a scan
            # object of its own (a shallow copy sharing them): a force cached on
            # a scan, or kept from an earlier round, is no faster or is wrong
            # (check). New ranges for every call would be 11 MB a round, read
            # from memory rather than cache by both sides.
            rng = np.random.default_rng(round_ + 1)
            scans = [
                LaserScan(
                    scan.ranges * rng.uniform(0.8, 1.2, scan.ranges.shape),
                    angle_min=scan.angle_min,
                    angle_increment=scan.angle_increment,
                    range_min=rmin,
                    range_max=rmax,
                )
                for _ in range(8)
            ]
            return [(copy.copy(scans[k % 8]), scans[k % 8].ranges) for k in range(4000)]

        def public_loop(todo: Sequence[tuple[LaserScan, np.ndarray]]) -> object:
            got = None
            for s, _ in todo:
                got = repulsive_force_from_scan(s, k_rep=0.5, influence_radius=1.0)
            return got

        def kernel_into_loop(todo: Sequence[tuple[LaserScan, np.ndarray]]) -> object:
            for _, r in todo:
                khatib_beam_force_into(r, directions, rmin, rmax, 0.5, 1.0, MIN_DISTANCE, into_out)
            return into_out

        def kernel_loop(todo: Sequence[tuple[LaserScan, np.ndarray]]) -> object:
            got = None
            for _, r in todo:
                got = khatib_beam_force(r, cos_t, sin_t, rmin, rmax, 0.5, 1.0, MIN_DISTANCE)
            return np.array(got)

        def floor_loop(todo: Sequence[tuple[LaserScan, np.ndarray]]) -> object:
            got = None
            for _, r in todo:
                got = empty(2)
                khatib_beam_force_into(r, directions, rmin, rmax, 0.5, 1.0, MIN_DISTANCE, got)
            return got

        def entry_loop(todo: Sequence[tuple[LaserScan, np.ndarray]]) -> object:
            for _, r in todo:
                entry(r, directions, rmin, rmax, 0.5, 1.0, MIN_DISTANCE, entry_out)
            return entry_out

        def check(answers: dict[str, object], last: tuple[LaserScan, np.ndarray]) -> None:
            want = np.array(khatib_beam_force(last[1], cos_t, sin_t, *rest)).tobytes()
            for name, got in answers.items():
                assert isinstance(got, np.ndarray) and got.tobytes() == want, name

        loops = {"public": public_loop, "kernel_into": kernel_into_loop, "kernel": kernel_loop,
                 "floor": floor_loop, "entry": entry_loop}  # fmt: skip
        ratios = benchmark.pedantic(_paired, (loops, 4000, check, inputs), rounds=1, iterations=1)
        benchmark.extra_info.update(ratios)


def _bare_diff_step(pose: tuple[float, float, float], dl: int, dr: int) -> tuple[float, ...]:
    """The first-order step with no checks: the floor for a Python-level reading."""
    d_left = 2.0 * math.pi * 0.1 / 1000.0 * dl
    d_right = 2.0 * math.pi * 0.1 / 1000.0 * dr
    dc = 0.5 * d_right + 0.5 * d_left
    dth = (d_right - d_left) / 0.5
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return pose[0] + c * dc, pose[1] + s * dc, pose[2] + dth


@pytest.mark.benchmark(group="DiffOdometry.update")
@pytest.mark.parametrize("contestant", ["public", "batch_of_one", "bare_python"])
def test_diff_odometry_update(benchmark: Any, contestant: str) -> None:
    odo = DiffOdometry(
        DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=16, method="first_order"
    )
    ticks = [0]

    def reading() -> tuple[int, int]:
        ticks[0] += 3
        return ticks[0] % 65536, (2 * ticks[0]) % 65536

    if contestant == "public":
        benchmark(lambda: odo.update(*reading()))
    elif contestant == "batch_of_one":
        # The pre-issue-17 implementation of update(): a one-row update_batch.
        benchmark(lambda: odo.update_batch(*([v] for v in reading())))
    else:
        benchmark(lambda: _bare_diff_step((0.0, 0.0, 0.0), *reading()))


@pytest.mark.benchmark(group="quaternion_to_yaw one", warmup=True, warmup_iterations=2000)
@pytest.mark.parametrize("contestant", ["public", "public_array", "general", "bare_math"])
def test_quaternion_to_yaw_one(benchmark: Any, contestant: str) -> None:
    """One ``(x, y, z, w)`` of a ROS message: the plain-float fast path (a list;
    ``public_array`` a float64 (4,) array) against the general, validating array
    way it skips (``general``: the same values byte-swapped, which takes that
    way) and the bare formula with ``math`` and no checks (``bare_math``)."""
    q = [0.01, -0.02, math.sin(0.25), math.cos(0.25)]
    want = quaternion_to_yaw(np.array(q, dtype=">f8"))
    if contestant == "public":
        assert benchmark(quaternion_to_yaw, q) == want
    elif contestant == "public_array":
        assert benchmark(quaternion_to_yaw, np.array(q)) == want
    elif contestant == "general":
        assert benchmark(quaternion_to_yaw, np.array(q, dtype=">f8")) == want
    else:
        x, y, z, w = q

        def bare_math() -> float:
            return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))

        benchmark(bare_math)
