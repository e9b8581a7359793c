"""OccupancyGrid: constructors, coordinates (continuous cells), views, inflation, conveniences."""

from __future__ import annotations

import copy
import inspect
import math
import pickle
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from shapely.geometry import box

import navkit.mapping as mapping
from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, io


def test_empty_grid_shape_and_extent() -> None:
    grid = OccupancyGrid.empty(
        width=3.0, height=2.0, resolution=0.1, origin=Pose2D(-1.0, -2.0, 0.0)
    )
    assert grid.shape == (20, 30)
    assert grid.width == pytest.approx(3.0) and grid.height == pytest.approx(2.0)
    assert grid.unknown().all() and not grid.occupied().any() and not grid.free().any()
    # Rounded up to whole cells.
    assert OccupancyGrid.empty(width=1.01, height=0.2, resolution=0.5).shape == (1, 3)


def test_row_zero_is_lowest_y() -> None:
    grid = OccupancyGrid.empty(
        width=2.0, height=3.0, resolution=0.5, origin=Pose2D(10.0, 20.0, 0.0)
    )
    cells = grid.world_to_cell([[10.1, 20.1], [10.1, 22.9], [11.9, 20.1]])
    assert cells.tolist() == [[0, 0], [5, 0], [0, 3]]


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-20, 20),
    st.floats(-20, 20),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.05, 0.1, 0.3]),
    st.integers(0, 2**32 - 1),
)
def test_world_cell_round_trip(ox: float, oy: float, yaw: float, res: float, seed: int) -> None:
    grid = OccupancyGrid(np.zeros((30, 40)), resolution=res, origin=Pose2D(ox, oy, yaw))
    rng = np.random.default_rng(seed)
    cells = np.column_stack((rng.integers(-5, 35, 50), rng.integers(-5, 45, 50)))
    centres = grid.cell_to_world(cells)
    assert np.array_equal(grid.world_to_cell(centres), cells)
    # Any point lies within half a cell diagonal of its cell's centre.
    local = rng.uniform([-1, -1], [13, 10], size=(200, 2))
    pts = grid.origin.transform_points(local)
    back = grid.cell_to_world(grid.world_to_cell(pts))
    assert np.all(np.hypot(*(back - pts).T) <= res * math.sqrt(0.5) + 1e-9)
    # The kernel agrees with a plain numpy statement of the same rule.
    expected = np.floor(local[:, ::-1] / res).astype(np.int64)
    close = np.abs(local / res - np.round(local / res)) < 1e-9
    ok = ~close.any(axis=1)
    assert np.array_equal(grid.world_to_cell(pts)[ok], expected[ok])
    inside = (expected[:, 0] >= 0) & (expected[:, 0] < 30) & (expected[:, 1] >= 0)
    inside &= expected[:, 1] < 40
    assert np.array_equal(grid.contains(pts)[ok], inside[ok])


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-20, 20),
    st.floats(-20, 20),
    st.floats(-math.pi, math.pi),
    st.sampled_from([0.05, 0.1, 0.3]),
    st.integers(0, 2**32 - 1),
)
def test_continuous_cells_round_trip(
    ox: float, oy: float, yaw: float, res: float, seed: int
) -> None:
    grid = OccupancyGrid(np.zeros((30, 40)), resolution=res, origin=Pose2D(ox, oy, yaw))
    rng = np.random.default_rng(seed)
    continuous = rng.uniform([-5.0, -5.0], [35.0, 45.0], size=(200, 2))
    world = grid.cell_to_world(continuous)
    back = grid.world_to_cell(world, continuous=True)
    assert back.dtype == np.float64
    assert np.allclose(back, continuous, rtol=0.0, atol=1e-9)
    # The cell containing a point is its continuous coordinates rounded half up
    # (away from the boundaries, where either neighbour is right).
    cells = grid.world_to_cell(world)
    ok = np.all(np.abs(continuous - np.floor(continuous) - 0.5) > 1e-6, axis=1)
    assert np.array_equal(cells[ok], np.floor(continuous[ok] + 0.5).astype(np.int64))
    # Integers are cell centres: the old integer-only rule (col + 0.5, row + 0.5) * res.
    ints = np.column_stack((rng.integers(-5, 35, 20), rng.integers(-5, 45, 20)))
    local = (ints[:, ::-1] + 0.5) * res
    assert np.allclose(grid.cell_to_world(ints), grid.origin.transform_points(local))
    # Corners: continuous (i - 0.5, j - 0.5) is the corner (j, i) * res of the grid
    # frame, e.g. a Field D* node; (-0.5, -0.5) is the origin itself.
    assert np.allclose(grid.cell_to_world([-0.5, -0.5]), [ox, oy])
    corner = grid.origin.transform_points([[4 * res, 3 * res]])[0]
    assert np.allclose(grid.cell_to_world([3 - 0.5, 4 - 0.5]), corner)
    assert np.allclose(grid.world_to_cell(corner, continuous=True), [2.5, 3.5])


