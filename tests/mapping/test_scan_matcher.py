"""ScanMatcher: exact gradient, synthetic recovery with navkit.sim's LiDAR, bad input."""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely import affinity
from shapely.geometry import LineString, Polygon, box

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, ScanMatchResult, integrate_scan
from navkit.mapping._logodds import logit
from navkit.mapping._scan_matcher import scan_points
from navkit.mapping._scan_matcher_kernels import (
    accumulate,
    correlative_search,
    interpolate_batch,
)
from navkit.sim import Lidar, RangeNoise, World

# A Hokuyo-class scanner: 1 % range noise, 360 beams, 10 m.
HOKUYO = RangeNoise(limits=(math.inf,), sigma=(0.01,))
RES = 0.05
HECTOR = {"hit": logit(0.9), "miss": logit(0.4), "clamp": (-50.0, 50.0)}


# ------------------------------------------------------------------ gradient
def _m(logodds: np.ndarray, row: float, col: float) -> float:
    out = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    return float(out[0, 0])


@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.floats(-6.0, 6.0), min_size=12, max_size=12),
    r0=st.integers(0, 2),
    c0=st.integers(0, 1),
    fr=st.floats(0.02, 0.98),
    fc=st.floats(0.02, 0.98),
)
def test_gradient_matches_finite_differences(
    values: list[float], r0: int, c0: int, fr: float, fc: float
) -> None:
    logodds = np.array(values, dtype=np.float32).reshape(4, 3)
    row, col = r0 + fr, c0 + fc
    out = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    h = 1e-6
    d_row = (_m(logodds, row + h, col) - _m(logodds, row - h, col)) / (2 * h)
    d_col = (_m(logodds, row, col + h) - _m(logodds, row, col - h)) / (2 * h)
    assert out[0, 1] == pytest.approx(d_row, abs=1e-6)
    assert out[0, 2] == pytest.approx(d_col, abs=1e-6)


def test_hector_swapped_gradient_is_wrong_and_ours_is_not() -> None:
    # Hector's interpMapValueWithDerivatives weights the x difference by the x
    # factor (and y by y); the derivative of the bilinear interpolant weights
    # each by the other axis' factor. One asymmetric cell shows the difference.
    p = np.array([[0.1, 0.9], [0.5, 0.2]])  # p[row, col]
    logodds = np.log(p / (1 - p)).astype(np.float32)
    row, col = 0.3, 0.8
    b, a = row, col
    out = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    h = 1e-6
    fd_col = (_m(logodds, row, col + h) - _m(logodds, row, col - h)) / (2 * h)
    fd_row = (_m(logodds, row + h, col) - _m(logodds, row - h, col)) / (2 * h)
    q = logodds.astype(np.float64)
    q = 1 / (1 + np.exp(-q))
    swapped_col = (1 - a) * (q[0, 1] - q[0, 0]) + a * (q[1, 1] - q[1, 0])
    swapped_row = (1 - b) * (q[1, 0] - q[0, 0]) + b * (q[1, 1] - q[0, 1])
    assert out[0, 2] == pytest.approx(fd_col, abs=1e-7)
    assert out[0, 1] == pytest.approx(fd_row, abs=1e-7)
    assert abs(swapped_col - fd_col) > 0.05 and abs(swapped_row - fd_row) > 0.05


def test_pose_jacobian_matches_finite_differences() -> None:
    rng = np.random.default_rng(3)
    logodds = rng.normal(0.0, 2.0, size=(40, 50)).astype(np.float32)
    origin = (0.3, -0.2, 0.4)  # a rotated grid exercises the frame change too
    points = rng.uniform(-0.6, 0.6, size=(30, 2))
    pose = np.array([1.1, 0.9, 0.3])

    def cost(p: np.ndarray) -> float:
        c, _ = accumulate(
            logodds, *origin, 0.1, points, p[0], p[1], p[2], 0.0, np.empty((0, 0)), np.empty(0)
        )
        return float(c)

    hess = np.empty((3, 3))
    grad = np.empty(3)
    accumulate(logodds, *origin, 0.1, points, pose[0], pose[1], pose[2], 0.0, hess, grad)
    numeric = np.empty(3)
    for i in range(3):
        d = np.zeros(3)
        d[i] = 1e-7
        numeric[i] = (cost(pose + d) - cost(pose - d)) / 2e-7
    # d/dξ Σ (1 - M)² = -2 Σ Jᵀ (1 - M)
    np.testing.assert_allclose(-2 * grad, numeric, rtol=1e-5, atol=1e-5)
    assert np.allclose(hess, hess.T) and np.linalg.eigvalsh(hess).min() >= -1e-9


