"""write_map's scale-mode image by table look-up: the same bytes as the formula (review 13).

``write_map(grid, path, mode="scale")`` (and ``grid.save``) used to compute
``np.rint(255 * (1 - grid.probability()))`` over the whole grid: a float64
``exp`` per cell and several float64 grids (29 bytes a cell at the peak). The
grey level is a step function of the float32 log-odds with 255 steps; it is now
found by look-up (the table builder grid_to_msg_fields' percentages use),
and the class corrections by a table of the 256 grey levels, over blocks of
cells. These tests hold the image (grey and alpha) to the former code bit for
bit: at every step ± 2 ulps, at special values, over a dense sample of float32
bit patterns, by hypothesis over values and thresholds, and through the written
PNG file. The slow tests check every float32 bit pattern.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from float32_edges import BEYOND_GRID, SPECIAL, ulps
from hypothesis_twins import slow_twin
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files as mf
from navkit.mapping.io import read_map, write_map
from navkit.mapping.io._step_tables import StepLookUp, StepTable

F32 = np.float32
# Thresholds that matter: the defaults; a band excluding p = 0.5 (unknown pixels
# read back as the band's middle); a narrow band (grey rounding crosses it); the
# extremes; thresholds beyond the grid's probability clipping; thresholds that
# are exactly the readings of grey levels (map_server's 1 - v / 255).
THRESHOLDS = [
    {},
    {"occupied_thresh": 0.9, "free_thresh": 0.6},
    {"occupied_thresh": 0.55, "free_thresh": 0.45},
    {"occupied_thresh": 1.0 - 90 / 255.0, "free_thresh": 1.0 - 200 / 255.0},
    {"occupied_thresh": 0.502, "free_thresh": 0.49},
    {"occupied_thresh": 1.0, "free_thresh": 0.0},
    {"occupied_thresh": 0.9999, "free_thresh": 0.0001},
]


# ------------------------------------------------------------------ the oracles


def _formula_grey(logodds: NDArray[np.float32]) -> NDArray[np.uint8]:
    """The former grey level, cell by cell: OccupancyGrid.probability's body, rounded."""
    with np.errstate(over="ignore"):
        p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    return np.asarray(np.rint(255.0 * (1.0 - p)).astype(np.uint8))


def _old_scale_image(grid: OccupancyGrid) -> NDArray[np.uint8]:
    """The former ``_map_pixels(grid, "scale")``, top row first, written out."""
    occ_t, free_t = grid.occupied_thresh, grid.free_thresh
    occupied, free = grid.occupied(), grid.free()
    unknown_l = mf._unknown_logodds(occ_t, free_t)
    transparent = ~occupied & ~free & (grid.logodds == np.float32(unknown_l))
    pixels = np.rint(255.0 * (1.0 - grid.probability())).astype(np.uint8)
    p_px = 1.0 - pixels / 255.0
    pixels[occupied & ~(p_px > occ_t)] = 0
    pixels[free & ~(p_px < free_t)] = 255
    between = ~occupied & ~free & ~transparent & ((p_px > occ_t) | (p_px < free_t))
    if between.any():
        pixels[between] = mf._nearest_unknown_pixels(grid.probability()[between], occ_t, free_t)
    rgba = np.empty((*grid.shape, 4), dtype=np.uint8)
    rgba[..., :3] = pixels[..., None]
    rgba[..., 3] = np.where(transparent, 0, 255)
    return rgba[::-1]


def _looked_up(values: NDArray[np.float32]) -> NDArray[np.uint8]:
    """The grey level by look-up alone, for any float32 (±inf and beyond ±1e6 too)."""
    darkness = np.empty(values.size, dtype=np.uint8)
    StepLookUp(mf._darkness_table(), max(values.size, 1))(values.ravel(), darkness)
    return np.asarray(255 - darkness)


def _image(values: NDArray[np.float32], **thresholds: float) -> NDArray[np.uint8]:
    return mf._map_image(_grid(values, **thresholds), "scale")


def _grid(values: NDArray[np.float32], **thresholds: float) -> OccupancyGrid:
    return OccupancyGrid(values.reshape(1, -1), resolution=1.0, **thresholds)