def test_single_point_shapes() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.5, origin=(1.0, 0.0, 0.0))
    # One point of shape (2,): one answer of shape (2,) (was (1, 2)).
    for point in ([1.6, 0.7], (1.6, 0.7), np.array([1.6, 0.7])):
        cell = grid.world_to_cell(point)
        assert cell.shape == (2,) and cell.dtype == np.int64
        assert cell.tolist() == [1, 1]
        cont = grid.world_to_cell(point, continuous=True)
        assert cont.shape == (2,) and cont.dtype == np.float64
        assert cont == pytest.approx([0.9, 0.7])
        assert grid.contains(point).shape == ()
        assert bool(grid.contains(point))
    assert grid.cell_to_world([1, 1]).shape == (2,)
    assert grid.cell_to_world([1, 1]).tolist() == [1.75, 0.75]
    assert grid.cell_to_world((1.0, 1.0)).tolist() == [1.75, 0.75]
    assert not bool(grid.contains([0.9, 0.7]))
    # (N, 2) input keeps its shape, N = 1 included.
    assert grid.world_to_cell([[1.6, 0.7]]).shape == (1, 2)
    assert grid.world_to_cell([[1.6, 0.7]], continuous=True).shape == (1, 2)
    assert grid.cell_to_world([[1, 1]]).shape == (1, 2)
    assert grid.contains([[1.6, 0.7]]).shape == (1,)
    assert grid.world_to_cell(np.empty((0, 2))).shape == (0, 2)
    assert grid.world_to_cell(np.empty((0, 2)), continuous=True).shape == (0, 2)
    assert grid.cell_to_world(np.empty((0, 2))).shape == (0, 2)
    assert grid.contains(np.empty((0, 2))).shape == (0,)


