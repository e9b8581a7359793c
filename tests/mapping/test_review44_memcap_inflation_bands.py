"""Inflation transforms the grid a band of rows at a time (review 44).

``inflate``, ``costmap`` and ``traversal_costs`` took SciPy's exact distance
transform of the whole grid (18 bytes a cell inside SciPy, 8 for the float64
distances): 19, 20 and 20 bytes a cell at their peak, 5 GiB for a map of
``OccupancyGrid.MAX_CELLS`` cells. Only distances up to the inflation radius
matter, so each band of rows is transformed with that many rows of its
neighbours (``obstacle_distance_bands``), and ``traversal_costs`` looks its
costs up in a table of the 256 Nav2 costs: about 2, 3 and 9 bytes a cell and a
band (~40 MiB). The results are the same bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.mapping._obstacle_distance as distance_module
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, costmap, traversal_costs


def _grid(rows: int, cols: int, seed: int, resolution: float = 0.1) -> OccupancyGrid:
    rng = np.random.default_rng(seed)
    kind = rng.choice(3, size=(rows, cols), p=[0.9, 0.05, 0.05])
    return OccupancyGrid.from_occupancy(kind == 1, resolution=resolution, unknown=kind == 2)


@settings(max_examples=40, deadline=None)
@given(
    rows=st.integers(1, 60),
    cols=st.integers(1, 30),
    seed=st.integers(0, 2**32 - 1),
    robot=st.sampled_from([0.0, 0.1, 0.15, 0.3, 1.0]),
    extra=st.sampled_from([0.0, 0.1, 0.25, 0.7, 5.0]),
    band=st.integers(1, 400),
    unknown_cost=st.sampled_from([np.inf, 3.0]),
)
@example(rows=60, cols=1, seed=1, robot=0.3, extra=0.25, band=1, unknown_cost=np.inf)
def test_bands_give_the_whole_grids_inflation(
    rows: int,
    cols: int,
    seed: int,
    robot: float,
    extra: float,
    band: int,
    unknown_cost: float,
) -> None:
    grid = _grid(rows, cols, seed)
    whole = (
        grid.inflate(robot),
        costmap(grid, robot_radius=robot, inflation_radius=robot + extra),
        costmap(grid, robot_radius=robot, inflation_radius=robot + extra, inflate_unknown=True),
        traversal_costs(
            grid, robot_radius=robot, inflation_radius=robot + extra, unknown_cost=unknown_cost
        ),
    )
    reference = distance_module.obstacle_distance(grid.occupied()) <= robot / 0.1 + 1e-9
    assert np.array_equal(whole[0], reference)
    with pytest.MonkeyPatch.context() as mp:
        # Bands of a few rows (review 45: with no halo, whatever the radius).
        mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        banded = (
            grid.inflate(robot),
            costmap(grid, robot_radius=robot, inflation_radius=robot + extra),
            costmap(grid, robot_radius=robot, inflation_radius=robot + extra, inflate_unknown=True),
            traversal_costs(
                grid, robot_radius=robot, inflation_radius=robot + extra, unknown_cost=unknown_cost
            ),
        )
    for a, b in zip(whole, banded, strict=True):
        assert a.dtype == b.dtype and np.array_equal(a, b)


def test_bands_cover_every_row_once_exact() -> None:
    occupied = np.zeros((300, 7), dtype=bool)
    occupied[[0, 150, 299], 3] = True
    whole = distance_module.obstacle_distance(occupied)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(distance_module, "_BAND_CELLS", 100 * 7)
        bands = list(distance_module.obstacle_distance_bands(occupied))
    assert len(bands) > 1
    rows = [(where[0].start, where[0].stop) for where, _ in bands]
    assert [r0 for r0, _ in rows] == [0, *[r1 for _, r1 in rows[:-1]]]
    assert rows[-1][1] == 300
    for where, d in bands:
        assert where[1] == slice(0, 7)
        # Review 45: exact everywhere, not only within a radius.
        assert np.array_equal(d, whole[where])


@pytest.mark.parametrize(
    ("name", "per_cell"),
    [("inflate", 3), ("costmap", 4), ("traversal_costs", 10)],
)
def test_inflation_takes_its_result_and_a_band(name: str, per_cell: int) -> None:
    rows, cols = 3000, 2500
    grid = _grid(rows, cols, 7, resolution=0.05)
    call = {
        "inflate": lambda: grid.inflate(0.3),
        "costmap": lambda: grid.costmap(robot_radius=0.2, inflation_radius=1.0),
        "traversal_costs": lambda: grid.traversal_costs(robot_radius=0.2, inflation_radius=1.0),
    }[name]
    peak, _ = peak_bytes(call)
    cells = rows * cols
    # 19, 20 and 20 bytes a cell before; a band's transform is about 40 MiB.
    assert peak < per_cell * cells + (48 << 20), f"{peak / cells:.2f} bytes a cell"


def test_a_wide_grid_with_a_large_radius_transforms_bands_of_twice_the_radius() -> None:
    # 8192 columns and a 5 m radius at 5 cm (100 cells): a band of 2**21 cells less its
    # halos would have 56 rows, fewer than its halo; bands of 400 rows (600 with their
    # halos: SciPy's 18 bytes a cell, then the indices and distances, 16) instead of
    # the whole grid at once (21 bytes a cell).
    rows, cols = 2400, 8192
    grid = _grid(rows, cols, 8, resolution=0.05)
    peak, _ = peak_bytes(lambda: grid.costmap(robot_radius=0.2, inflation_radius=5.0))
    cells = rows * cols
    assert peak < 3 * cells + 26 * cols * 600 + (8 << 20), f"{peak / cells:.2f} bytes a cell"