def _thresholds() -> NDArray[np.float32]:
    return mf._darkness_table().thresholds[:255]


def _assert_as_before(values: NDArray[np.float32], **thresholds: float) -> None:
    """Grey and alpha of a one-row grid of ``values`` as the former code made them."""
    values = values[np.abs(values) <= 1e6]
    grid = _grid(values, **thresholds)
    np.testing.assert_array_equal(mf._map_image(grid, "scale"), _old_scale_image(grid))


# --------------------------------------------------------------- the steps


def test_the_table_is_made_by_the_shared_builder_with_one_comparison() -> None:
    from navkit.mapping.io._ros_msgs import _percent_table

    for table, levels in ((mf._darkness_table(), 255), (_percent_table(), 100)):
        assert isinstance(table, StepTable)
        assert table.thresholds.shape == (levels + 1,) and np.isnan(table.thresholds[-1])
        assert table.base.dtype == np.uint8 and table.rounds == 1
        assert not table.base.flags.writeable and not table.thresholds.flags.writeable


def test_every_step_is_where_the_formula_steps() -> None:
    thresholds = _thresholds()
    assert thresholds.dtype == F32 and np.all(np.diff(thresholds) > 0)
    below = np.nextafter(thresholds, F32(-np.inf))
    # Grey drops to 255 - k exactly at the k-th threshold, not one ulp earlier.
    np.testing.assert_array_equal(_formula_grey(thresholds), 254 - np.arange(255))
    np.testing.assert_array_equal(_formula_grey(below), 255 - np.arange(255))


def test_every_step_plus_minus_two_ulps_matches_the_formula() -> None:
    values = ulps(_thresholds(), 2)
    np.testing.assert_array_equal(_looked_up(values), _formula_grey(values))
    for thresholds in THRESHOLDS:
        _assert_as_before(values, **thresholds)


def test_grey_midpoints_and_class_bounds_match() -> None:
    # Log-odds of the 256 grey readings and the midpoints between them, and of
    # every threshold: where rounding, classes and their corrections change.
    p = np.concatenate([np.arange(1, 255), np.arange(0.5, 255.0, 1.0)]) / 255.0
    bounds = [t for th in THRESHOLDS for t in th.values() if 0.0 < t < 1.0] + [0.65, 0.196]
    p = np.concatenate([p, bounds])
    values = ulps(np.log(p / (1.0 - p)).astype(F32), 2)
    np.testing.assert_array_equal(_looked_up(values), _formula_grey(values))
    for thresholds in THRESHOLDS:
        _assert_as_before(values, **thresholds)


def test_special_values_match() -> None:
    values = ulps(np.array(SPECIAL, dtype=F32), 1)
    np.testing.assert_array_equal(_looked_up(values), _formula_grey(values))
    for thresholds in THRESHOLDS:
        _assert_as_before(values, **thresholds)
    image = _image(np.array([0.0, -0.0, 1e-45, -1e-45], dtype=F32))[0]
    # ±0 (never observed) transparent, the subnormals next to them opaque mid grey.
    assert image[:, 3].tolist() == [0, 0, 255, 255]
    assert image[:, 0].tolist() == [128, 128, 128, 128]


def test_values_no_grid_holds_match_too() -> None:
    values = np.array(BEYOND_GRID, dtype=F32)
    np.testing.assert_array_equal(_looked_up(values), _formula_grey(values))
    assert _looked_up(values).tolist() == [0, 255, 0, 255, 0, 255]


def test_nan_reads_as_an_end() -> None:
    # No grid holds NaN; the look-up still gives a grey level, not garbage.
    values = np.array([np.nan, -np.nan], dtype=F32)
    assert set(_looked_up(values).tolist()) <= {0, 255}


def test_a_dense_sample_of_bit_patterns_matches() -> None:
    # Every 4093rd bit pattern (about a million float32s, all exponents).
    values = np.arange(0, 2**32, 4093, dtype=np.uint64).astype(np.uint32).view(F32)
    values = values[~np.isnan(values)]
    np.testing.assert_array_equal(_looked_up(values), _formula_grey(values))
    for thresholds in THRESHOLDS[:2]:
        _assert_as_before(values, **thresholds)