def test_coordinate_input_validation() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    with pytest.raises(ValueError, match="points_xy must have shape"):
        grid.world_to_cell(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="points_xy must have shape"):
        grid.world_to_cell([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="finite"):
        grid.world_to_cell([[math.nan, 0.0]])
    with pytest.raises(ValueError, match="finite"):
        grid.world_to_cell([math.inf, 0.0], continuous=True)
    with pytest.raises(ValueError, match="points_xy must have shape"):
        grid.contains(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="cells must have shape"):
        grid.cell_to_world(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="cells must contain only finite"):
        grid.cell_to_world([[math.nan, 1.0]])
    # Continuous cells are accepted (they were refused): (0.5, 1.0) is between
    # the centres of cells (0, 1) and (1, 1).
    assert grid.cell_to_world([[0.5, 1.0]]) == pytest.approx(np.array([[0.15, 0.1]]))
    with pytest.raises(TypeError, match="positional"):
        grid.world_to_cell([0.0, 0.0], True)  # type: ignore[call-arg]


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (
            lambda: OccupancyGrid.empty(width=1.0, height=1.0, resolution=-0.1),
            ValueError,
            r"resolution must be >= 1e-6 and <= 1e6 m",
        ),
        (
            lambda: OccupancyGrid.empty(width=0.0, height=1.0, resolution=0.1),
            ValueError,
            "width must be > 0",
        ),
        (
            lambda: OccupancyGrid.empty(
                width=1.0, height=1.0, resolution=0.1, origin=[0, math.nan, 0]
            ),
            ValueError,
            "origin",
        ),
        (lambda: OccupancyGrid(np.zeros(5), resolution=0.1), ValueError, "logodds must be 2-D"),
        (lambda: OccupancyGrid(np.zeros((0, 3)), resolution=0.1), ValueError, "must not be empty"),
        (
            lambda: OccupancyGrid.from_probabilities(np.zeros((0, 0)), resolution=0.1),
            ValueError,
            r"^probabilities must not be empty",
        ),
        (
            lambda: OccupancyGrid(np.zeros((2, 2)), resolution=0.1, free_thresh=0.7),
            ValueError,
            "free_thresh .* must be smaller",
        ),
        (
            lambda: OccupancyGrid.from_occupancy(np.zeros((2, 2)), resolution=0.1),
            TypeError,
            "boolean",
        ),
        (
            lambda: OccupancyGrid.from_probabilities([[0.2, 1.5]], resolution=0.1),
            ValueError,
            r"probabilities must lie in \[0, 1\]",
        ),
        # Swappable floats are keyword-only: the old `empty(0.05, 10, 10)` built a
        # 1 x 1 grid of 10 m cells.
        (lambda: OccupancyGrid.empty(0.05, 10, 10), TypeError, "positional"),
        (lambda: OccupancyGrid(np.zeros((2, 2)), 0.1), TypeError, "positional"),
        (
            lambda: OccupancyGrid.from_occupancy(np.zeros((2, 2), dtype=bool), 0.1),
            TypeError,
            "positional",
        ),
        (lambda: OccupancyGrid.from_probabilities([[0.5]], 0.1), TypeError, "positional"),
        (
            lambda: OccupancyGrid.from_probabilities([[0.5]], resolution=0.1, free_thresh=0.9),
            ValueError,
            "free_thresh .* must be smaller",
        ),
    ],
)
def test_bad_constructor_arguments(call: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        call()  # type: ignore[operator]


def test_views_and_thresholds() -> None:
    p = np.array([[0.0, 0.1, 0.19, 0.2, 0.5, 0.64, 0.66, 0.9, 1.0]])
    grid = OccupancyGrid.from_probabilities(p, resolution=0.1)
    assert grid.occupied().tolist() == [[False] * 6 + [True] * 3]
    assert grid.free().tolist() == [[True] * 3 + [False] * 6]
    assert grid.unknown().tolist() == [[False] * 3 + [True] * 3 + [False] * 3]
    assert grid.occupied(threshold=0.95).sum() == 1
    assert grid.free(threshold=0.5).sum() == 4
    assert np.allclose(grid.probability(), np.clip(p, 1e-3, 1 - 1e-3), atol=1e-6)
    assert grid.unknown(occupied_thresh=0.95, free_thresh=0.5).tolist() == [
        [False] * 4 + [True] * 4 + [False]
    ]
    with pytest.raises(ValueError, match="threshold must lie in"):
        grid.occupied(threshold=1.5)
    with pytest.raises(ValueError, match="free_thresh must lie in"):
        grid.unknown(free_thresh=-0.1)
    with pytest.raises(TypeError, match="positional"):
        grid.unknown(0.95, 0.5)  # type: ignore[call-arg]


def test_from_probabilities_keeps_thresholds() -> None:
    p = np.array([[0.25, 0.5, 0.75]])
    grid = OccupancyGrid.from_probabilities(
        p, resolution=0.1, origin=(1.0, 2.0, 0.5), occupied_thresh=0.7, free_thresh=0.3
    )
    assert (grid.occupied_thresh, grid.free_thresh) == (0.7, 0.3)
    assert grid.origin == Pose2D(1.0, 2.0, 0.5)
    assert grid.occupied().tolist() == [[False, False, True]]
    assert grid.free().tolist() == [[True, False, False]]
    # Probability 0.5 is log-odds exactly 0 (unknown, never observed).
    assert grid.logodds[0, 1] == 0.0


def test_arrays_are_copied_and_read_only() -> None:
    occ = np.zeros((3, 3), dtype=bool)
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1)
    occ[1, 1] = True
    assert not grid.occupied().any()
    with pytest.raises(ValueError):
        grid.logodds[0, 0] = 1.0
    other = grid.copy()
    before = grid.logodds.copy()
    other.integrate_scan(
        LaserScan([0.15], angle_min=0.0, angle_increment=0.1, range_min=0.01, range_max=1.0),
        Pose2D(0.05, 0.05, 0.0),
    )
    assert np.array_equal(grid.logodds, before)
    assert not np.array_equal(other.logodds, before)