# ----------------------------------------------------------------- synthetic
def _room() -> list[object]:
    shapes = [box(0, 0, 8, 6).exterior, box(3.0, 2.0, 3.6, 2.6), box(6.0, 4.0, 6.5, 4.3)]
    return [affinity.rotate(s, 17, origin=(0, 0)) for s in shapes]


def _corridor() -> list[object]:
    # 30 m long, 2 m wide, door recesses every 3 m on alternating sides.
    south = [(0.0, 0.0)]
    north = [(0.0, 2.0)]
    for i, x in enumerate(np.arange(2.0, 29.0, 3.0)):
        if i % 2:
            south += [(x, 0.0), (x, -0.3), (x + 0.9, -0.3), (x + 0.9, 0.0)]
        else:
            north += [(x, 2.0), (x, 2.3), (x + 0.9, 2.3), (x + 0.9, 2.0)]
    south.append((30.0, 0.0))
    north.append((30.0, 2.0))
    shapes = [LineString(south), LineString(north)]
    return [affinity.rotate(s, 17, origin=(0, 0)) for s in shapes]


def _poses(
    world: World, region: tuple[float, ...], n: int, rng: np.random.Generator
) -> list[Pose2D]:
    c, s = math.cos(math.radians(17)), math.sin(math.radians(17))
    out: list[Pose2D] = []
    while len(out) < n:
        x, y = rng.uniform(region[0], region[2]), rng.uniform(region[1], region[3])
        pose = Pose2D(c * x - s * y, s * x + c * y, rng.uniform(-math.pi, math.pi))
        if not world.collides(0.3, pose):
            out.append(pose)
    return out


def _mapped(world: World, region: tuple[float, ...], rng: np.random.Generator) -> OccupancyGrid:
    """A map built as the mapper builds it: 25 noisy scans written with Hector's update."""
    grid = OccupancyGrid.empty(width=50.0, height=50.0, resolution=RES, origin=(-15.0, -15.0, 0.0))
    lidar = Lidar(n_beams=360, range_max=10.0, noise=HOKUYO)
    for pose in _poses(world, region, 25, rng):
        integrate_scan(grid, lidar.scan(world, pose, seed=rng), pose, **HECTOR)
    return grid


@pytest.mark.parametrize(
    ("shapes", "region"),
    [(_room, (0.8, 0.8, 7.2, 5.2)), (_corridor, (4.0, 0.6, 26.0, 1.4))],
    ids=["room", "corridor"],
)
def test_recovers_offsets_of_30cm_and_03rad(shapes: object, region: tuple[float, ...]) -> None:
    rng = np.random.default_rng(11)
    world = World(shapes())  # type: ignore[operator]
    grid = _mapped(world, region, rng)
    matcher = ScanMatcher()
    pyramid = matcher.pyramid(grid)
    lidar = Lidar(n_beams=360, range_max=10.0, noise=HOKUYO)
    for true in _poses(world, region, 25, rng):
        scan = lidar.scan(world, true, seed=rng)
        d = rng.uniform(0.0, 0.3)
        a = rng.uniform(-math.pi, math.pi)
        turn = rng.choice([-1.0, 1.0]) * rng.uniform(0.0, 0.3)
        guess = Pose2D(true.x + d * math.cos(a), true.y + d * math.sin(a), true.theta + turn)
        result = matcher.match(pyramid, scan, guess)
        assert result.converged, result
        assert math.hypot(result.pose.x - true.x, result.pose.y - true.y) < RES
        assert abs(math.remainder(result.pose.theta - true.theta, math.tau)) < math.radians(1)
        assert result.score > 0.6
        # The covariance is a real one: symmetric, positive definite, small.
        cov = result.covariance
        assert np.allclose(cov, cov.T) and np.linalg.eigvalsh(cov).min() > 0
        assert np.sqrt(cov[0, 0]) < RES and np.sqrt(cov[2, 2]) < math.radians(1)


