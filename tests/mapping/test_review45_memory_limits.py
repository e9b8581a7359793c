"""Inflation's memory whatever the radius (review 45).

``inflate``, ``costmap`` and ``traversal_costs`` transformed the grid a band
of rows at a time with ``ceil(radius / resolution)`` rows of its neighbours
on either side (review 44), and the whole grid at once (SciPy's 18 bytes a
cell: 20 to 21 at their peak, 5 GiB for ``OccupancyGrid.MAX_CELLS``) once the
radius reached about a quarter of the grid's rows, or on a grid of fewer
than 64 rows. The bands are now exact with no halo
(``navkit.mapping._edt_kernels``: the nearest occupied cell above and below
each column is carried from band to band), so the peak is the result and a
band at any radius; a grid much wider than tall is transformed by bands of
columns. Oracle: :func:`scipy.ndimage.distance_transform_edt` of the whole
grid, the distances every earlier version used, bit for bit.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.mapping._costs as costs_module
import navkit.mapping._grid as grid_module
import navkit.mapping._obstacle_distance as distance_module
from edt_oracle import float_bits, scipy_distances
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, costmap, traversal_costs


def _whole_grid(occupied: np.ndarray) -> Iterator[tuple[tuple[slice, slice], np.ndarray]]:
    """One band, the whole grid, SciPy's distances: what a radius of a quarter of the rows took."""
    yield (slice(None), slice(None)), scipy_distances(occupied)


def assert_bands_change_nothing(calls: Callable[[], list[np.ndarray]], band: int) -> None:
    """``calls()`` gives the same arrays on SciPy's whole grid and on bands of ``band`` rows."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(costs_module, "obstacle_distance_bands", _whole_grid)
        mp.setattr(grid_module, "obstacle_distance_bands", _whole_grid)
        whole = calls()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        banded = calls()
    for a, b in zip(whole, banded, strict=True):
        assert a.dtype == b.dtype and np.array_equal(a, b)


def _occupied(rows: int, cols: int, seed: int, density: float, band: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    occupied = rng.random((rows, cols)) < density
    # Obstacles on the rows and columns either side of the bands' edges.
    for edge in range(band, max(rows, cols), band):
        for at in (edge - 1, edge):
            if at < rows:
                occupied[at, rng.integers(cols)] = True
            if at < cols:
                occupied[rng.integers(rows), at] = True
    return occupied


@settings(max_examples=300, deadline=None)
@given(
    rows=st.integers(1, 50),
    cols=st.integers(1, 50),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.0, 0.002, 0.02, 0.2, 0.9]),
    band=st.integers(1, 60),
    wide=st.booleans(),
)
@example(rows=40, cols=3, seed=0, density=0.0, band=7, wide=False)  # edges only
@example(rows=2, cols=50, seed=1, density=0.0, band=3, wide=True)  # by columns
def test_bands_are_scipys_distances_bit_for_bit(
    rows: int, cols: int, seed: int, density: float, band: int, wide: bool
) -> None:
    occupied = _occupied(rows, cols, seed, density, band)
    kept = occupied.copy()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        # A band budget of one cell: a grid wider than tall goes by bands of columns.
        mp.setattr(distance_module, "_BAND_CELLS", 0 if wide else 1 << 21)
        bands = list(distance_module.obstacle_distance_bands(occupied))
    seen = np.zeros(occupied.shape, dtype=np.int64)
    want = scipy_distances(occupied)
    for where, dist in bands:
        seen[where] += 1
        assert dist.dtype == np.float64
        assert np.array_equal(float_bits(dist), float_bits(want[where]))
    assert (seen == 1).all()
    assert np.array_equal(occupied, kept)


@settings(max_examples=60, deadline=None)
@given(
    rows=st.integers(1, 40),
    cols=st.integers(1, 40),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.0, 0.01, 0.05, 0.3]),
    band=st.integers(1, 12),
    robot=st.sampled_from([0.0, 0.1, 0.25, 0.5, 1.0, 3.0]),
    extra=st.sampled_from([0.0, 0.1, 0.75, 1.5, 4.0, 100.0]),
)
# A radius of a quarter, a half and all of the rows, obstacles at the bands' edges.
@example(rows=40, cols=20, seed=3, density=0.01, band=4, robot=1.0, extra=0.0)
@example(rows=40, cols=20, seed=4, density=0.01, band=5, robot=0.5, extra=1.5)
@example(rows=40, cols=40, seed=5, density=0.0, band=7, robot=3.0, extra=100.0)
def test_inflation_at_any_radius_is_the_whole_grids_bit_for_bit(
    rows: int, cols: int, seed: int, density: float, band: int, robot: float, extra: float
) -> None:
    kind = np.random.default_rng(seed).choice(3, size=(rows, cols), p=[0.8, 0.1, 0.1])
    occupied = _occupied(rows, cols, seed, density, band) | (kind == 1)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=(kind == 2) & ~occupied)

    def calls() -> list[np.ndarray]:
        infl = robot + extra
        return [
            grid.inflate(robot),
            grid.inflate(infl),
            costmap(grid, robot_radius=robot, inflation_radius=infl),
            costmap(grid, robot_radius=robot, inflation_radius=infl, inflate_unknown=True),
            traversal_costs(grid, robot_radius=robot, inflation_radius=infl),
            traversal_costs(grid, robot_radius=robot, inflation_radius=infl, unknown_cost=3.0),
        ]

    assert_bands_change_nothing(calls, band)


def _grid(rows: int, cols: int) -> OccupancyGrid:
    kind = np.random.default_rng(45).choice(3, size=(rows, cols), p=[0.98, 0.01, 0.01])
    return OccupancyGrid.from_occupancy(kind == 1, resolution=0.05, unknown=kind == 2)


_CALLS = {
    "inflate": lambda grid, radius: grid.inflate(radius),
    "costmap": lambda grid, radius: grid.costmap(robot_radius=0.2, inflation_radius=radius),
    "traversal_costs": lambda grid, radius: grid.traversal_costs(
        robot_radius=0.2, inflation_radius=radius
    ),
}


@pytest.mark.parametrize(
    ("name", "per_cell"), [("inflate", 3), ("costmap", 4), ("traversal_costs", 10)]
)
@pytest.mark.parametrize("radius", [1.0, 40.0, 150.0])
def test_any_radius_takes_the_result_and_a_band(name: str, per_cell: int, radius: float) -> None:
    # 3000 rows at 5 cm: 20 cells, a quarter of the rows (800 cells) and all of them.
    # Before: 5, 6 and 9 bytes a cell at 1 m; 20, 21 and 21 at 40 and 150 m.
    rows, cols = 3000, 2500
    grid = _grid(rows, cols)
    peak, _ = peak_bytes(lambda: _CALLS[name](grid, radius))
    assert peak < per_cell * rows * cols + (56 << 20), f"{peak / (rows * cols):.2f} bytes a cell"


@pytest.mark.parametrize("name", sorted(_CALLS))
def test_a_grid_much_wider_than_tall_goes_by_bands_of_columns(name: str) -> None:
    # 16 rows: fewer than one band's 64, so the whole grid at once before (20 to
    # 21 bytes a cell); bands of columns of its transpose (a 1-byte copy) now.
    rows, cols = 16, 1 << 20
    grid = _grid(rows, cols)
    per_cell = {"inflate": 4, "costmap": 5, "traversal_costs": 11}[name]
    peak, _ = peak_bytes(lambda: _CALLS[name](grid, 0.5))
    assert peak < per_cell * rows * cols + (64 << 20), f"{peak / (rows * cols):.2f} bytes a cell"