def test_copy_module_copies_own_their_log_odds() -> None:
    grid = OccupancyGrid.from_probabilities(
        [[0.2, 0.5, 0.9]], resolution=0.1, origin=(1.0, 2.0, 0.3), occupied_thresh=0.8,
        free_thresh=0.3,
    )  # fmt: skip
    before = grid.logodds.copy()
    scan = LaserScan([0.25], angle_min=0.0, angle_increment=0.1, range_min=0.01, range_max=1.0)
    for other in (copy.copy(grid), copy.deepcopy(grid), pickle.loads(pickle.dumps(grid))):
        assert np.array_equal(other.logodds, before)
        assert (other.resolution, other.origin, other.occupied_thresh, other.free_thresh) == (
            0.1, grid.origin, 0.8, 0.3,
        )  # fmt: skip
        # Ray casting writes into the copy's log-odds, never into the original's.
        assert other.integrate_scan(scan, [*grid.cell_to_world([0, 0]).tolist(), 0.3]) > 0
        assert not np.array_equal(other.logodds, before)
        assert np.array_equal(grid.logodds, before)


def test_from_occupancy_unknown() -> None:
    occ = np.array([[True, False, False]])
    unknown = np.array([[False, False, True]])
    grid = OccupancyGrid.from_occupancy(occ, resolution=1.0, unknown=unknown)
    assert grid.occupied().tolist() == [[True, False, False]]
    assert grid.free().tolist() == [[False, True, False]]
    assert grid.unknown().tolist() == [[False, False, True]]
    with pytest.raises(ValueError, match="must not overlap"):
        OccupancyGrid.from_occupancy(occ, resolution=1.0, unknown=occ)


# ------------------------------------------------------------------ inflation
@settings(max_examples=30, deadline=None)
# 5e-10 m short of 3 cells: outside the radius, and outside the 1e-9-cell slack; a
# slack of 1e-9 m (ten times wider at 0.1 m cells) wrongly expected those cells in.
@example(0, 0.3 - 5e-10)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 0.6))
def test_inflate_matches_brute_force(seed: int, radius: float) -> None:
    rng = np.random.default_rng(seed)
    occ = rng.random((15, 18)) < 0.05
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1)
    mask = grid.inflate(radius)
    obstacles = np.argwhere(occ)
    cells = np.argwhere(np.ones_like(occ))
    if len(obstacles):
        d = np.hypot(*(cells[:, None, :] - obstacles[None, :, :]).transpose(2, 0, 1)).min(axis=1)
        # Within the radius, with inflate's slack of 1e-9 cells (so that a radius of a
        # whole number of cells, as typed, takes the cells at that distance).
        expected = (d <= radius / 0.1 + 1e-9).reshape(occ.shape)
    else:
        expected = np.zeros_like(occ)
    assert np.array_equal(mask, expected)


def test_inflate_exact_multiple_of_resolution() -> None:
    occ = np.zeros((9, 9), dtype=bool)
    occ[4, 4] = True
    mask = OccupancyGrid.from_occupancy(occ, resolution=0.1).inflate(0.3)
    assert mask[4, 1] and mask[4, 7] and not mask[4, 0]
    assert mask.sum() == 29  # lattice points with dx² + dy² <= 9
    with pytest.raises(ValueError, match="robot_radius must be >= 0"):
        OccupancyGrid.from_occupancy(occ, resolution=0.1).inflate(-0.1)


# ---------------------------------------------------------- thin conveniences
def _parameters(function: Callable[..., Any], drop: str) -> list[inspect.Parameter]:
    params = list(inspect.signature(function).parameters.values())
    assert params[0].name == drop
    return params[1:]


@pytest.mark.parametrize(
    ("method", "function"),
    [
        (OccupancyGrid.costmap, mapping.costmap),
        (OccupancyGrid.traversal_costs, mapping.traversal_costs),
        (OccupancyGrid.integrate_scan, mapping.integrate_scan),
        (OccupancyGrid.save, io.write_map),
    ],
)
def test_methods_have_the_signature_of_their_function(
    method: Callable[..., Any], function: Callable[..., Any]
) -> None:
    # Same names, kinds and defaults: the method is the function with the grid bound.
    assert _parameters(method, "self") == _parameters(function, "grid")


def test_classmethods_have_the_signature_of_their_function() -> None:
    assert inspect.signature(OccupancyGrid.from_polygons).parameters == (
        inspect.signature(mapping.rasterize_polygons).parameters
    )
    assert list(inspect.signature(OccupancyGrid.load).parameters) == list(
        inspect.signature(io.read_map).parameters
    )