def test_correlative_search_widens_the_basin() -> None:
    # Guesses 0.45-0.6 m and 0.45-0.6 rad off: beyond Gauss-Newton's basin on
    # a 20 cm coarsest level, inside a ±0.6 m, ±0.7 rad pre-search.
    rng = np.random.default_rng(5)
    world = World(_room())
    region = (0.8, 0.8, 7.2, 5.2)
    pyramid = ScanMatcher().pyramid(_mapped(world, region, rng))
    lidar = Lidar(n_beams=360, range_max=10.0, noise=HOKUYO)
    plain = ScanMatcher()
    searching = ScanMatcher(search_distance=0.6, search_angle=0.7)
    recovered = {"plain": 0, "search": 0}
    trials = _poses(world, region, 12, rng)
    for true in trials:
        scan = lidar.scan(world, true, seed=rng)
        d, a = rng.uniform(0.45, 0.6), rng.uniform(-math.pi, math.pi)
        turn = rng.choice([-1.0, 1.0]) * rng.uniform(0.45, 0.6)
        guess = Pose2D(true.x + d * math.cos(a), true.y + d * math.sin(a), true.theta + turn)
        for name, matcher in (("plain", plain), ("search", searching)):
            pose = matcher.match(pyramid, scan, guess).pose
            ok = math.hypot(pose.x - true.x, pose.y - true.y) < RES and abs(
                math.remainder(pose.theta - true.theta, math.tau)
            ) < math.radians(1)
            recovered[name] += ok
    assert recovered["search"] == len(trials)
    assert recovered["plain"] < len(trials) // 2


