"""Review 9: behaviour the mapping tests did not pin down (found by mutation testing).

Each test states a promise of a docstring, checked against an independent
computation, that a one-line change of the code broke without any other test failing.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher
from navkit.mapping._scan_matcher_kernels import (
    STATUS_CONVERGED,
    STATUS_MAX_ITERATIONS,
    correlative_search,
    interpolate_batch,
    match_level,
)
from navkit.mapping.io._map_files import MapMetadata, pixel_occupancy


def _bilinear(p: np.ndarray, row: float, col: float) -> float:
    """Bilinear interpolation of ``p`` between cell centres, written out independently."""
    r0, c0 = math.floor(row), math.floor(col)
    b, a = row - r0, col - c0
    return float(
        (1 - b) * (1 - a) * p[r0, c0]
        + (1 - b) * a * p[r0, c0 + 1]
        + b * (1 - a) * p[r0 + 1, c0]
        + b * a * p[r0 + 1, c0 + 1]
    )


@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.floats(-6.0, 6.0), min_size=12, max_size=12),
    row=st.floats(-1.5, 4.5),
    col=st.floats(-1.5, 3.5),
)
def test_interpolation_is_bilinear_on_the_map_padded_with_unknown_cells(
    values: list[float], row: float, col: float
) -> None:
    # interpolate_batch's docstring: beyond the edge cells' centres (a (4, 3) map
    # covers rows [-0.5, 3.5) and cols [-0.5, 2.5)) the neighbours beyond the edge
    # are unknown (p = 1/2): the map padded with them (zeros past the edge until
    # review 50).
    logodds = np.array(values, dtype=np.float32).reshape(4, 3)
    out = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    p = np.pad(1.0 / (1.0 + np.exp(-logodds.astype(np.float64))), 2, constant_values=0.5)
    assert out[0, 0] == pytest.approx(_bilinear(p, row + 2, col + 2), rel=1e-6, abs=1e-7)


def test_the_outer_half_cell_sees_the_edge_cells_and_unknown_beyond() -> None:
    # Points between the last cell centre and the map edge (col in [cols - 1,
    # cols - 0.5)) interpolate towards unknown cells beyond the edge (they read 0
    # once, as if off the map); past the edge too (zeros there until review 50),
    # and a cell past the edge cells' centres M is 1/2 with no gradient.
    logodds = np.full((3, 3), 4.0, dtype=np.float32)
    p = 1.0 / (1.0 + math.exp(-4.0))
    coords = np.array([[0.5, 2.0], [0.5, 2.25], [2.0, 0.5], [2.25, 1.2], [-0.25, 1.0]])
    out = np.full((len(coords), 3), np.nan)
    interpolate_batch(logodds, coords, out)
    assert out[:, 0] == pytest.approx([p, 0.75 * p + 0.125, p, 0.75 * p + 0.125, 0.75 * p + 0.125])
    beyond = np.array([[0.5, 2.5], [0.5, 2.7], [2.9, 1.2], [2.5, 2.5], [-0.5001, 1.0]])
    interpolate_batch(logodds, beyond, out[: len(beyond)])
    # 2.9 and 2.7: 0.1 and 0.3 of a cell from unknown cells' centres.
    expected = [0.5 * p + 0.25, 0.3 * p + 0.35, 0.1 * p + 0.45, 0.25 * p + 0.375]
    assert out[:4, 0] == pytest.approx(expected)
    assert out[4, 0] == pytest.approx(0.4999 * p + 0.5001 * 0.5)
    far = np.array([[0.5, 3.0], [0.5, 40.0], [-1.0001, 1.0], [1e300, -1e300], [-9.0, 9.0]])
    interpolate_batch(logodds, far, out[: len(far)])
    assert out[: len(far)].tolist() == [[0.5, 0.0, 0.0]] * len(far)



def _match_on_a_flat_map(
    start: tuple[float, float, float],
    prior: tuple[float, float, float],
    translation_weight: float,
    rotation_weight: float,
    *,
    iterations: int = 50,
    max_step_xy: float = 10.0,
    max_step_theta: float = 1.0,
) -> tuple[np.ndarray, int, int]:
    """match_level on a map of constant probability: only the pull towards ``prior`` acts."""
    logodds = np.zeros((40, 40), dtype=np.float32)  # p = 0.5 everywhere: no map gradient
    points = np.array([[0.3, 0.0], [0.0, 0.4], [-0.2, -0.1], [0.1, -0.3]])
    pose = np.array(start, dtype=np.float64)
    done, status = match_level(
        logodds, 0.0, 0.0, 0.0, 0.1, points, pose,
        iterations, max_step_xy, max_step_theta, 1e-9, 1e-10,
        np.array(prior, dtype=np.float64), translation_weight, rotation_weight, 0.0,
        np.empty((3, 3)), np.empty(3), np.empty(3), np.empty((0, 0)),
    )  # fmt: skip
    return pose, done, status


def test_the_pull_alone_brings_the_pose_back_to_the_prior() -> None:
    # match_level minimises the mean (1 - M)² (constant here) plus
    # translation_weight² |t - t0|² + rotation_weight² (θ - θ0)²: the minimum is
    # the prior itself, whatever the (different) weights.
    prior = (2.0, 2.0, 0.1)
    pose, _, status = _match_on_a_flat_map((2.1, 1.95, 0.3), prior, 0.5, 3.0)
    assert status == STATUS_CONVERGED
    np.testing.assert_allclose(pose, prior, atol=1e-9)


def test_a_semi_definite_system_is_solved_not_called_singular() -> None:
    # No rotation weight and no map gradient: H = diag(w², w², 0) is only
    # semi-definite. _solve3's ridge keeps it solvable (the docstring's promise),
    # so the translation still goes back to the prior and the heading stays.
    pose, _, status = _match_on_a_flat_map((2.1, 1.95, 0.3), (2.0, 2.0, 0.1), 0.5, 0.0)
    assert status == STATUS_CONVERGED
    np.testing.assert_allclose(pose, (2.0, 2.0, 0.3), atol=1e-9)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_steps_are_clamped_keeping_their_direction(sign: float) -> None:
    # match_level clamps the translation of a step to max_step_xy (keeping its
    # direction) and its rotation to ±max_step_theta. The pull alone asks for
    # one step of (0.6, 0.8) m and 0.5 rad back to the prior; each clamped step
    # lowers the cost, so three iterations move exactly three clamped steps.
    prior = np.array([2.0, 2.0, 0.0])
    offset = sign * np.array([0.6, 0.8, 0.5])
    pose, done, status = _match_on_a_flat_map(
        tuple(prior + offset), tuple(prior), 1.0, 1.0,
        iterations=3, max_step_xy=0.1, max_step_theta=0.05,
    )  # fmt: skip
    assert (done, status) == (3, STATUS_MAX_ITERATIONS)
    expected = prior + offset - 3 * sign * np.array([0.06, 0.08, 0.05])
    np.testing.assert_allclose(pose, expected, atol=1e-12)


def test_a_cell_exactly_at_a_threshold_is_neither_occupied_nor_free() -> None:
    # occupied: p > threshold; free: p < threshold; unknown: free_thresh <= p <=
    # occupied_thresh (map_server's rule). Log-odds 0 is p = 0.5 exactly.
    grid = OccupancyGrid.empty(width=0.2, height=0.1, resolution=0.1)  # two p = 0.5 cells
    assert not grid.occupied(0.5).any()
    assert not grid.free(0.5).any()
    at_occupied = OccupancyGrid(
        np.zeros((1, 2)), resolution=0.1, occupied_thresh=0.5, free_thresh=0.2
    )
    at_free = OccupancyGrid(np.zeros((1, 2)), resolution=0.1, occupied_thresh=0.8, free_thresh=0.5)
    for grid in (at_occupied, at_free):
        assert grid.unknown().all()
        assert not grid.occupied().any() and not grid.free().any()


def test_a_step_stops_only_when_its_rotation_is_below_tolerance_too() -> None:
    # "It stops when a step is below tol_xy and tol_theta": a pure turn back to
    # the prior (no translation at all) goes on until the turn is done.
    prior = (2.0, 2.0, 0.0)
    pose, done, status = _match_on_a_flat_map(
        (2.0, 2.0, 0.5), prior, 1.0, 1.0, iterations=50, max_step_theta=0.05
    )
    assert status == STATUS_CONVERGED
    assert done > 10  # ten clamped turns of 0.05 rad at least
    np.testing.assert_allclose(pose, prior, atol=1e-9)


def _outwards(n: int) -> list[int]:
    """0, 1, -1, 2, -2, ... n, -n: the kernel's documented visiting order."""
    return [0] + [s * k for k in range(1, n + 1) for s in (1, -1)]