def test_conveniences_give_the_function_results(tmp_path: Path) -> None:
    occ = np.zeros((6, 8), dtype=bool)
    occ[2, 3] = True
    unknown = np.zeros_like(occ)
    unknown[5, 7] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1, unknown=unknown)
    assert np.array_equal(
        grid.costmap(robot_radius=0.1, inflation_radius=0.3, inflate_unknown=True),
        mapping.costmap(grid, robot_radius=0.1, inflation_radius=0.3, inflate_unknown=True),
    )
    assert np.array_equal(
        grid.traversal_costs(robot_radius=0.1, unknown_cost=2.0),
        mapping.traversal_costs(grid, robot_radius=0.1, unknown_cost=2.0),
    )
    bounds = (0.0, 0.0, 2.0, 1.0)
    a = OccupancyGrid.from_polygons(box(0.2, 0.2, 0.6, 0.4), bounds=bounds, resolution=0.25)
    b = mapping.rasterize_polygons(box(0.2, 0.2, 0.6, 0.4), bounds=bounds, resolution=0.25)
    assert np.array_equal(a.logodds, b.logodds) and a.origin == b.origin
    scan = LaserScan([0.35, 0.5], angle_min=0.0, angle_increment=1.0, range_min=0.1, range_max=1.0)
    by_method, by_function = grid.copy(), grid.copy()
    n_method = by_method.integrate_scan(scan, (0.05, 0.05, 0.0), exact=True)
    n_function = mapping.integrate_scan(by_function, scan, (0.05, 0.05, 0.0), exact=True)
    assert n_method == n_function > 0
    assert np.array_equal(by_method.logodds, by_function.logodds)
    image = grid.save(tmp_path / "m.yaml", mode="scale")
    assert image == tmp_path / "m.png"  # scale maps need alpha for their unknown cells
    loaded = OccupancyGrid.load(tmp_path / "m.yaml")
    assert np.array_equal(loaded.logodds, io.read_map(tmp_path / "m.yaml").logodds)
    assert np.array_equal(loaded.occupied(), grid.occupied())


# ------------------------------------------------------------ issue 12: bad input
def test_complex_and_string_data_are_refused() -> None:
    with pytest.raises(TypeError, match="logodds must hold real numbers"):
        OccupancyGrid(np.ones((2, 2)) * (1 + 1j), resolution=0.1)
    with pytest.raises(TypeError, match="logodds must hold real numbers"):
        OccupancyGrid([["1", "2"]], resolution=0.1)
    with pytest.raises(TypeError, match="probabilities must hold real numbers"):
        OccupancyGrid.from_probabilities([[0.5 + 0j]], resolution=0.1)
    with pytest.raises(TypeError, match="resolution must be a real number"):
        OccupancyGrid(np.zeros((2, 2)), resolution="0.1")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="occupied_thresh must be a real number"):
        OccupancyGrid(np.zeros((2, 2)), resolution=0.1, occupied_thresh=None)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("call", "match"),
    [
        # OverflowError in the issue.
        (
            lambda: OccupancyGrid.empty(width=1e308, height=1e308, resolution=1e-308),
            r"resolution must be >= 1e-6 and <= 1e6 m, got 1e-308",
        ),
        (
            lambda: OccupancyGrid.empty(width=1e308, height=1e308, resolution=1.0),
            r"would need more than 1e308 cells .*the maximum is 2\*\*28 = 268435456 cells",
        ),
        # MemoryError (3.47 EiB) in the issue.
        (
            lambda: OccupancyGrid.empty(width=1e6, height=1e6, resolution=1e-3),
            r"would need 1e\+18 cells \(3\.47 EiB of float32\); the maximum is 2\*\*28",
        ),
        (
            lambda: OccupancyGrid.empty(width=16384.0, height=16384.01, resolution=1.0),
            r"would need 2\.68e\+08 cells",
        ),
        (
            lambda: OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1, origin=(2e9, 0, 0)),
            r"origin x and y must lie within ±1e9 m",
        ),
        (
            lambda: OccupancyGrid(np.full((2, 2), 1e308), resolution=0.1),
            r"logodds must lie within ±1e6",
        ),
        (
            lambda: OccupancyGrid(np.zeros((2, 2)), resolution=1e7),
            r"resolution must be >= 1e-6 and <= 1e6 m",
        ),
        (
            lambda: OccupancyGrid(np.zeros((2, 2)), resolution=0.1, occupied_thresh=1.5),
            r"occupied_thresh must be >= 0 and <= 1",
        ),
        (
            lambda: OccupancyGrid.empty(width=-1.0, height=1.0, resolution=0.1),
            r"width must be > 0 m",
        ),
    ],
)
def test_sizes_and_ranges_are_checked_before_allocating(
    call: Callable[[], object], match: str
) -> None:
    with pytest.raises(ValueError, match=match):
        call()