def test_random_log_odds_of_a_map_match() -> None:
    rng = np.random.default_rng(7)
    values = rng.normal(0.0, 3.0, 1 << 16).astype(F32)
    for thresholds in THRESHOLDS:
        _assert_as_before(values, **thresholds)


@settings(max_examples=100, deadline=None)
@given(
    st.lists(
        st.floats(-1e6, 1e6, width=32) | st.floats(-8.0, 8.0, width=32) | st.just(0.0),
        min_size=1,
        max_size=40,
    ),
    st.floats(0.0, 1.0),
    st.floats(0.0, 1.0),
)
def test_any_grid_and_thresholds_give_the_former_image(
    values: list[float], a: float, b: float
) -> None:
    free_t, occ_t = sorted((a, b))
    if free_t == occ_t:
        return
    logodds = np.array(values, dtype=F32)
    unknown_l = F32(mf._unknown_logodds(occ_t, free_t))
    logodds[::3] = unknown_l  # some cells with the log-odds read_map gives unknown pixels
    grid = _grid(logodds, occupied_thresh=occ_t, free_thresh=free_t)
    try:
        expected = _old_scale_image(grid)
    except ValueError as exc:  # a band holding no grey level, with cells to place in it
        with pytest.raises(ValueError) as raised:
            mf._map_image(grid, "scale")
        assert str(raised.value) == str(exc)
        return
    np.testing.assert_array_equal(mf._map_image(grid, "scale"), expected)


test_any_grid_and_thresholds_give_the_former_image_thoroughly = slow_twin(
    test_any_grid_and_thresholds_give_the_former_image, max_examples=1000
)


# ------------------------------------------------------------- the pipeline


@pytest.mark.parametrize(
    "shape",
    [(1, 1), (1, 3), (301, 251), (3, (1 << 16) + 5), (1, (1 << 17) + 1), ((1 << 16) + 3, 1)],
)
def test_blocks_cover_every_cell_in_image_order(shape: tuple[int, int]) -> None:
    # Grids of one cell, of rows longer than a block (split within a row) and of
    # many blocks of whole rows, none a multiple of the block.
    rng = np.random.default_rng(3)
    logodds = rng.uniform(-8.0, 8.0, shape).astype(F32)
    logodds[rng.random(shape) < 0.3] = 0.0
    grid = OccupancyGrid(logodds, resolution=0.05)
    image = mf._map_image(grid, "scale")
    np.testing.assert_array_equal(image, _old_scale_image(grid))
    assert image.flags.c_contiguous and image.shape == (*shape, 4)
    np.testing.assert_array_equal(image[::-1, :, 3] == 0, logodds == 0.0)


def test_the_file_holds_the_same_bytes(tmp_path: Path) -> None:
    rng = np.random.default_rng(5)
    for i, thresholds in enumerate(THRESHOLDS[:3]):
        logodds = rng.normal(0.0, 3.0, (120, 97)).astype(F32)
        grid = OccupancyGrid(logodds, resolution=0.05, **thresholds)
        # Some cells with the log-odds read_map gives unknown pixels: transparent.
        logodds[rng.random(logodds.shape) < 0.2] = mf._unknown_logodds(
            grid.occupied_thresh, grid.free_thresh
        )
        grid = OccupancyGrid(logodds, resolution=0.05, **thresholds)
        image = write_map(grid, tmp_path / f"map{i}.yaml", mode="scale")
        assert image.read_bytes() == mf.png_bytes(_old_scale_image(grid))
        saved = grid.save(tmp_path / f"saved{i}.yaml", mode="scale")
        assert saved.read_bytes() == image.read_bytes()
        again = read_map(tmp_path / f"map{i}.yaml")
        np.testing.assert_array_equal(again.unknown(), grid.unknown())


def test_a_band_without_grey_levels_is_refused_as_before(tmp_path: Path) -> None:
    # A band narrower than 1/255 with an in-between cell to write: no level to write it as.
    grid = OccupancyGrid(
        np.array([[0.0005]], dtype=F32), resolution=0.1, occupied_thresh=0.5002, free_thresh=0.5
    )
    with pytest.raises(ValueError) as old:
        _old_scale_image(grid)
    with pytest.raises(ValueError, match="leave no 8-bit grey level") as new:
        write_map(grid, tmp_path / "map.yaml", mode="scale")
    assert str(new.value) == str(old.value)
    assert not list(tmp_path.iterdir())


