"""LocalGrid: the robot-centred grid, with OccupancyGrid's conversion names."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan, LocalGrid


def test_turtlebot3_local_grid_indexing() -> None:
    # Eight beams 45° apart from -π; known returns, the rest +inf (nothing in range).
    r = math.inf
    ranges = [r, r, 0.7, r, 0.5, 0.4, 1.3, math.sqrt(2.0)]
    scan = LaserScan(
        ranges, angle_min=-math.pi, angle_increment=math.pi / 4, range_min=0.05, range_max=3.5
    )
    grid = scan.to_local_grid()
    assert grid.occupied.shape == (21, 21)
    expected = {
        (math.floor(10 * y + 10 + 0.5), math.floor(10 * x + 10 + 0.5))  # i = 10y+10, j = 10x+10
        for x, y in scan.to_points()
        if abs(x) <= 1.05 and abs(y) <= 1.05
    }
    got = {(int(i), int(j)) for i, j in np.argwhere(grid.occupied)}
    assert got == expected
    # (0.5, 0) ahead, (0, -0.7) right, (-1, 1) back-left corner, (0.28, 0.28) diagonal;
    # the return 1.3 m to the left is outside the ±1 m grid.
    assert got == {(10, 15), (3, 10), (20, 0), (13, 13)}


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.1, 3.0),
    st.sampled_from([0.05, 0.1, 0.2, 0.25]),
    st.lists(st.tuples(st.floats(-4, 4), st.floats(-4, 4)), max_size=20),
)
def test_local_grid_any_size(
    half_width: float, resolution: float, points: list[tuple[float, float]]
) -> None:
    grid = LocalGrid.from_points(
        np.array(points).reshape(-1, 2), half_width=half_width, resolution=resolution
    )
    ratio = half_width / resolution
    # Half up, a ratio within 1e-9 cells of a half counting as a half (as documented:
    # 0.15 / 0.1 is 1.4999999999999998 and must round up).
    n = 2 * (math.floor(ratio) + (ratio - math.floor(ratio) >= 0.5 - 1e-9)) + 1
    assert grid.occupied.shape == (n, n)
    assert grid.half_width == pytest.approx((n - 1) / 2 * resolution)
    cells = grid.world_to_cell(np.array(points).reshape(-1, 2))
    inside = grid.contains(np.array(points).reshape(-1, 2))
    assert np.array_equal(inside, np.all((cells >= 0) & (cells < n), axis=1))
    assert grid.occupied.sum() == len({tuple(c) for c in cells[inside]})
    if inside.any():
        centres = grid.cell_to_world(cells[inside])
        assert np.all(np.abs(centres - np.array(points)[inside]) <= resolution / 2 + 1e-9)
    assert np.array_equal(grid.cell_to_world([[n // 2, n // 2]]), [[0.0, 0.0]])
    assert np.array_equal(grid.cell_to_world([n // 2, n // 2]), [0.0, 0.0])


def test_local_grid_validation() -> None:
    with pytest.raises(ValueError, match="n odd"):
        LocalGrid(np.zeros((4, 4), dtype=bool), resolution=0.1, half_width=0.15)
    with pytest.raises(ValueError, match="half_width must be"):
        LocalGrid(np.zeros((21, 21), dtype=bool), resolution=0.1, half_width=1.5)
    with pytest.raises(TypeError, match="boolean"):
        LocalGrid(np.zeros((3, 3)), resolution=0.1, half_width=0.1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6 and <= 1e6 m"):
        LocalGrid.from_points([[0.0, 0.0]], half_width=1.0, resolution=-0.1)
    with pytest.raises(ValueError, match="points_xy must have shape"):
        LocalGrid.from_points([[0.0, 0.0, 0.0]])
    grid = LocalGrid.from_points([], half_width=1.0, resolution=0.1)
    with pytest.raises(ValueError, match="points_xy must have shape"):
        grid.world_to_cell(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="cells must contain only finite"):
        grid.cell_to_world([math.nan, 1.0])
    # resolution and half_width (two floats) are keyword-only.
    with pytest.raises(TypeError, match="positional"):
        LocalGrid(np.zeros((3, 3), dtype=bool), 0.1, 0.1)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="positional"):
        LocalGrid.from_points([], 1.0, 0.1)  # type: ignore[call-arg]


def test_local_grid_is_frozen_and_copies() -> None:
    occ = np.zeros((3, 3), dtype=bool)
    grid = LocalGrid(occ, resolution=0.5, half_width=0.5)
    occ[1, 1] = True
    assert not grid.occupied.any()
    with pytest.raises(ValueError, match="read-only"):
        grid.occupied[0, 0] = True
    with pytest.raises(dataclasses.FrozenInstanceError):
        grid.resolution = 1.0  # type: ignore[misc]


def test_local_grid_conversions_have_occupancy_grid_names() -> None:
    grid = LocalGrid.from_points([], half_width=1.0, resolution=0.1)
    assert not hasattr(grid, "point_to_cell") and not hasattr(grid, "cell_to_point")
    # The paper's i = 10 y + 10, j = 10 x + 10 (round half up), in the robot frame.
    assert grid.world_to_cell([[0.5, -0.2], [0.05, 0.05]]).tolist() == [[8, 15], [11, 11]]
    assert grid.world_to_cell([[-0.04, -0.06]]).tolist() == [[9, 10]]
    assert grid.cell_to_world([[8, 15], [10, 10]]) == pytest.approx(
        np.array([[0.5, -0.2], [0.0, 0.0]])
    )


def test_local_grid_single_point_shapes() -> None:
    grid = LocalGrid.from_points([], half_width=1.0, resolution=0.1)
    cell = grid.world_to_cell([0.5, -0.2])
    assert cell.shape == (2,) and cell.dtype == np.int64 and cell.tolist() == [8, 15]
    assert grid.world_to_cell([[0.5, -0.2]]).shape == (1, 2)
    assert grid.world_to_cell([0.5, -0.2], continuous=True).shape == (2,)
    assert grid.cell_to_world([8, 15]).shape == (2,)
    assert grid.cell_to_world([[8, 15]]).shape == (1, 2)
    assert grid.contains([0.5, -0.2]).shape == () and bool(grid.contains([0.5, -0.2]))
    assert not bool(grid.contains((1.2, 0.0)))
    assert grid.contains([[0.5, -0.2]]).shape == (1,)
    assert grid.world_to_cell(np.empty((0, 2))).shape == (0, 2)


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.1, 3.0),
    st.sampled_from([0.05, 0.1, 0.2, 0.25]),
    st.lists(st.tuples(st.floats(-40, 40), st.floats(-40, 40)), min_size=1, max_size=20),
)
def test_local_grid_continuous_round_trip(
    half_width: float, resolution: float, cells: list[tuple[float, float]]
) -> None:
    # Continuous coordinates put integers at cell centres, as on OccupancyGrid; the
    # cell of a point is its continuous coordinates rounded half up.
    grid = LocalGrid.from_points([], half_width=half_width, resolution=resolution)
    continuous = np.array(cells)
    points = grid.cell_to_world(continuous)
    back = grid.world_to_cell(points, continuous=True)
    assert np.allclose(back, continuous, rtol=0.0, atol=1e-9)
    ok = np.all(np.abs(continuous - np.floor(continuous) - 0.5) > 1e-6, axis=1)
    expected = np.floor(continuous[ok] + 0.5).astype(np.int64)
    assert np.array_equal(grid.world_to_cell(points)[ok], expected)
    # Half a cell from the robot's cell centre is the boundary: continuous ±0.5.
    centre = grid.size // 2
    edge = grid.world_to_cell([resolution / 2, -resolution / 2], continuous=True)
    assert edge == pytest.approx([centre - 0.5, centre + 0.5])


# ------------------------------------------------------------ issue 12: bad input
def test_local_grid_from_lists_copies_and_never_freezes_the_callers_array() -> None:
    rows = [[False, False, False], [False, True, False], [False, False, False]]
    grid = LocalGrid(rows, resolution=0.5, half_width=0.5)  # type: ignore[arg-type]
    rows[1][1] = False
    assert grid.occupied[1, 1] and not grid.occupied.flags.writeable
    mine = np.zeros((3, 3), dtype=bool)
    LocalGrid(mine, resolution=0.5, half_width=0.5)
    assert mine.flags.writeable


@pytest.mark.parametrize(
    ("half_width", "resolution", "size"),
    [(0.5, 1.0, 3), (1.5, 1.0, 5), (2.5, 1.0, 7), (3.5, 1.0, 9), (0.25, 0.5, 3), (0.25, 0.1, 7)],
)
def test_half_width_snaps_half_up(half_width: float, resolution: float, size: int) -> None:
    # Halfway between two multiples of the resolution rounds up, as cells do; round()
    # went to even: 1.5 and 2.5 cells both gave 5 cells a side, half a cell gave 1.
    grid = LocalGrid.from_points([[0.0, half_width]], half_width=half_width, resolution=resolution)
    assert grid.size == size
    assert grid.half_width == (size - 1) // 2 * resolution
    assert grid.occupied[size - 1, size // 2] and grid.occupied.sum() == 1


def test_copied_and_unpickled_grids_stay_read_only(
    duplicate: Callable[[LocalGrid], LocalGrid],
) -> None:
    # pickle and deepcopy rebuild the fields without __post_init__; the copied
    # array used to come back writable, so the "frozen" grid could change.
    grid = LocalGrid.from_points([[0.1, 0.0]], half_width=0.2, resolution=0.1)
    twin = duplicate(grid)
    with pytest.raises(ValueError, match="read-only"):
        twin.occupied[0, 0] = True
    np.testing.assert_array_equal(twin.occupied, grid.occupied)
    assert (twin.resolution, twin.half_width) == (grid.resolution, grid.half_width)


def test_local_grid_size_is_checked_before_allocating() -> None:
    with pytest.raises(ValueError, match=r"would need 4e\+14 cells .*maximum is 2\*\*28"):
        LocalGrid.from_points([], half_width=1e4, resolution=1e-3)
    with pytest.raises(ValueError, match=r"half_width must be >= 0 and <= 1e6 m"):
        LocalGrid.from_points([], half_width=1e308, resolution=1.0)
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6"):
        LocalGrid.from_points([], half_width=1.0, resolution=5e-324)
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6"):
        LocalGrid(np.zeros((3, 3), dtype=bool), resolution=1e-308, half_width=1e-308)
    # The largest allowed grid is 16383 cells a side; one more cell a side is refused.
    with pytest.raises(ValueError, match="would need"):
        LocalGrid.from_points([], half_width=8192.0, resolution=1.0)


def test_local_grid_far_points_and_cells() -> None:
    grid = LocalGrid.from_points([[1e308, -1e308], [0.0, 0.0]], half_width=0.2, resolution=0.1)
    assert grid.occupied.sum() == 1 and grid.occupied[2, 2]
    far = grid.world_to_cell([[1e308, -1e308], [-1e308, 1e308]])
    assert far.tolist() == [[-(2**62), 2**62], [2**62, -(2**62)]]
    cont = grid.world_to_cell([1e308, -1e308], continuous=True)
    assert np.all(np.isfinite(cont)) and cont.tolist() == [-(2.0**62), 2.0**62]
    assert not grid.contains([[1e308, 0.0]]).any()
    assert np.all(np.isfinite(grid.cell_to_world([[2.0**62, -(2.0**62)]])))
    with pytest.raises(ValueError, match=r"cells must lie within ±2\*\*62"):
        grid.cell_to_world([1e300, 0.0])
    with pytest.raises(TypeError, match="continuous must be a bool"):
        grid.world_to_cell([0.0, 0.0], continuous="yes")  # type: ignore[call-overload]
    with pytest.raises(TypeError, match="points_xy must hold real numbers"):
        grid.world_to_cell([1 + 1j, 0.0])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=2, max_size=8))
def test_local_grid_any_finite_points(values: list[float]) -> None:
    pts = np.array(values[: len(values) // 2 * 2]).reshape(-1, 2)
    grid = LocalGrid.from_points(pts, half_width=0.5, resolution=0.1)
    cells = grid.world_to_cell(pts)
    assert np.all(np.abs(cells) <= 2**62)
    assert np.all(np.isfinite(grid.world_to_cell(pts, continuous=True)))
    inside = grid.contains(pts)
    assert grid.occupied.sum() == len({tuple(c) for c in cells[inside].tolist()})