def test_largest_grid_is_accepted_as_a_shape() -> None:
    # 16384 x 16384 = 2**28 cells is the maximum itself (checked without allocating).
    assert OccupancyGrid.MAX_CELLS == 2**28
    from navkit.mapping._limits import grid_shape

    assert grid_shape(width=16384.0, height=16384.0, resolution=1.0, what="x") == (16384, 16384)


def test_unknown_with_reversed_thresholds_is_an_error() -> None:
    grid = OccupancyGrid.from_probabilities([[0.1, 0.5, 0.9]], resolution=1.0)
    # All False in the issue.
    with pytest.raises(ValueError, match=r"free_thresh \(0\.9\) must be smaller .*swapped"):
        grid.unknown(occupied_thresh=0.1, free_thresh=0.9)
    with pytest.raises(ValueError, match=r"free_thresh .* must be smaller"):
        grid.unknown(free_thresh=0.65)  # equal to the grid's occupied_thresh
    with pytest.raises(TypeError, match="free_thresh must be a real number"):
        grid.unknown(free_thresh="0.1")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="threshold must be a real number"):
        grid.occupied(True)  # type: ignore[arg-type]
    assert grid.unknown(occupied_thresh=0.95, free_thresh=0.05).tolist() == [[True, True, True]]


def test_flags_must_be_bools() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5)
    for value in ("no", 1, None, np.array([True])):
        with pytest.raises(TypeError, match="continuous must be a bool"):
            grid.world_to_cell([0.1, 0.1], continuous=value)  # type: ignore[call-overload]
    assert grid.world_to_cell([0.1, 0.1], continuous=np.True_).tolist() == [-0.3, -0.3]


def test_far_points_and_cells_never_overflow() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1, origin=(1e9, -1e9, 0.7))
    far = np.array([[1e308, -1e308], [-1.7e308, 1.7e308], [1e20, 1e20]])
    cells = grid.world_to_cell(far)
    # Far points stay on their side, clamped to ±2**62: no int64 wrap-around.
    c, s = math.cos(0.7), math.sin(0.7)
    dx, dy = far[:, 0] - 1e9, far[:, 1] + 1e9
    with np.errstate(over="ignore"):
        local = np.column_stack((-s * dx + c * dy, c * dx + s * dy)) / 0.1
    assert np.array_equal(cells, np.clip(np.floor(local), -(2.0**62), 2.0**62).astype(np.int64))
    cont = grid.world_to_cell(far, continuous=True)
    assert np.all(np.isfinite(cont)) and np.all(np.abs(cont) <= 2.0**62)
    assert not grid.contains(far).any()
    assert np.all(np.isfinite(grid.cell_to_world([[2.0**62, -(2.0**62)]])))
    with pytest.raises(ValueError, match=r"cells must lie within ±2\*\*62"):
        grid.cell_to_world([[1e300, 0.0]])


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-1e9, 1e9),
    st.floats(-1e9, 1e9),
    st.floats(-10.0, 10.0),
    st.floats(1e-6, 1e6),
    st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=2, max_size=10),
)
def test_coordinates_are_finite_for_any_finite_input(
    ox: float, oy: float, yaw: float, res: float, values: list[float]
) -> None:
    grid = OccupancyGrid.empty(width=res, height=res, resolution=res, origin=(ox, oy, yaw))
    pts = np.array(values[: len(values) // 2 * 2]).reshape(-1, 2)
    cells = grid.world_to_cell(pts)
    assert cells.dtype == np.int64 and np.all(np.abs(cells) <= 2**62)
    cont = grid.world_to_cell(pts, continuous=True)
    assert np.all(np.isfinite(cont))
    # The cell is the round-half-up of the continuous coordinates (both clamped;
    # up to rounding at a cell boundary).
    assert np.all(np.abs(cells - np.clip(np.floor(cont + 0.5), -(2.0**62), 2.0**62)) <= 1)
    assert np.all(np.isfinite(grid.cell_to_world(np.clip(pts, -(2.0**62), 2.0**62))))
    assert pts.tolist() == np.array(values[: len(values) // 2 * 2]).reshape(-1, 2).tolist()


test_coordinates_are_finite_for_any_finite_input_thoroughly = slow_twin(
    test_coordinates_are_finite_for_any_finite_input, max_examples=100
)