def test_trinary_images_are_unchanged(tmp_path: Path) -> None:
    rng = np.random.default_rng(9)
    logodds = rng.uniform(-8.0, 8.0, (40, 30)).astype(F32)
    logodds[::7] = 0.0
    grid = OccupancyGrid(logodds, resolution=0.05)
    pixels = np.full(grid.shape, 254, dtype=np.uint8)
    pixels[grid.unknown()] = 205
    pixels[grid.occupied()] = 0
    image = write_map(grid, tmp_path / "map.yaml")
    assert image.read_bytes() == mf.pgm_bytes(pixels[::-1])


def test_grid_is_not_modified(tmp_path: Path) -> None:
    rng = np.random.default_rng(4)
    logodds = rng.uniform(-8.0, 8.0, (70, 1000)).astype(F32)
    grid = OccupancyGrid(logodds, resolution=0.05)
    grid.save(tmp_path / "map.yaml", mode="scale")
    np.testing.assert_array_equal(grid.logodds, logodds)


# ---------------------------------------------------------------- the cost


def test_scale_save_holds_the_image_and_little_else(tmp_path: Path) -> None:
    # The former code held float64 probabilities, exp temporaries and a flipped
    # copy of the image: 29 bytes a cell at the peak. Now the RGBA image (4 bytes
    # a cell), the compressed PNG and cache-sized blocks remain.
    rng = np.random.default_rng(6)
    logodds = np.zeros((1000, 1000), dtype=F32)
    logodds[:, :500] = rng.uniform(-8.0, 8.0, (1000, 500)).astype(F32)
    grid = OccupancyGrid(logodds, resolution=0.05)
    peak, image = peak_bytes(lambda: grid.save(tmp_path / "map.yaml", mode="scale"))
    assert peak / grid.logodds.size < 8.0
    assert image.stat().st_size > 0


# ------------------------------------------------------ every float32 (slow)


def _chunks(bits: int = 24) -> Iterator[NDArray[np.float32]]:
    """All 2**32 float32 bit patterns, NaNs left out, in chunks of 2**bits."""
    for start in range(0, 1 << 32, 1 << bits):
        values = np.arange(start, start + (1 << bits), dtype=np.uint64)
        values = values.astype(np.uint32).view(F32)
        yield values[~np.isnan(values)]


@pytest.mark.slow
def test_every_float32_gets_the_formulas_grey_and_percentage() -> None:
    # Both tables of the shared builder: write_map's grey, grid_to_msg_fields' percentage.
    from navkit.mapping.io._ros_msgs import _percent_table

    size = 1 << 24
    grey_of = StepLookUp(mf._darkness_table(), size)
    percent_of = StepLookUp(_percent_table(), size)
    darkness = np.empty(size, dtype=np.uint8)
    percent = np.empty(size, dtype=np.uint8)
    for values in _chunks():
        m = values.size
        with np.errstate(over="ignore"):
            p = 1.0 / (1.0 + np.exp(-values.astype(np.float64)))
        grey_of(values, darkness[:m])
        percent_of(values, percent[:m])
        np.testing.assert_array_equal(255 - darkness[:m], np.rint(255.0 * (1.0 - p)))
        np.testing.assert_array_equal(percent[:m], np.rint(p * 100.0))


@pytest.mark.slow
@pytest.mark.parametrize("thresholds", THRESHOLDS[:2], ids=["default", "band-above-half"])
def test_every_float32_a_grid_holds_gets_the_former_pixel(thresholds: dict[str, float]) -> None:
    for values in _chunks():
        values = values[np.abs(values) <= 1e6]
        if not values.size:  # exponents beyond the grid's range
            continue
        grid = OccupancyGrid(values.reshape(1, -1), resolution=1.0, **thresholds)
        np.testing.assert_array_equal(mf._map_image(grid, "scale"), _old_scale_image(grid))
