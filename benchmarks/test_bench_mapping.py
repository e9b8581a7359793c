"""Laser-to-grid ray casting and world-to-cell conversion (issue 4).

Run with ``python -m pytest benchmarks/test_bench_mapping.py --benchmark-only``.

Scene: one 360-beam scan (1° apart) with a 12 m maximum range, taken at (4, 3) m
with heading 0.3 rad in a 16 x 10 m rectangular room whose far corner is out of
range (those beams clear free space up to 12 m and mark nothing), integrated into
a 30 x 30 m grid of 0.05 m cells (600 x 600) with OctoMap's log-odds model.

Contestants for one scan:

* ``navkit``: ``navkit.mapping.integrate_scan`` through the public API (input
  validation included), Bresenham lines (the default) and ``exact=True``
  (Amanatides–Woo traversal); each cell is updated once per scan.
  ``navkit_method`` is the same call through the convenience method
  ``OccupancyGrid.integrate_scan`` (one more Python call, about 1-2 µs).
* ``numba_bresenham``: the hand-written baseline below, a single numba loop over
  beams doing ``+=`` along Bresenham lines with clamping (no deduplication, grid
  frame angles precomputed outside the timer).
* ``skimage_loop``: a Python loop over beams calling ``skimage.draw.line`` and
  updating the line's cells with NumPy fancy indexing.

``world_to_cell`` on 10^6 points (integer cells, and ``continuous=True``) is
compared with the same rule in NumPy, every round on new points, its cells checked.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from numba import njit

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from test_bench_astar import peer, timed_fresh

# scikit-image is a peer (``test`` extra): without it only its contestant skips
# (peer()), and test_bench_raycast, which imports this file, still runs.
try:
    from skimage.draw import line
except ImportError:
    line = None  # type: ignore[assignment]

RES = 0.05
ROOM = (0.0, 0.0, 16.0, 10.0)
POSE = Pose2D(4.0, 3.0, 0.3)
RANGE_MAX = 12.0
HIT = math.log(0.7 / 0.3)
MISS = math.log(0.4 / 0.6)
CLAMP = (math.log(0.12 / 0.88), math.log(0.97 / 0.03))
# Off the round numbers so that no wall lies on a cell boundary (either cell
# would be right there, and the contestants could round differently).
ORIGIN = Pose2D(-7.013, -10.027, 0.0)
# Rounds of the timed_fresh groups: one call each (0.1-5 ms integrate_scan, ~10 ms
# world_to_cell on 10^6 points), each on new arguments.
ROUNDS = 100


def room_scan() -> LaserScan:
    """Exact ranges to the room walls; beyond RANGE_MAX they read +inf (no return)."""
    xmin, ymin, xmax, ymax = ROOM
    angles = -math.pi + 2 * math.pi * np.arange(360) / 360
    phi = angles + POSE.theta
    c, s = np.cos(phi), np.sin(phi)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, (xmax - POSE.x) / c, (xmin - POSE.x) / c)
        ty = np.where(s > 0, (ymax - POSE.y) / s, (ymin - POSE.y) / s)
    ranges = np.minimum(np.abs(tx), np.abs(ty))
    ranges[ranges >= RANGE_MAX] = np.inf
    return LaserScan(
        ranges,
        angle_min=-math.pi,
        angle_increment=2 * math.pi / 360,
        range_min=0.05,
        range_max=RANGE_MAX,
    )


def new_grid() -> OccupancyGrid:
    return OccupancyGrid.empty(width=30.0, height=30.0, resolution=RES, origin=ORIGIN)


def beam_cells(scan: LaserScan) -> tuple[int, int, np.ndarray, np.ndarray, np.ndarray]:
    """Sensor cell, end cells and hit flags in the grid frame (shared by the peers)."""
    su = (POSE.x - ORIGIN.x) / RES
    sv = (POSE.y - ORIGIN.y) / RES
    valid = scan.ranges >= scan.range_min
    is_hit = scan.ranges < scan.range_max
    d = np.where(is_hit, scan.ranges, scan.range_max)[valid]
    phi = (scan.angles() + POSE.theta)[valid]
    r1 = np.floor(sv + d / RES * np.sin(phi)).astype(np.int64)
    c1 = np.floor(su + d / RES * np.cos(phi)).astype(np.int64)
    return math.floor(sv), math.floor(su), r1, c1, is_hit[valid]


@njit(cache=True)
def numba_bresenham(
    logodds: np.ndarray,
    r0: int,
    c0: int,
    r1s: np.ndarray,
    c1s: np.ndarray,
    hits: np.ndarray,
    hit: float,
    miss: float,
    lo: float,
    hi: float,
) -> None:
    """Baseline: Bresenham from the sensor cell to each end cell, ``+=`` and clamp."""
    rows, cols = logodds.shape
    for k in range(r1s.shape[0]):
        r1 = r1s[k]
        c1 = c1s[k]
        dr = abs(r1 - r0)
        dc = abs(c1 - c0)
        sr = 1 if r1 > r0 else -1
        sc = 1 if c1 > c0 else -1
        err = dc - dr
        r = r0
        c = c0
        while True:
            last = r == r1 and c == c1
            if 0 <= r < rows and 0 <= c < cols:
                upd = hit if (last and hits[k]) else miss
                logodds[r, c] = np.minimum(np.maximum(logodds[r, c] + upd, lo), hi)
            if last:
                break
            e2 = 2 * err
            if e2 > -dr:
                err -= dr
                c += sc
            if e2 < dc:
                err += dc
                r += sr


def skimage_loop(
    logodds: np.ndarray, r0: int, c0: int, r1s: np.ndarray, c1s: np.ndarray, hits: np.ndarray
) -> None:
    rows, cols = logodds.shape
    for r1, c1, is_hit in zip(r1s, c1s, hits, strict=True):
        rr, cc = line(r0, c0, int(r1), int(c1))
        upd = np.full(rr.shape, MISS, dtype=np.float32)
        if is_hit:
            upd[-1] = HIT
        keep = (rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)
        rr, cc = rr[keep], cc[keep]
        logodds[rr, cc] = np.clip(logodds[rr, cc] + upd[keep], *CLAMP)


@pytest.mark.benchmark(group="integrate_scan 360 beams, 12 m, 0.05 m")
@pytest.mark.parametrize(
    "contestant", ["navkit", "navkit_method", "navkit_exact", "numba_bresenham", "skimage"]
)
def test_integrate_scan(benchmark: Any, contestant: str) -> None:
    """One scan into a new grid every round (made outside the timer): a grid saturating
    over the rounds, or a scan skipped as already integrated, cannot stand in for the
    work; every round's grid is checked equal to what an untimed call wrote into a
    new grid (:func:`timed_fresh`; navkit's Bresenham cells are the baseline's,
    :func:`test_navkit_and_baseline_agree`)."""
    scan = room_scan()
    r0, c0, r1s, c1s, hits = beam_cells(scan)
    if contestant == "navkit":
        run: Any = lambda grid: integrate_scan(grid, scan, POSE)  # noqa: E731
    elif contestant == "navkit_method":
        run = lambda grid: grid.integrate_scan(scan, POSE)  # noqa: E731
    elif contestant == "navkit_exact":
        run = lambda grid: integrate_scan(grid, scan, POSE, exact=True)  # noqa: E731
    elif contestant == "numba_bresenham":
        run = lambda lo: numba_bresenham(lo, r0, c0, r1s, c1s, hits, HIT, MISS, *CLAMP)  # noqa: E731
    else:
        peer("skimage")
        run = lambda lo: skimage_loop(lo, r0, c0, r1s, c1s, hits)  # noqa: E731
    if contestant.startswith("navkit"):
        fresh: Any = lambda: (new_grid(),)  # noqa: E731
    else:
        fresh = lambda: (np.zeros(new_grid().shape, dtype=np.float32),)  # noqa: E731

    def logodds(args: tuple[Any, ...]) -> np.ndarray:
        return np.asarray(getattr(args[0], "logodds", args[0]))

    first = fresh()
    run(*first)  # compile (numba) outside the timer
    want = logodds(first)

    def check(args: tuple[Any, ...], _answer: Any) -> None:
        assert np.array_equal(logodds(args), want), contestant

    timed_fresh(benchmark, run, fresh, check, ROUNDS)
    updated = int((want != 0).sum())  # every round's grid is want (check)
    benchmark.extra_info["cells_updated"] = updated
    benchmark.extra_info["beams"] = len(scan)
    # All contestants touch the same region: a sanity check, not a timing assertion.
    assert updated > 20_000


def test_navkit_and_baseline_agree() -> None:
    """One scan into empty grids: navkit's Bresenham cells are the baseline's."""
    scan = room_scan()
    grid = new_grid()
    integrate_scan(grid, scan, POSE)
    r0, c0, r1s, c1s, hits = beam_cells(scan)
    logodds = np.zeros(grid.shape, dtype=np.float32)
    numba_bresenham(logodds, r0, c0, r1s, c1s, hits, HIT, MISS, *CLAMP)
    assert np.array_equal(grid.logodds != 0, logodds != 0)
    ends = {(int(r), int(c)) for r, c, h in zip(r1s, c1s, hits, strict=True) if h}
    assert {(int(r), int(c)) for r, c in np.argwhere(grid.logodds > 0)} == ends


def world_to_cell_grid() -> OccupancyGrid:
    """The rotated grid of the ``world_to_cell`` group."""
    return OccupancyGrid.empty(
        width=50.0, height=40.0, resolution=RES, origin=Pose2D(-20.0, -15.0, 0.4)
    )


def world_points(rng: np.random.Generator) -> np.ndarray:
    """10^6 points over the grid and around it (some fall outside: no clipping)."""
    return rng.uniform(-30, 30, size=(1_000_000, 2))


def world_to_cell_case() -> tuple[OccupancyGrid, np.ndarray]:
    """The rotated grid and the 10^6 seeded points of the ``world_to_cell`` group."""
    return world_to_cell_grid(), world_points(np.random.default_rng(0))


def numpy_world_to_cell(grid: OccupancyGrid, pts: np.ndarray) -> np.ndarray:
    """The rule in NumPy: rotate into the grid frame, divide by the resolution, floor."""
    o = grid.origin
    c, s = math.cos(o.theta), math.sin(o.theta)
    d = pts - (o.x, o.y)
    u = (d[:, 0] * c + d[:, 1] * s) / RES
    v = (-d[:, 0] * s + d[:, 1] * c) / RES
    return np.floor(np.column_stack((v, u))).astype(np.int64)


def assert_cells(grid: OccupancyGrid, pts: np.ndarray, cells: np.ndarray, continuous: bool) -> None:
    """``cells`` are those of ``pts`` by the NumPy rule; continuous ones floor to them
    after the half-cell shift to cell centres (a point on a boundary: either cell)."""
    want = numpy_world_to_cell(grid, pts)
    assert cells.shape == want.shape
    if not continuous:
        np.testing.assert_array_equal(cells, want)
        return
    close = np.abs(cells + 0.5 - np.round(cells + 0.5)) < 1e-6
    np.testing.assert_array_equal(np.floor(cells + 0.5)[~close], want[~close])


# Rounds of the world_to_cell group: one call each (~10-30 ms), each on 10^6 new
# points made outside the timer, its cells checked after it (also outside).
WORLD_TO_CELL_ROUNDS = 20


@pytest.mark.benchmark(group="world_to_cell 10^6 points")
@pytest.mark.parametrize("contestant", ["navkit", "navkit_continuous", "numpy"])
def test_world_to_cell(benchmark: Any, contestant: str) -> None:
    """10^6 new points every round (seeded, made outside the timer), every round's
    cells checked against the NumPy rule (:func:`timed_fresh`): an answer kept
    for the points of an earlier round cannot stand in for the work, one wrong
    under the timer fails. The first round's points are
    :func:`world_to_cell_case`'s (``compare_peers.py`` compares its contestants'
    first answers and times this test's first call, so nothing runs before it
    here)."""
    grid = world_to_cell_grid()
    rng = np.random.default_rng(0)
    if contestant == "navkit":
        run: Any = grid.world_to_cell
    elif contestant == "navkit_continuous":
        run = lambda pts: grid.world_to_cell(pts, continuous=True)  # noqa: E731
    else:
        run = lambda pts: numpy_world_to_cell(grid, pts)  # noqa: E731
    continuous = contestant == "navkit_continuous"
    cells = timed_fresh(
        benchmark,
        run,
        lambda: (world_points(rng),),
        lambda args, found: assert_cells(grid, args[0], found, continuous),
        WORLD_TO_CELL_ROUNDS,
    )
    assert cells.shape == (1_000_000, 2)


def test_world_to_cell_agree() -> None:
    """The contestants' cells: navkit's integer cells are NumPy's; continuous ones floor
    to them after the half-cell shift to cell centres."""
    grid, pts = world_to_cell_case()
    assert_cells(grid, pts, grid.world_to_cell(pts), continuous=False)
    assert_cells(grid, pts, grid.world_to_cell(pts, continuous=True), continuous=True)
