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

Run with ``python -m pytest benchmarks/test_bench_fields.py --benchmark-only``.
"""

from __future__ import annotations

import math

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
from test_bench_astar import shared_data

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


@pytest.fixture(params=[360, 3600], ids=lambda n: f"{n}beams")
def scan(request: pytest.FixtureRequest) -> LaserScan:
    s = make_scan(request.param)
    want = KhatibRepulsion(s.to_points(), k_rep=K_REP, influence_radius=D0).force([0.0, 0.0])[0]
    got = repulsive_force_from_scan(s, k_rep=K_REP, influence_radius=D0)
    np.testing.assert_allclose(got, want, rtol=1e-12)
    np.testing.assert_allclose(numpy_repulsion(s, K_REP, D0), want, rtol=1e-9)
    return s


def test_empty_numba_call(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    cos_t, sin_t = _beam_table(scan)
    args = (scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, K_REP, D0, MIN_DISTANCE)
    empty_kernel(*args)
    benchmark(empty_kernel, *args)


def test_kernel(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    cos_t, sin_t = _beam_table(scan)
    args = (scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, K_REP, D0, MIN_DISTANCE)
    khatib_beam_force(*args)
    benchmark(khatib_beam_force, *args)


def test_public_call(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    benchmark(repulsive_force_from_scan, scan, k_rep=K_REP, influence_radius=D0)


def test_public_call_mounted(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    # A LiDAR 0.2 m ahead of the robot's centre (review 46): the point-field path,
    # peer of test_point_field_on_scan_points and test_public_call.
    mount = Pose2D(0.2, 0.0, 0.0)
    benchmark(repulsive_force_from_scan, scan, k_rep=K_REP, influence_radius=D0, mount=mount)


def test_numpy_vectorised(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    benchmark(numpy_repulsion, scan, K_REP, D0)


def test_numpy_vectorised_with_tables(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    cos_t, sin_t = _beam_table(scan)
    benchmark(numpy_repulsion_tables, scan, cos_t, sin_t, K_REP, D0)


def test_point_field_on_scan_points(benchmark, scan: LaserScan) -> None:  # type: ignore[no-untyped-def]
    # The generic field path: convert the scan to points, then evaluate KhatibRepulsion.
    def via_points() -> np.ndarray:
        points = scan.to_points()
        return KhatibRepulsion(points, k_rep=K_REP, influence_radius=D0).force((0.0, 0.0))[0]

    benchmark(via_points)


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


@pytest.fixture(scope="module")
def hokuyo_scans() -> list[LaserScan]:
    """The first 50 scans of the shared Hokuyo bag (681 beams each)."""
    rows = np.loadtxt(shared_data(HOKUYO_CSV), delimiter=",", skiprows=1, max_rows=50)
    return [
        LaserScan(
            row[3:], angle_min=-2.0862, angle_increment=0.0061359, range_min=0.02, range_max=5.6
        )
        for row in rows
    ]


def test_public_call_real_hokuyo(benchmark, hokuyo_scans: list[LaserScan]) -> None:  # type: ignore[no-untyped-def]
    benchmark(
        lambda: [
            repulsive_force_from_scan(s, k_rep=K_REP, influence_radius=D0) for s in hokuyo_scans
        ]
    )


def test_numpy_real_hokuyo(benchmark, hokuyo_scans: list[LaserScan]) -> None:  # type: ignore[no-untyped-def]
    benchmark(lambda: [numpy_repulsion(s, K_REP, D0) for s in hokuyo_scans])