def test_correlative_search_spreads_translations_beyond_its_pose_budget(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A wide window on a fine grid keeps to the pose budget and still covers the window.

    (A 100 m window on a 1 cm grid used to mean 3e11 candidate poses: days.)
    """
    import navkit.mapping._scan_matcher as module

    calls: list[tuple[int, float, int, float]] = []

    def spy(*args: object) -> float:
        calls.append(args[7:11])  # type: ignore[arg-type]
        return float(correlative_search(*args))  # type: ignore[arg-type]

    angles = np.linspace(-math.pi, math.pi, 180, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    scan = _scan(list(ranges))
    room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=RES, origin=(-4.0, -3.0, 0.0))
    integrate_scan(room, scan, (0.0, 0.0, 0.0), hit=2.2, miss=-0.4)
    monkeypatch.setattr(module, "correlative_search", spy)
    matcher = ScanMatcher(levels=1, search_distance=2.0, search_angle=0.3)
    matcher.match(room, scan, Pose2D(0.1, 0.0, 0.0))
    steps_xy, step_xy, steps_theta, _ = calls[-1]
    assert (steps_xy, step_xy) == (40, RES)  # within the budget: one cell apart
    monkeypatch.setattr(module, "_MAX_SEARCH_POSES", 20_000)
    matcher.match(room, scan, Pose2D(0.1, 0.0, 0.0))
    steps_xy, step_xy, steps_theta, _ = calls[-1]
    assert (2 * steps_xy + 1) ** 2 * (2 * steps_theta + 1) <= 20_000
    assert steps_xy < 40 and steps_xy * step_xy == pytest.approx(2.0)


def test_correlative_search_kernel_finds_the_grid_pose() -> None:
    # An L of occupied cells; points placed at a pose that is on the search grid.
    logodds = np.full((60, 60), -2.0, dtype=np.float32)
    logodds[10, 10:50] = 5.0
    logodds[10:50, 10] = 5.0
    res = 0.1
    cells = np.array([(10, c) for c in range(12, 50, 2)] + [(r, 10) for r in range(12, 50, 2)])
    world = (cells[:, ::-1] + 0.5) * res  # (x, y) of the cell centres
    true = np.array([2.0, 2.5, 0.3])
    c, s = math.cos(true[2]), math.sin(true[2])
    points = (world - true[:2]) @ np.array([[c, -s], [s, c]])  # sensor frame
    step_theta = 0.05
    pose = true + np.array([2 * res, -3 * res, -4 * step_theta])
    cost = correlative_search(
        logodds, 0.0, 0.0, 0.0, res, points, pose, 4, res, 5, step_theta, 0.0, 0.0
    )
    np.testing.assert_allclose(pose, true, atol=1e-9)
    assert cost == pytest.approx((1.0 - 1.0 / (1.0 + math.exp(-5.0))) ** 2, rel=1e-5)
    # A flat (unknown) map: every candidate ties and the input pose is kept.
    flat = np.zeros((60, 60), dtype=np.float32)
    start = np.array([3.0, 3.0, 0.1])
    pose = start.copy()
    correlative_search(flat, 0.0, 0.0, 0.0, res, points, pose, 2, res, 3, 0.05, 1.0, 1.0)
    np.testing.assert_array_equal(pose, start)


def test_single_grid_and_pyramid_agree() -> None:
    rng = np.random.default_rng(2)
    world = World(_room())
    grid = _mapped(world, (0.8, 0.8, 7.2, 5.2), rng)
    matcher = ScanMatcher()
    true = _poses(world, (2.0, 1.0, 6.0, 5.0), 1, rng)[0]
    scan = Lidar(n_beams=360, range_max=10.0, noise=None).scan(world, true)
    guess = Pose2D(true.x + 0.1, true.y - 0.1, true.theta + 0.1)
    one = matcher.match(grid, scan, guess)
    many = matcher.match(matcher.pyramid(grid), scan, guess)
    assert one.pose == many.pose and np.array_equal(one.covariance, many.covariance)
    levels = matcher.pyramid(grid)
    assert [g.resolution for g in levels] == [RES, 2 * RES, 4 * RES]
    assert all(g.origin == grid.origin for g in levels)
    # Coarse cells keep the largest log-odds of their block: walls survive.
    assert levels[1].occupied().sum() >= grid.occupied().sum() / 4


# ------------------------------------------------------------------ bad input
def _scan(ranges: list[float], range_max: float = 10.0) -> LaserScan:
    n = len(ranges)
    return LaserScan(
        ranges,
        angle_min=-math.pi,
        angle_increment=2 * math.pi / n,
        range_min=0.1,
        range_max=range_max,
    )


def _square_map() -> OccupancyGrid:
    occ = np.zeros((80, 80), dtype=bool)
    occ[10, 10:70] = occ[69, 10:70] = occ[10:70, 10] = occ[10:70, 69] = True
    return OccupancyGrid.from_occupancy(occ, resolution=0.05)


def _assert_guess_kept(result: ScanMatchResult, guess: Pose2D, reason: str) -> None:
    assert result.reason == reason and not result.converged
    assert result.pose == guess
    assert np.isinf(np.diag(result.covariance)).all()
    assert not np.isnan(result.covariance).any()


@pytest.mark.parametrize(
    "ranges",
    [[math.nan] * 90, [math.inf] * 90, [-math.inf] * 90, [10.0] * 90, [0.01] * 90, [1.0, 1.0]],
    ids=["nan", "inf", "too-close", "max-range", "below-min", "two-beams"],
)
def test_no_valid_beams_keeps_the_guess(ranges: list[float]) -> None:
    guess = Pose2D(2.0, 2.0, 0.3)
    result = ScanMatcher().match(_square_map(), _scan(ranges), guess)
    _assert_guess_kept(result, guess, "no valid beams")
    assert result.iterations == 0


def test_guess_outside_the_map_keeps_the_guess() -> None:
    guess = Pose2D(50.0, -3.0, 0.0)
    result = ScanMatcher().match(_square_map(), _scan([1.0] * 90), guess)
    _assert_guess_kept(result, guess, "guess outside the map")
    # Every point off the map reads unknown (p = 1/2; 0 until review 50).
    assert result.score == 0.5


@pytest.mark.parametrize("weights", [(0.0, 0.0), (1.0, 1.0)])
def test_featureless_corridor_is_degenerate(weights: tuple[float, float]) -> None:
    # Two endless parallel walls: nothing fixes the position along them. They run
    # along cell middles, not cell edges, where the last bit of each range would
    # decide the row of each hit (a ragged wall that does fix the position).
    world = World([LineString([(-50, 0), (50, 0)]), LineString([(-50, 2), (50, 2)])])
    grid = OccupancyGrid.empty(width=30, height=6, resolution=RES, origin=(-15, -2 - RES / 2, 0))
    lidar = Lidar(n_beams=360, range_max=8.0, noise=None)
    for x in np.linspace(-5, 5, 11):
        integrate_scan(grid, lidar.scan(world, (x, 1.0, 0.0)), (x, 1.0, 0.0), **HECTOR)
    guess = Pose2D(0.3, 1.1, 0.05)
    tw, rw = weights
    matcher = ScanMatcher(translation_weight=tw, rotation_weight=rw)
    result = matcher.match(grid, lidar.scan(world, (0.0, 1.0, 0.0)), guess)
    assert result.reason == "degenerate" and not result.converged
    assert np.isfinite([result.pose.x, result.pose.y, result.pose.theta]).all()
    if tw == 0.0:
        assert result.pose == guess
    else:
        # The prior keeps the free direction; the walls still fix y and theta.
        assert result.pose.x == pytest.approx(0.3, abs=0.02)
        assert result.pose.y == pytest.approx(1.0, abs=RES)
        assert result.pose.theta == pytest.approx(0.0, abs=0.01)


def test_empty_map_is_degenerate() -> None:
    grid = OccupancyGrid.empty(width=5, height=5, resolution=0.1)
    guess = Pose2D(2.5, 2.5, 0.0)
    result = ScanMatcher(translation_weight=0.0, rotation_weight=0.0).match(
        grid, _scan([1.0] * 90), guess
    )
    _assert_guess_kept(result, guess, "degenerate")
    assert result.score == pytest.approx(0.5)


def test_wrong_arguments() -> None:
    matcher = ScanMatcher()
    grid = _square_map()
    scan = _scan([1.0] * 90)
    with pytest.raises(TypeError, match="maps"):
        matcher.match("map", scan, (1, 1, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"maps\[1\]"):
        matcher.match([grid, 3], scan, (1, 1, 0))  # type: ignore[list-item]
    with pytest.raises(ValueError, match="at least one"):
        matcher.match([], scan, (1, 1, 0))
    with pytest.raises(TypeError, match="scan"):
        matcher.match(grid, [1.0], (1, 1, 0))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="guess"):
        matcher.match(grid, scan, (math.nan, 1, 0))
    with pytest.raises(TypeError, match="grid"):
        matcher.pyramid([grid])  # type: ignore[arg-type]
    for kwargs, error in [
        ({"levels": 0}, ValueError),
        ({"levels": 2.0}, TypeError),
        ({"levels": True}, TypeError),
        ({"max_iterations": 0}, ValueError),
        ({"max_step_cells": 0.0}, ValueError),
        ({"max_step_angle": 4.0}, ValueError),
        ({"tolerance": -1.0}, ValueError),
        ({"range_max": 0.0}, ValueError),
        ({"translation_weight": -1.0}, ValueError),
        ({"rotation_weight": math.inf}, ValueError),
        ({"search_distance": -0.1}, ValueError),
        ({"search_angle": 4.0}, ValueError),
        ({"search_angle": "wide"}, TypeError),
    ]:
        with pytest.raises(error, match=next(iter(kwargs))):
            ScanMatcher(**kwargs)  # type: ignore[arg-type]


def test_inputs_untouched_and_result_frozen() -> None:
    grid = _square_map()
    before = grid.logodds.copy()
    ranges = [1.5] * 90
    scan = _scan(ranges)
    result = ScanMatcher().match(grid, scan, (2.0, 2.0, 0.0))
    assert np.array_equal(grid.logodds, before)
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.score = 1.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        result.covariance[0, 0] = 1.0
    with pytest.raises(ValueError, match="covariance"):
        ScanMatchResult(Pose2D(0, 0, 0), np.full((3, 3), np.nan), 0, 0.5, False, "degenerate")


def test_range_max_drops_long_returns() -> None:
    scan = _scan([1.0, 5.0, 2.0, 8.0])
    assert len(scan_points(scan, None)) == 4
    assert len(scan_points(scan, 4.0)) == 2
    assert ScanMatcher(range_max=4.0).range_max == 4.0


def test_outside_points_do_not_pull() -> None:
    # A polygon obstacle inside, the scan half off the map: still no NaN.
    grid = OccupancyGrid.from_polygons(
        Polygon([(1, 1), (2, 1), (2, 2), (1, 2)]), bounds=(0, 0, 3, 3), resolution=0.05
    )
    result = ScanMatcher().match(grid, _scan([0.8] * 40 + [30.0] * 40), (0.5, 1.5, 0.0))
    assert np.isfinite(result.pose.as_array()).all()


@pytest.mark.parametrize("clone", [copy.deepcopy, lambda r: pickle.loads(pickle.dumps(r))])
def test_copied_and_unpickled_results_stay_read_only(clone: object) -> None:
    # pickle and deepcopy rebuild the fields without __post_init__: the copied
    # covariance came back writable, a "frozen" result that could be changed.
    result = ScanMatchResult(Pose2D(1.0, 2.0, 0.5), np.eye(3), 4, 0.9, True, "converged")
    back = clone(result)  # type: ignore[operator]
    assert back.pose == result.pose and np.array_equal(back.covariance, result.covariance)
    assert back.reason == "converged" and back.iterations == 4
    with pytest.raises(ValueError, match="read-only"):
        back.covariance[0, 0] = 5.0
