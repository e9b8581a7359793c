"""``OccupancyGrid.obstacle_distance``: the distance to obstacles as a public method (review 45).

``RegulatedPurePursuit(clearance=grid)`` and the demo scenario each ran
SciPy's Euclidean distance transform on the whole grid themselves (34 bytes
a cell at their peak), as they may not import mapping's private banded
transform. The method gives them, and users, the distances ``inflate``,
``costmap`` and ``traversal_costs`` grow obstacles by. Oracle: SciPy's
``distance_transform_edt(~occupied) * resolution`` bit for bit, and ``inf``
everywhere when nothing is occupied (what each caller did: SciPy has no
answer there).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.mapping._obstacle_distance as distance_module
from edt_oracle import float_bits, scipy_distances
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid

# Log-odds on either side of the default occupied_thresh (0.65, log-odds 0.619)
# and of the thresholds drawn below, unknown (0) and the extremes.
_LOGODDS = [-1e6, -2.0, 0.0, 0.4054651, 0.6190392, 0.62, 0.85, 2.0, 1e6]


@settings(max_examples=200, deadline=None)
@given(
    rows=st.integers(1, 40),
    cols=st.integers(1, 40),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.0, 0.01, 0.1, 0.5, 1.0]),
    resolution=st.sampled_from([1e-6, 0.05, 0.1, 0.3, 1.0, 7.3, 1e6]),
    threshold=st.one_of(st.none(), st.sampled_from([0.0, 0.5, 0.6, 0.65, 0.9, 1.0])),
    band=st.integers(1, 45),
    wide=st.booleans(),
)
@example(rows=5, cols=7, seed=0, density=0.0, resolution=0.1, threshold=None, band=2, wide=False)
@example(rows=5, cols=7, seed=0, density=1.0, resolution=0.1, threshold=None, band=2, wide=True)
def test_distances_are_scipys_times_the_resolution_bit_for_bit(
    rows: int,
    cols: int,
    seed: int,
    density: float,
    resolution: float,
    threshold: float | None,
    band: int,
    wide: bool,
) -> None:
    rng = np.random.default_rng(seed)
    logodds = rng.choice(_LOGODDS, size=(rows, cols)).astype(np.float32)
    # density 0: nothing occupied (at the default threshold); 1: every cell.
    logodds[rng.random((rows, cols)) >= density] = -2.0
    logodds[rng.random((rows, cols)) < density * (density >= 1.0)] = 1e6
    grid = OccupancyGrid(logodds, resolution=resolution)
    before = grid.logodds.copy()
    with pytest.MonkeyPatch.context() as mp:
        # Small bands, and bands of columns, on small grids: every path of the transform.
        mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        mp.setattr(distance_module, "_BAND_CELLS", 0 if wide else 1 << 21)
        got = grid.obstacle_distance(occupied_thresh=threshold)
    want = scipy_distances(grid.occupied(threshold), resolution)
    assert got.dtype == np.float64 and got.shape == (rows, cols)
    np.testing.assert_array_equal(float_bits(got), float_bits(want))
    np.testing.assert_array_equal(grid.logodds, before)


def test_no_obstacle_is_inf_everywhere_and_every_obstacle_zero() -> None:
    empty = OccupancyGrid.empty(width=0.5, height=0.3, resolution=0.1)  # all unknown
    assert np.isposinf(empty.obstacle_distance()).all()
    # Unknown cells (p = 0.5) are obstacles once the threshold is below 0.5.
    np.testing.assert_array_equal(empty.obstacle_distance(occupied_thresh=0.4), np.zeros((3, 5)))
    full = OccupancyGrid.from_occupancy(np.ones((3, 5), dtype=bool), resolution=0.1)
    np.testing.assert_array_equal(full.obstacle_distance(), np.zeros((3, 5)))
    # p > 1 holds nowhere: no cell is occupied at occupied_thresh=1.
    assert np.isposinf(full.obstacle_distance(occupied_thresh=1.0)).all()


def test_the_threshold_chooses_the_obstacles_as_occupied_does() -> None:
    grid = OccupancyGrid.from_probabilities([[0.6, 0.1, 0.1, 0.9]], resolution=0.25)
    assert grid.obstacle_distance().tolist() == [[0.75, 0.5, 0.25, 0.0]]
    assert grid.obstacle_distance(occupied_thresh=0.5).tolist() == [[0.0, 0.25, 0.25, 0.0]]
    # Diagonals: sqrt(dy**2 + dx**2) cells, then times the resolution.
    occ = np.zeros((3, 3), dtype=bool)
    occ[0, 0] = True
    got = OccupancyGrid.from_occupancy(occ, resolution=0.5).obstacle_distance()
    assert got[2, 2] == math.sqrt(8.0) * 0.5 and got[1, 2] == math.sqrt(5.0) * 0.5


@pytest.mark.parametrize(
    ("value", "error", "message"),
    [
        ("0.5", TypeError, "occupied_thresh"),
        (True, TypeError, "occupied_thresh"),
        (1.5, ValueError, r"occupied_thresh must lie in \[0, 1\], got 1.5"),
        (-0.1, ValueError, r"occupied_thresh must lie in \[0, 1\]"),
        (math.nan, ValueError, "occupied_thresh"),
        (math.inf, ValueError, "occupied_thresh"),
    ],
)
def test_a_bad_threshold_is_refused_by_name(value: object, error: type, message: str) -> None:
    grid = OccupancyGrid.empty(width=0.5, height=0.3, resolution=0.1)
    with pytest.raises(error, match=message):
        grid.obstacle_distance(occupied_thresh=value)  # type: ignore[arg-type]


def test_the_threshold_is_keyword_only() -> None:
    # A bare number would read as a distance: grid.obstacle_distance(0.5).
    grid = OccupancyGrid.empty(width=0.5, height=0.3, resolution=0.1)
    with pytest.raises(TypeError, match="positional"):
        grid.obstacle_distance(0.5)  # type: ignore[call-arg]


def test_each_call_returns_a_new_array_of_its_own() -> None:
    occ = np.zeros((4, 6), dtype=bool)
    occ[1, 2] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1)
    first = grid.obstacle_distance()
    first[:] = -1.0
    second = grid.obstacle_distance()
    assert second[1, 2] == 0.0 and second.flags.writeable and second.flags.c_contiguous
    assert not np.shares_memory(second, grid.logodds)


def test_peak_memory_is_the_result_the_mask_and_a_band() -> None:
    # 2048 x 2048 cells: SciPy's transform with the mask and the product peaked at
    # 34 bytes a cell (136 MiB); now 8 (result) + 1 (mask) and a band of 1024 rows
    # of int64 column distances (16 MiB): 52 MiB measured.
    rows = cols = 2048
    rng = np.random.default_rng(3)
    grid = OccupancyGrid.from_occupancy(rng.random((rows, cols)) < 0.001, resolution=0.05)
    band_cells = distance_module._band_rows(rows, cols) * cols
    peak, got = peak_bytes(grid.obstacle_distance)
    assert got.shape == (rows, cols)
    assert peak <= 9 * rows * cols + 8 * band_cells + (1 << 20), peak / (rows * cols)
