"""Per-beam repulsion from a LaserScan (issue 7).

Compares, for a 360-beam and a 3,600-beam scan:

* the numba kernel against an empty numba function taking the same arguments
  (the floor of a numba call), target: within 2x;
* the public ``repulsive_force_from_scan`` (validation included) against a
  NumPy-vectorised version, target: at least 3x faster;

and, for reference, the same on real 681-beam Hokuyo scans (when the shared data
is found, as navkit's ``find_data`` finds it: ``$NAVKIT_DATA``, then ``shared/data``
nearby), ``sample_field`` on 300 x 300 and 1200 x 1200 maps, one ``greedy_step`` on the
TurtleBot3 paper's 21 x 21 grid and one ``PotentialFieldController.step``.

Every round of the repulsion groups is ``PER_ROUND`` calls, each on a scan no
earlier call had (from a pool built before the timing: the same scanner, other
noise and dropouts), every force checked against the point field's outside the
timer (:func:`timed_on_scans`); the Hokuyo groups take the bag's next 10 scans a
round. A force kept for a scan already seen cannot stand in for the work.

Run with ``python -m pytest benchmarks/test_bench_fields.py --benchmark-only``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterator
from functools import cache
from typing import Any, NamedTuple

import numpy as np
import pytest
from numba import njit

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan
from navkit.planning import (
    BlendedAttraction,
    KhatibRepulsion,
    greedy_step,
    repulsive_force_from_scan,
    sample_field,
)
from navkit.planning.reactive._limits import MIN_DISTANCE
from navkit.planning.reactive._scan_repulsion import _beam_table
from navkit.planning.reactive._scan_repulsion_kernels import khatib_beam_force
from test_bench_astar import shared_data, timed_fresh

K_REP = 0.5
D0 = 1.0
HOKUYO_CSV = "rosbag-hokuyo-laserscan-demo/demo_scans.csv"


@njit(cache=False)
def empty_kernel(
    ranges: np.ndarray,
    cos_t: np.ndarray,
    sin_t: np.ndarray,
    range_min: float,
    range_max: float,
    k_rep: float,
    influence_radius: float,
    min_distance: float,
) -> tuple[float, float]:
    return 0.0, 0.0


def make_scan(n: int, seed: int = 0) -> LaserScan:
    """A 360° scan from (1.2, 0.7) in a 6 x 4 m room with a round pillar.

    Ranges follow the walls (1 cm noise, 2 % NaN dropouts) the way a real scan
    does: neighbouring beams are alike, about a third lie within d0 = 1 m.
    """
    rng = np.random.default_rng(seed)
    x, y, width, height = 1.2, 0.7, 6.0, 4.0
    th = -math.pi + 2.0 * math.pi * np.arange(n) / n
    c, s = np.cos(th), np.sin(th)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, (width - x) / c, np.where(c < 0, -x / c, np.inf))
        ty = np.where(s > 0, (height - y) / s, np.where(s < 0, -y / s, np.inf))
    r = np.minimum(tx, ty)
    px, py, pr = 2.2 - x, 1.0 - y, 0.25
    b = c * px + s * py
    disc = b * b - (px * px + py * py - pr * pr)
    hit = (disc >= 0.0) & (b > 0.0)
    t = b - np.sqrt(np.where(hit, disc, 0.0))
    r = np.where(hit & (t > 0.0) & (t < r), t, r) + rng.normal(0.0, 0.01, n)
    r[rng.random(n) < 0.02] = math.nan
    return LaserScan(
        r, angle_min=-math.pi, angle_increment=2.0 * math.pi / n, range_min=0.12, range_max=3.5
    )


def numpy_repulsion(scan: LaserScan, k_rep: float, d0: float) -> np.ndarray:
    """The same sum written with NumPy array operations."""
    r = scan.ranges
    with np.errstate(invalid="ignore"):
        use = (r >= scan.range_min) & (r < scan.range_max) & (r <= d0)
    rr = r[use]
    th = scan.angle_min + scan.angle_increment * np.flatnonzero(use)
    w = k_rep * (1.0 / rr - 1.0 / d0) / (rr * rr)
    return -np.array((np.dot(w, np.cos(th)), np.dot(w, np.sin(th))))


def numpy_repulsion_tables(
    scan: LaserScan, cos_t: np.ndarray, sin_t: np.ndarray, k_rep: float, d0: float
) -> np.ndarray:
    """NumPy with precomputed beam direction tables (a stronger baseline)."""
    r = scan.ranges
    with np.errstate(invalid="ignore", divide="ignore"):
        use = (r >= scan.range_min) & (r < scan.range_max) & (r <= d0)
        w = np.where(use, k_rep * (1.0 / r - 1.0 / d0) / (r * r), 0.0)
    return -np.array((np.dot(w, cos_t), np.dot(w, sin_t)))


# Rounds of each repulsion group, each of PER_ROUND calls on scans of their own (the
# pool's): one call a round would put timed_fresh's bookkeeping and the timer's own
# cost (about 1 µs together) into every 0.5-3 µs call, PER_ROUND share it.
ROUNDS = 100
PER_ROUND = 16
MOUNT = Pose2D(0.2, 0.0, 0.0)  # a LiDAR 0.2 m ahead of the robot's centre (review 46)


class Round(NamedTuple):
    """One scan and its forces by the generic point field (the reference)."""

    scan: LaserScan
    force: np.ndarray  # (2,), the LiDAR at the robot's centre
    mounted: np.ndarray  # (2,), the LiDAR at MOUNT


def make_round(n: int, seed: int) -> Round:
    scan = make_scan(n, seed)
    points = scan.to_points()
    forces = [
        KhatibRepulsion(p, k_rep=K_REP, influence_radius=D0).force((0.0, 0.0))[0]
        for p in (points, points + np.array([MOUNT.x, MOUNT.y]))
    ]
    return Round(scan, *forces)


@cache
def scan_pool(n: int) -> tuple[Round, ...]:
    """``(ROUNDS + 1) * PER_ROUND`` scans of ``n`` beams (seeds 1, 2, ...: other noise
    and dropouts), built once, before any timing, with their reference forces."""
    return tuple(make_round(n, seed) for seed in range(1, (ROUNDS + 1) * PER_ROUND + 1))


def scan_supply(n: int) -> Iterator[tuple[Round, ...]]:
    """The pool's scans, ``PER_ROUND`` at a time, then new ones (``compare_peers.py``
    may call more often than a pytest group; it builds those in the untimed setup).
    Never a scan twice."""
    pool = scan_pool(n)
    for k in range(0, len(pool), PER_ROUND):
        yield pool[k : k + PER_ROUND]
    for first in itertools.count(len(pool) + 1, PER_ROUND):
        yield tuple(make_round(n, seed) for seed in range(first, first + PER_ROUND))


def timed_on_scans(
    benchmark: Any, n: int, run: Callable[[LaserScan], Any], want: Callable[[Round], Any]
) -> list[Any]:
    """:func:`timed_fresh` of ``run`` on ``PER_ROUND`` scans a round, each a scan no
    earlier call had, every answer checked against ``want(round)`` (1e-9 relative)
    outside the timer, so a force kept for an earlier scan cannot stand in for the
    work and one wrong under the timer fails. Every test of a group is timed this
    way (the same bookkeeping), floors included. Times are per round
    (``PER_ROUND`` calls; ``calls_per_round`` in ``extra_info``)."""
    supply = scan_supply(n)
    given: dict[int, tuple[Round, ...]] = {}

    def fresh() -> tuple[list[LaserScan]]:
        batch = next(supply)
        scans = [one.scan for one in batch]
        for scan in scans:
            # Read once here, untimed: a scan arrives in the cache its driver wrote it
            # through, not from a pool of tens of MB in main memory.
            scan.ranges.sum()
        given[id(scans)] = batch
        return (scans,)

    def check(args: tuple[Any, ...], answers: list[Any]) -> None:
        for answer, one in zip(answers, given.pop(id(args[0])), strict=True):
            np.testing.assert_allclose(
                np.asarray(answer, dtype=float), want(one), rtol=1e-9, atol=0
            )

    benchmark.extra_info["calls_per_round"] = PER_ROUND
    answers: list[Any] = timed_fresh(
        benchmark, lambda scans: [run(s) for s in scans], fresh, check, ROUNDS
    )
    return answers


def the_force(one: Round) -> np.ndarray:
    return one.force


def no_force(_one: Round) -> np.ndarray:
    return np.zeros(2)


@pytest.fixture(scope="module", autouse=True)
def _pools_agree() -> None:
    """Before timing: on a scan of each size the public call and NumPy give the point
    field's force (1e-12, NumPy 1e-9), as do the pools' first scans."""
    for n in (360, 3600):
        for one in (make_round(n, 0), scan_pool(n)[0]):
            got = repulsive_force_from_scan(one.scan, k_rep=K_REP, influence_radius=D0)
            np.testing.assert_allclose(got, one.force, rtol=1e-12)
            mounted = repulsive_force_from_scan(
                one.scan, k_rep=K_REP, influence_radius=D0, mount=MOUNT
            )
            np.testing.assert_allclose(mounted, one.mounted, rtol=1e-12)
            np.testing.assert_allclose(numpy_repulsion(one.scan, K_REP, D0), one.force, rtol=1e-9)


BEAMS = pytest.mark.parametrize("n", [360, 3600], ids=lambda n: f"{n}beams")


def kernel_args(scan: LaserScan) -> tuple[Any, ...]:
    cos_t, sin_t = _beam_table(scan)
    return (scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, K_REP, D0, MIN_DISTANCE)


@BEAMS
def test_empty_numba_call(benchmark: Any, n: int) -> None:
    # The tables of the pool's geometry (one scanner: the same for every round).
    _, cos_t, sin_t, *rest = kernel_args(scan_pool(n)[0].scan)
    empty_kernel(*kernel_args(scan_pool(n)[0].scan))
    timed_on_scans(
        benchmark, n, lambda scan: empty_kernel(scan.ranges, cos_t, sin_t, *rest), no_force
    )


@BEAMS
def test_kernel(benchmark: Any, n: int) -> None:
    _, cos_t, sin_t, *rest = kernel_args(scan_pool(n)[0].scan)
    timed_on_scans(
        benchmark, n, lambda scan: khatib_beam_force(scan.ranges, cos_t, sin_t, *rest), the_force
    )


@BEAMS
def test_public_call(benchmark: Any, n: int) -> None:
    timed_on_scans(
        benchmark,
        n,
        lambda scan: repulsive_force_from_scan(scan, k_rep=K_REP, influence_radius=D0),
        the_force,
    )


@BEAMS
def test_public_call_mounted(benchmark: Any, n: int) -> None:
    # The point-field path, peer of test_point_field_on_scan_points and test_public_call.
    timed_on_scans(
        benchmark,
        n,
        lambda scan: repulsive_force_from_scan(scan, k_rep=K_REP, influence_radius=D0, mount=MOUNT),
        lambda one: one.mounted,
    )


@BEAMS
def test_numpy_vectorised(benchmark: Any, n: int) -> None:
    timed_on_scans(benchmark, n, lambda scan: numpy_repulsion(scan, K_REP, D0), the_force)


@BEAMS
def test_numpy_vectorised_with_tables(benchmark: Any, n: int) -> None:
    cos_t, sin_t = _beam_table(scan_pool(n)[0].scan)
    timed_on_scans(
        benchmark,
        n,
        lambda scan: numpy_repulsion_tables(scan, cos_t, sin_t, K_REP, D0),
        the_force,
    )


@BEAMS
def test_point_field_on_scan_points(benchmark: Any, n: int) -> None:
    # The generic field path: convert the scan to points, then evaluate KhatibRepulsion.
    def via_points(scan: LaserScan) -> np.ndarray:
        points = scan.to_points()
        return KhatibRepulsion(points, k_rep=K_REP, influence_radius=D0).force((0.0, 0.0))[0]

    timed_on_scans(benchmark, n, via_points, the_force)


def test_sample_field_300x300(benchmark) -> None:  # type: ignore[no-untyped-def]
    obstacles = np.random.default_rng(1).uniform(0.0, 12.0, (50, 2))
    field = BlendedAttraction((10.0, 10.0), threshold_radius=2.0, width=0.5) + KhatibRepulsion(
        obstacles, k_rep=0.2, influence_radius=0.8
    )
    benchmark(sample_field, field, xlim=(0.0, 12.0), ylim=(0.0, 12.0), resolution=0.04)


def test_sample_field_1200x1200(benchmark) -> None:  # type: ignore[no-untyped-def]
    # The paper's map size, with a scan's worth of obstacle points.
    obstacles = np.random.default_rng(2).uniform(0.0, 12.0, (360, 2))
    field = BlendedAttraction((10.0, 10.0), threshold_radius=2.0, width=0.5) + KhatibRepulsion(
        obstacles, k_rep=0.2, influence_radius=0.8
    )
    benchmark.pedantic(
        sample_field,
        (field,),
        {"xlim": (0.0, 12.0), "ylim": (0.0, 12.0), "resolution": 0.01},
        rounds=3,
    )


def test_greedy_step_21x21(benchmark) -> None:  # type: ignore[no-untyped-def]
    # The TurtleBot3 planner on the paper's grid built from a room scan.
    grid = make_scan(360).to_local_grid()
    benchmark(greedy_step, grid, (3.0, 0.5))


def test_controller_step_with_scan(benchmark) -> None:  # type: ignore[no-untyped-def]
    ctl = PotentialFieldController()
    s = make_scan(360)
    benchmark(ctl.step, Pose2D(1.2, 0.7, 0.3), Pose2D(5.0, 3.0, 0.0), dt=0.05, obstacles=s)


HOKUYO_PER_ROUND = 10  # scans a round: the bag's 360 make 36 rounds, none repeated


@pytest.fixture(scope="module")
def hokuyo_rounds() -> list[list[tuple[LaserScan, np.ndarray]]]:
    """The shared Hokuyo bag's scans (681 beams each), ``HOKUYO_PER_ROUND`` a round,
    each with its force by the generic point field."""
    rows = np.loadtxt(shared_data(HOKUYO_CSV), delimiter=",", skiprows=1)
    scans = [
        LaserScan(
            row[3:], angle_min=-2.0862, angle_increment=0.0061359, range_min=0.02, range_max=5.6
        )
        for row in rows
    ]
    pairs = [
        (s, KhatibRepulsion(s.to_points(), k_rep=K_REP, influence_radius=D0).force((0, 0))[0])
        for s in scans
    ]
    k = HOKUYO_PER_ROUND
    return [pairs[i : i + k] for i in range(0, len(pairs) - k + 1, k)]


def timed_on_hokuyo(
    benchmark: Any,
    rounds: list[list[tuple[LaserScan, np.ndarray]]],
    force: Callable[[LaserScan], np.ndarray],
) -> None:
    """Each round (one call: ``force`` of each of its scans) on scans no earlier round
    had, every force checked against the point field's (1e-9) outside the timer."""
    supply = iter(rounds)
    wants: dict[int, list[np.ndarray]] = {}

    def fresh() -> tuple[list[LaserScan]]:
        batch = next(supply)
        scans = [s for s, _ in batch]
        for scan in scans:
            scan.ranges.sum()  # in the cache, as a scan just received (timed_on_scans)
        wants[id(scans)] = [w for _, w in batch]
        return (scans,)

    def check(args: tuple[Any, ...], answer: list[np.ndarray]) -> None:
        np.testing.assert_allclose(answer, wants.pop(id(args[0])), rtol=1e-9, atol=0)

    timed_fresh(benchmark, lambda scans: [force(s) for s in scans], fresh, check, len(rounds) - 1)


def test_public_call_real_hokuyo(benchmark, hokuyo_rounds) -> None:  # type: ignore[no-untyped-def]
    timed_on_hokuyo(
        benchmark,
        hokuyo_rounds,
        lambda s: repulsive_force_from_scan(s, k_rep=K_REP, influence_radius=D0),
    )


def test_numpy_real_hokuyo(benchmark, hokuyo_rounds) -> None:  # type: ignore[no-untyped-def]
    timed_on_hokuyo(benchmark, hokuyo_rounds, lambda s: numpy_repulsion(s, K_REP, D0))