def _search_costs(
    logodds: np.ndarray, res: float, points: np.ndarray, start: np.ndarray,
    steps_xy: int, step_xy: float, steps_theta: int, step_theta: float, wt: float, wr: float,
) -> list[tuple[float, np.ndarray]]:
    """Every candidate of the correlative search with its cost, brute force, in visiting order."""
    p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    rows, cols = logodds.shape
    out = []
    for k in _outwards(steps_theta):
        theta = start[2] + k * step_theta
        c, s = math.cos(theta), math.sin(theta)
        for i in _outwards(steps_xy):
            for j in _outwards(steps_xy):
                x, y = start[0] + i * step_xy, start[1] + j * step_xy
                world_x = x + c * points[:, 0] - s * points[:, 1]
                world_y = y + s * points[:, 0] + c * points[:, 1]
                col = np.floor(world_x / res).astype(int)
                row = np.floor(world_y / res).astype(int)
                inside = (row >= 0) & (row < rows) & (col >= 0) & (col < cols)
                prob = np.full(len(points), 0.5)
                prob[inside] = p[row[inside], col[inside]]
                shift = (i * step_xy) ** 2 + (j * step_xy) ** 2
                pull = wt**2 * shift + wr**2 * (k * step_theta) ** 2
                out.append((float(np.mean((1.0 - prob) ** 2)) + pull, np.array([x, y, theta])))
    return out


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    wt=st.sampled_from([0.0, 0.5, 3.0]),
    wr=st.sampled_from([0.0, 0.5, 3.0]),
)
def test_correlative_search_returns_the_cheapest_candidate(seed: int, wt: float, wr: float) -> None:
    # The search's docstring: the best of the grid of rotations and translations,
    # cost = mean (1 - p)² of the points' cells (1/2 off the map, unknown; 0 until
    # review 50) + the pull.
    rng = np.random.default_rng(seed)
    res = 0.1
    logodds = rng.choice([-3.0, 0.0, 4.0], size=(12, 14)).astype(np.float32)
    points = rng.uniform(-0.5, 0.5, size=(8, 2))
    start = np.array([rng.uniform(0.3, 1.1), rng.uniform(0.3, 0.9), rng.uniform(-3.0, 3.0)])
    args = (2, 0.07, 2, 0.2, wt, wr)
    pose = start.copy()
    cost = correlative_search(logodds, 0.0, 0.0, 0.0, res, points, pose, *args)
    candidates = _search_costs(logodds, res, points, start, *args)
    best_cost = min(c for c, _ in candidates)
    # (p of a cell comes from a single-precision exp: hence rel=1e-6.)
    assert cost == pytest.approx(best_cost, rel=1e-6)
    # The pose returned is a candidate, and one of that cost.
    match = [c for c, q in candidates if np.allclose(q, pose, rtol=0.0, atol=1e-12)]
    assert match and match[0] == pytest.approx(best_cost, rel=1e-6)


