"""``navkit.mapping.distance_transform``: the banded exact transform of any mask (review 46).

``OccupancyGrid.obstacle_distance`` transforms a grid's occupied cells; the
diff-astar localiser needs the distances to its cells that are not free
(unknown ones too) and, inside them, to the free ones, which it took from
SciPy's whole-grid transform. The public function takes a boolean mask and a
resolution. Oracle: ``scipy.ndimage.distance_transform_edt(~mask) *
resolution``, bit for bit, on every path of the transform (bands of rows, of
columns, one band).
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
from navkit.mapping import OccupancyGrid, distance_transform


@settings(max_examples=200, deadline=None)
@given(
    rows=st.integers(1, 40),
    cols=st.integers(1, 40),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.0, 0.01, 0.1, 0.5, 0.99, 1.0]),
    resolution=st.sampled_from([1e-6, 0.05, 0.1, 0.3, 1.0, 7.3, 1e6]),
    band=st.integers(1, 45),
    wide=st.booleans(),
    order=st.sampled_from(["C", "F", "strided"]),
)
@example(rows=1, cols=37, seed=1, density=0.1, resolution=0.1, band=2, wide=False, order="C")
@example(rows=37, cols=1, seed=1, density=0.1, resolution=0.1, band=2, wide=True, order="C")
@example(rows=1, cols=1, seed=0, density=1.0, resolution=0.1, band=1, wide=False, order="C")
def test_distances_are_scipys_times_the_resolution_bit_for_bit(
    rows: int,
    cols: int,
    seed: int,
    density: float,
    resolution: float,
    band: int,
    wide: bool,
    order: str,
) -> None:
    rng = np.random.default_rng(seed)
    mask = rng.random((rows, 2 * cols if order == "strided" else cols)) < density
    if order == "strided":
        mask = mask[:, ::2]
    elif order == "F":
        mask = np.asfortranarray(mask)
    before = mask.copy()
    with pytest.MonkeyPatch.context() as mp:
        # Small bands, and bands of columns, on small masks: every path of the transform.
        mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        mp.setattr(distance_module, "_BAND_CELLS", 0 if wide else 1 << 21)
        got = distance_transform(mask, resolution=resolution)
    assert got.dtype == np.float64 and got.shape == (rows, cols)
    assert got.flags.c_contiguous and got.flags.writeable
    np.testing.assert_array_equal(mask, before)
    # (inf everywhere for a mask with nothing in it)
    np.testing.assert_array_equal(float_bits(got), float_bits(scipy_distances(mask, resolution)))


@pytest.mark.parametrize("shape", [(1, 1), (1, 9), (9, 1), (6, 7)])
def test_empty_and_full_masks(shape: tuple[int, int]) -> None:
    assert np.isposinf(distance_transform(np.zeros(shape, dtype=bool), resolution=0.1)).all()
    full = distance_transform(np.ones(shape, dtype=bool), resolution=0.1)
    np.testing.assert_array_equal(full, np.zeros(shape))


def test_one_row_and_one_column_are_distances_along_them() -> None:
    row = np.zeros((1, 7), dtype=bool)
    row[0, 2] = True
    assert distance_transform(row, resolution=0.5).tolist() == [[1.0, 0.5, 0.0, 0.5, 1.0, 1.5, 2.0]]
    assert distance_transform(row.T, resolution=0.5).ravel().tolist() == [
        1.0, 0.5, 0.0, 0.5, 1.0, 1.5, 2.0,
    ]  # fmt: skip


def test_a_grid_method_and_the_function_agree() -> None:
    # obstacle_distance is the function applied to the occupied cells.
    rng = np.random.default_rng(5)
    grid = OccupancyGrid.from_occupancy(rng.random((30, 50)) < 0.05, resolution=0.07)
    got = distance_transform(grid.occupied(), resolution=grid.resolution)
    np.testing.assert_array_equal(float_bits(got), float_bits(grid.obstacle_distance()))


def test_a_wide_mask_goes_by_bands_of_columns_and_stays_exact() -> None:
    # 4 x 1.1 M cells: a band of sqrt(rows) rows would be over 2**21 cells.
    mask = np.zeros((4, 1_100_000), dtype=bool)
    mask[1, 7] = mask[3, 600_000] = True
    assert distance_module._by_columns(*mask.shape)
    got = distance_transform(mask, resolution=0.05)
    np.testing.assert_array_equal(float_bits(got), float_bits(scipy_distances(mask, 0.05)))


@pytest.mark.parametrize(
    ("mask", "resolution", "error", "message"),
    [
        (np.zeros((2, 3), dtype=np.int64), 0.1, TypeError, "mask must be a boolean array"),
        ([[0.0, 1.0]], 0.1, TypeError, "mask must be a boolean array"),
        (None, 0.1, TypeError, "mask"),
        ([[True], [True, False]], 0.1, ValueError, "mask must be a rectangular array"),
        (np.zeros(3, dtype=bool), 0.1, ValueError, r"mask must be a non-empty 2-D"),
        (np.zeros((2, 2, 2), dtype=bool), 0.1, ValueError, r"mask must be a non-empty 2-D"),
        (np.zeros((0, 4), dtype=bool), 0.1, ValueError, r"mask must be a non-empty 2-D"),
        (np.ma.masked_array([[True]], mask=[[True]]), 0.1, (TypeError, ValueError), "mask"),
        (np.ones((2, 2), dtype=bool), 0.0, ValueError, "resolution must be >= 1e-6"),
        (np.ones((2, 2), dtype=bool), 2e6, ValueError, "resolution must be"),
        (np.ones((2, 2), dtype=bool), math.nan, ValueError, "resolution"),
        (np.ones((2, 2), dtype=bool), math.inf, ValueError, "resolution"),
        (np.ones((2, 2), dtype=bool), "0.1", TypeError, "resolution"),
        (np.ones((2, 2), dtype=bool), True, TypeError, "resolution"),
    ],
)
def test_bad_input_is_refused_by_name(
    mask: object, resolution: object, error: type, message: str
) -> None:
    with pytest.raises(error, match=message):
        distance_transform(mask, resolution=resolution)  # type: ignore[arg-type]


def test_too_many_cells_are_refused_before_anything_is_allocated() -> None:
    # A broadcast view: 2**28 + 1 cells that take one byte of memory.
    huge = np.broadcast_to(np.array([[True]]), (2**14 + 1, 2**14))
    with pytest.raises(ValueError, match=r"mask would need .* float64\); the maximum is 2\*\*28"):
        distance_transform(huge, resolution=0.1)


def test_resolution_is_keyword_only() -> None:
    # A bare number after the mask could be read as a radius or a threshold.
    with pytest.raises(TypeError, match="positional"):
        distance_transform(np.ones((2, 2), dtype=bool), 0.1)  # type: ignore[misc]


def test_peak_memory_is_the_result_and_a_band() -> None:
    # 2048 x 2048 cells: SciPy's transform of the mask's complement times the
    # resolution peaked at about 29 bytes a cell; the function's result is 8 bytes a
    # cell and one band of 1024 rows of int64 column distances (16 MiB) at a time.
    rows = cols = 2048
    mask = np.random.default_rng(3).random((rows, cols)) < 0.001
    band_cells = distance_module._band_rows(rows, cols) * cols
    peak, got = peak_bytes(lambda: distance_transform(mask, resolution=0.05))
    assert got.shape == (rows, cols)
    assert peak <= 8 * rows * cols + 8 * band_cells + (1 << 20), peak / (rows * cols)
