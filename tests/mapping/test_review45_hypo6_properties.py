"""Metamorphic properties of the exact banded distance transform and what uses it (review 45).

No SciPy oracle here (test_review45_memory_limits and test_review45_edt_adversarial
compare bit for bit): relations the transform, :meth:`OccupancyGrid.inflate`,
:func:`costmap` and :func:`traversal_costs` must keep among themselves, on random
masks, resolutions and radii, with the real bands and with bands of a few rows or
of columns forced on small grids.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.mapping._obstacle_distance as distance_module
from navkit.mapping import OccupancyGrid, costmap, traversal_costs

# Resolutions whose multiples are not exact in binary (0.1, 0.3, 0.07) next to exact ones.
_RESOLUTIONS = st.sampled_from([0.05, 0.07, 0.1, 0.25, 0.3, 1.0])


@st.composite
def _masks(draw: st.DrawFn, max_side: int = 12) -> np.ndarray:
    rows, cols = draw(st.integers(1, max_side)), draw(st.integers(1, max_side))
    density = draw(st.sampled_from([0.0, 0.02, 0.1, 0.3, 0.7]))
    seed = draw(st.integers(0, 2**32 - 1))
    occupied = np.random.default_rng(seed).random((rows, cols)) < density
    if draw(st.booleans()):  # at least one obstacle, wherever the draw put none
        occupied[draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))] = True
    return occupied


@st.composite
def _radii(draw: st.DrawFn, resolution: float) -> float:
    """A multiple of the resolution (the rounding edge) as a product or as typed
    (0.3 for 3 cells of 0.1 m: 0.3 / 0.1 < 3 in float64), or any radius up to 6 cells."""
    kind = draw(st.sampled_from(["product", "typed", "any"]))
    if kind == "any":
        return draw(st.floats(0.0, 6.0 * resolution, allow_nan=False))
    radius = draw(st.integers(0, 6)) * resolution
    return round(radius, 9) if kind == "typed" else radius


# How the transform is split: the real bands, bands of `n` rows, or (a grid wider
# than tall) bands of columns of its transpose.
_SPLITS = st.one_of(st.none(), st.integers(1, 5), st.just("columns"))


@contextmanager
def _split(how: int | str | None) -> Iterator[None]:
    with pytest.MonkeyPatch.context() as mp:
        if how == "columns":
            mp.setattr(distance_module, "_BAND_CELLS", 0)
        elif how is not None:
            mp.setattr(distance_module, "_band_rows", lambda rows, cols: how)
        yield


def _grid(occupied: np.ndarray, resolution: float) -> OccupancyGrid:
    return OccupancyGrid.from_occupancy(occupied, resolution=resolution)


@settings(max_examples=150, deadline=None)
@given(occupied=_masks(), resolution=_RESOLUTIONS, data=st.data())
def test_a_larger_radius_inflates_a_superset(
    occupied: np.ndarray, resolution: float, data: st.DataObject
) -> None:
    grid = _grid(occupied, resolution)
    small, large = sorted(data.draw(_radii(resolution)) for _ in range(2))
    inner, outer = grid.inflate(small), grid.inflate(large)
    assert not (inner & ~outer).any(), (small, large)
    assert np.array_equal(grid.inflate(0.0), occupied)


@settings(max_examples=150, deadline=None)
@given(occupied=_masks(), resolution=_RESOLUTIONS, split=_SPLITS, data=st.data())
def test_costs_never_rise_with_the_distance_and_agree_with_inflate(
    occupied: np.ndarray, resolution: float, split: int | str | None, data: st.DataObject
) -> None:
    grid = _grid(occupied, resolution)
    robot, extra = data.draw(_radii(resolution)), data.draw(_radii(resolution))
    scale = data.draw(st.sampled_from([0.5, 3.0, 10.0, 1e3]))
    dist = grid.obstacle_distance()
    with _split(split):
        cost = costmap(
            grid, robot_radius=robot, inflation_radius=robot + extra, cost_scaling_factor=scale
        )
        travel = traversal_costs(
            grid, robot_radius=robot, inflation_radius=robot + extra, cost_scaling_factor=scale
        )
    inflated = grid.inflate(robot)
    # One rule for "the robot's body touches an obstacle" across the three.
    assert np.array_equal(cost >= 253, inflated), (robot, extra)
    assert np.array_equal(np.isinf(travel), inflated)
    # A cost is a non-increasing function of the distance: sorted by distance,
    # costs never rise, and cells at the same distance cost the same.
    order = np.argsort(dist, axis=None, kind="stable")
    d, c = dist.ravel()[order], cost.ravel()[order].astype(np.int64)
    assert not np.any(np.diff(c) > 0), (d.tolist(), c.tolist())
    assert not np.any((np.diff(c) != 0) & (d[1:] == d[:-1])), "same distance, other cost"


@settings(max_examples=150, deadline=None)
@given(occupied=_masks(), resolution=_RESOLUTIONS, split=_SPLITS)
def test_distances_change_by_at_most_a_step_between_neighbours(
    occupied: np.ndarray, resolution: float, split: int | str | None
) -> None:
    with _split(split):
        dist = _grid(occupied, resolution).obstacle_distance()
    if not occupied.any():
        assert np.isinf(dist).all()
        return
    assert np.isfinite(dist).all()
    assert np.array_equal(dist == 0, occupied)
    # 1-Lipschitz: a neighbour's nearest obstacle is at most one step farther
    # (float rounding of sqrt and the product allows a few ulps).
    slack = 1 + 1e-12
    assert (np.abs(np.diff(dist, axis=0)) <= resolution * slack).all()
    assert (np.abs(np.diff(dist, axis=1)) <= resolution * slack).all()
    diagonal = np.hypot(resolution, resolution) * slack
    assert (np.abs(dist[1:, 1:] - dist[:-1, :-1]) <= diagonal).all()
    assert (np.abs(dist[1:, :-1] - dist[:-1, 1:]) <= diagonal).all()


@settings(max_examples=150, deadline=None)
@given(
    occupied=_masks(),
    resolution=_RESOLUTIONS,
    split=_SPLITS,
    flip=st.sampled_from(["T", "ud", "lr"]),
)
def test_a_transposed_or_mirrored_grid_has_the_same_distances_bit_for_bit(
    occupied: np.ndarray, resolution: float, split: int | str | None, flip: str
) -> None:
    moves: dict[str, Callable[[np.ndarray], np.ndarray]] = {
        "T": np.transpose,
        "ud": np.flipud,
        "lr": np.fliplr,
    }
    moved = moves[flip]
    with _split(split):
        dist = _grid(occupied, resolution).obstacle_distance()
        dist_moved = _grid(moved(occupied), resolution).obstacle_distance()
    assert np.array_equal(dist_moved.view(np.int64), moved(dist).view(np.int64))


@settings(max_examples=150, deadline=None)
@given(
    occupied=_masks(max_side=10),
    resolution=_RESOLUTIONS,
    split=_SPLITS,
    pad=st.tuples(*[st.integers(0, 7)] * 4),
    data=st.data(),
)
def test_free_cells_padded_around_keep_the_inner_distances_and_inflation(
    occupied: np.ndarray,
    resolution: float,
    split: int | str | None,
    pad: tuple[int, int, int, int],
    data: st.DataObject,
) -> None:
    top, bottom, left, right = pad
    padded = np.pad(occupied, ((top, bottom), (left, right)))
    inner = (slice(top, top + occupied.shape[0]), slice(left, left + occupied.shape[1]))
    radius = data.draw(_radii(resolution))
    with _split(split):
        grid, grid_padded = _grid(occupied, resolution), _grid(padded, resolution)
        dist, dist_padded = grid.obstacle_distance(), grid_padded.obstacle_distance()
        inflated, inflated_padded = grid.inflate(radius), grid_padded.inflate(radius)
    # No obstacle was added: each inner cell's nearest obstacle is the same one.
    assert np.array_equal(dist_padded[inner].view(np.int64), dist.view(np.int64))
    assert np.array_equal(inflated_padded[inner], inflated)
    outside = np.ones(padded.shape, dtype=bool)
    outside[inner] = False
    # The padding is marked only where an obstacle lies within the radius.
    assert np.array_equal(
        inflated_padded[outside], dist_padded[outside] <= radius + 1e-9 * resolution
    )


@settings(max_examples=100, deadline=None)
@given(
    rows=st.integers(1, 10),
    cols=st.integers(1, 10),
    seed=st.integers(0, 2**32 - 1),
    resolution=_RESOLUTIONS,
    thresholds=st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0)),
)
def test_a_higher_threshold_keeps_fewer_obstacles_and_no_nearer_distances(
    rows: int, cols: int, seed: int, resolution: float, thresholds: tuple[float, float]
) -> None:
    probabilities = np.random.default_rng(seed).random((rows, cols))
    grid = OccupancyGrid.from_probabilities(probabilities, resolution=resolution)
    low, high = sorted(thresholds)
    near, far = (
        grid.obstacle_distance(occupied_thresh=low),
        grid.obstacle_distance(occupied_thresh=high),
    )
    assert (near <= far).all(), (low, high)
    # The threshold only chooses the obstacles: the same as a grid of those obstacles.
    alone = _grid(grid.occupied(high), resolution).obstacle_distance()
    assert np.array_equal(far.view(np.int64), alone.view(np.int64))


@settings(max_examples=100, deadline=None)
@given(occupied=_masks(), resolution=_RESOLUTIONS, split=_SPLITS, data=st.data())
def test_inflating_around_unknown_is_inflating_unknown_cells_made_obstacles(
    occupied: np.ndarray, resolution: float, split: int | str | None, data: st.DataObject
) -> None:
    seed = data.draw(st.integers(0, 2**32 - 1))
    unknown = ~occupied & (np.random.default_rng(seed).random(occupied.shape) < 0.2)
    robot, extra = data.draw(_radii(resolution)), data.draw(_radii(resolution))
    with _split(split):
        around = costmap(
            OccupancyGrid.from_occupancy(occupied, resolution=resolution, unknown=unknown),
            inflate_around_unknown=True,
            robot_radius=robot,
            inflation_radius=robot + extra,
            cost_scaling_factor=3.0,
        )
        solid = costmap(
            _grid(occupied | unknown, resolution),
            robot_radius=robot,
            inflation_radius=robot + extra,
            cost_scaling_factor=3.0,
        )
    assert np.array_equal(around, solid)