def test_correlative_search_keeps_the_input_pose_on_a_flat_map_without_pull() -> None:
    # "A tie keeps the earlier one, so a flat cost leaves the pose unchanged",
    # with no pull to break the ties.
    flat = np.zeros((30, 30), dtype=np.float32)
    points = np.array([[0.4, 0.1], [-0.2, 0.3], [0.0, -0.5]])
    start = np.array([1.5, 1.4, 0.2])
    pose = start.copy()
    correlative_search(flat, 0.0, 0.0, 0.0, 0.1, points, pose, 3, 0.1, 4, 0.05, 0.0, 0.0)
    np.testing.assert_array_equal(pose, start)


@settings(max_examples=30, deadline=None)
@given(rows=st.integers(1, 7), cols=st.integers(1, 7), seed=st.integers(0, 2**32 - 1))
def test_pyramid_levels_take_the_largest_log_odds_of_each_block(
    rows: int, cols: int, seed: int
) -> None:
    # downsample: each coarse cell is the largest log-odds of its 2 x 2 block, and
    # cells beyond an odd edge count as unknown (log-odds 0).
    values = np.random.default_rng(seed).uniform(-3.0, -0.1, size=(rows, cols))
    grid = OccupancyGrid(values, resolution=0.1, origin=(1.0, -2.0, 0.3))
    levels = ScanMatcher(levels=2).pyramid(grid)
    if rows == cols == 1:
        assert len(levels) == 1  # no coarser level than one cell
        return
    coarse = levels[1]
    fine = grid.logodds.astype(np.float64)
    expected = np.empty(((rows + 1) // 2, (cols + 1) // 2))
    for r in range(expected.shape[0]):
        for c in range(expected.shape[1]):
            block = fine[2 * r : 2 * r + 2, 2 * c : 2 * c + 2]
            incomplete = block.shape != (2, 2)
            expected[r, c] = max(block.max(), 0.0) if incomplete else block.max()
    np.testing.assert_array_equal(coarse.logodds, expected.astype(np.float32))
    assert coarse.resolution == 0.2 and coarse.origin == grid.origin


def test_unknown_cells_of_an_occupancy_mask_get_log_odds_zero() -> None:
    # from_occupancy: unknown cells at p = 0.5, i.e. log-odds exactly 0.
    occupied = np.array([[True, False, False]])
    unknown = np.array([[False, False, True]])
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5, unknown=unknown)
    assert grid.logodds[0, 2] == 0.0
    assert grid.probability()[0, 2] == 0.5


def test_probabilities_are_float64_to_double_precision() -> None:
    # probability(): a new float64 array, 1 / (1 + exp(-l)) of the stored float32
    # log-odds computed in double precision.
    grid = OccupancyGrid(np.array([[1e-4, -7.3, 0.3]]), resolution=1.0)
    p = grid.probability()
    assert p.dtype == np.float64
    stored = [float(v) for v in grid.logodds[0]]
    expected = [1.0 / (1.0 + math.exp(-v)) for v in stored]
    np.testing.assert_allclose(p[0], expected, rtol=1e-15)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"logodds": np.array([[0.0, 1.5e6]])},
        {"logodds": np.array([[-1.0e6 * 1.01]])},
        {"origin": (0.0, 2e9, 0.0)},
        {"origin": (0.0, -2e9, 0.0)},
        {"origin": (2e9, 0.0, 0.0)},
    ],
)
def test_documented_ranges_of_the_constructor_are_enforced(kwargs: dict[str, object]) -> None:
    # Log-odds within ±1e6 and an origin within ±1e9 m in x and y, else ValueError.
    args: dict[str, object] = {"logodds": np.zeros((1, 1)), "resolution": 0.1, **kwargs}
    logodds = args.pop("logodds")
    with pytest.raises(ValueError, match=r"logodds|origin"):
        OccupancyGrid(logodds, **args)  # type: ignore[arg-type]


def test_a_reading_exactly_at_range_min_is_valid() -> None:
    # Valid readings are finite and in [range_min, range_max).
    scan = LaserScan(np.array([0.5, 0.49, 2.0, 1.0]), angle_min=0.0, angle_increment=0.1,
                     range_min=0.5, range_max=2.0)  # fmt: skip
    assert scan.valid_mask().tolist() == [True, False, False, True]


def test_a_span_beyond_a_full_turn_and_one_increment_is_refused() -> None:
    # 65 beams 0.1 rad apart span 6.4 rad > 2π + 0.1: angles in degrees, or wrong.
    with pytest.raises(ValueError, match="span"):
        LaserScan(np.ones(65), angle_min=-3.2, angle_increment=0.1, range_min=0.0, range_max=5.0)
    # One beam fewer spans 6.3 rad < 2π + 0.1: a full turn plus overlap, accepted.
    LaserScan(np.ones(64), angle_min=-3.15, angle_increment=0.1, range_min=0.0, range_max=5.0)


def test_a_pixel_exactly_at_free_thresh_is_not_free() -> None:
    # map_server: free when p < free_thresh. With free_thresh 0, a white pixel
    # (p = 1 - 255 / 255 = 0 exactly) is not free but unknown.
    meta = MapMetadata(Path("m.pgm"), 0.05, (0.0, 0.0, 0.0), False, 0.65, 0.0, "trinary")
    prob, unknown = pixel_occupancy(np.array([[255.0, 0.0]]), None, meta)
    assert unknown.tolist() == [[True, False]]
    assert prob.tolist() == [[0.5, 1.0]]
