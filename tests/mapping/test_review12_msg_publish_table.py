"""grid_to_msg_fields' scale mode by table look-up: the same int8s as the formula (review 12).

A ROS node publishing /map converts the whole grid each time. Mode "scale" used
to compute ``np.rint(grid.probability() * 100.0).astype(np.int8)``: a float64
``exp`` per cell and float64 grids of 8 bytes a cell (16 bytes a cell at the
peak). The percentage is a step function of the float32 log-odds with 100
steps; the message now finds each cell's step by look-up. These tests hold it to
the old formula bit for bit: at every step ± 2 ulps, at special values, over
random float32 bit patterns and by hypothesis, and through the whole pipeline
(-1 for unknown cells, trinary mode, a map whose unknown band excludes p = 0.5).
All 2**32 float32 bit patterns were checked once outside the suite.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from float32_edges import BEYOND_GRID, SPECIAL, ulps
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_to_msg_fields, read_map
from navkit.mapping.io._map_files import pgm_bytes

F32 = np.float32


def _formula(logodds: NDArray[np.float32]) -> NDArray[np.int8]:
    """The former scale mode, cell by cell: OccupancyGrid.probability's body, rounded."""
    with np.errstate(over="ignore"):
        p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    return np.asarray(np.rint(p * 100.0).astype(np.int8))


def _old_scale_data(grid: OccupancyGrid) -> NDArray[np.int8]:
    """The former grid_to_msg_fields(grid).data of mode "scale", written out."""
    from navkit.mapping.io._map_files import _unknown_logodds

    data = np.rint(grid.probability() * 100.0).astype(np.int8)
    logodds = grid.logodds
    unknown = logodds == 0.0
    unknown_l = np.float32(_unknown_logodds(grid.occupied_thresh, grid.free_thresh))
    if unknown_l != 0.0:
        unknown |= (logodds == unknown_l) & grid.unknown()
    data[unknown] = -1
    return np.asarray(data.ravel())


def _published(values: NDArray[np.float32]) -> NDArray[np.int8]:
    """grid_to_msg_fields' data for a one-row grid of ``values`` (within the grid's range)."""
    return grid_to_msg_fields(OccupancyGrid(values.reshape(1, -1), resolution=1.0)).data


def _looked_up(values: NDArray[np.float32]) -> NDArray[np.int8]:
    """The look-up alone, for any float32 (also those no grid holds: ±inf, beyond ±1e6)."""
    from navkit.mapping.io._ros_msgs import _scale_data

    return _scale_data(values, [])


def _thresholds() -> NDArray[np.float32]:
    from navkit.mapping.io._ros_msgs import _percent_table

    return _percent_table()[1][:100]


# --------------------------------------------------------------- the steps


def test_every_step_is_where_the_formula_steps() -> None:
    thresholds = _thresholds()
    assert thresholds.dtype == F32 and np.all(np.diff(thresholds) > 0)
    below = np.nextafter(thresholds, F32(-np.inf))
    # The formula reaches k exactly at the k-th threshold, not one ulp earlier.
    np.testing.assert_array_equal(_formula(thresholds), np.arange(1, 101))
    np.testing.assert_array_equal(_formula(below), np.arange(0, 100))


def test_every_step_plus_minus_two_ulps_matches_the_formula() -> None:
    values = ulps(_thresholds(), 2)
    np.testing.assert_array_equal(_published(values), _formula(values))
    np.testing.assert_array_equal(_looked_up(values), _formula(values))


def test_step_midpoints_and_probability_levels_match() -> None:
    # log-odds of p = k/100 and (k +- 0.5)/100, where rounding and steps sit.
    p = np.concatenate([np.arange(1, 100), np.arange(0.5, 100.0, 1.0)]) / 100.0
    values = ulps(np.log(p / (1.0 - p)).astype(F32), 1)
    np.testing.assert_array_equal(_looked_up(values), _formula(values))
    np.testing.assert_array_equal(_published(values), _old_scale_data(_grid(values)))


def test_special_values_match() -> None:
    values = ulps(np.array(SPECIAL, dtype=F32), 1)
    values = values[np.abs(values) <= 1e6]
    data = _published(values)
    expected = _formula(values)
    expected[values == 0.0] = -1  # ±0: never observed
    np.testing.assert_array_equal(data, expected)
    np.testing.assert_array_equal(_looked_up(values), _formula(values))


def test_values_no_grid_holds_match_too() -> None:
    values = np.array(BEYOND_GRID, dtype=F32)
    np.testing.assert_array_equal(_looked_up(values), _formula(values))
    assert _looked_up(values).tolist() == [100, 0, 100, 0, 100, 0]


def test_random_bit_patterns_match() -> None:
    rng = np.random.default_rng(12)
    values = rng.integers(0, 2**32, 1 << 18, dtype=np.uint64).astype(np.uint32).view(F32)
    values = values[~np.isnan(values)]
    np.testing.assert_array_equal(_looked_up(values), _formula(values))
    held = values[np.abs(values) <= 1e6]
    np.testing.assert_array_equal(_published(held), _old_scale_data(_grid(held)))


def test_random_log_odds_of_a_map_match() -> None:
    rng = np.random.default_rng(7)
    values = rng.normal(0.0, 3.0, 1 << 16).astype(F32)
    np.testing.assert_array_equal(_published(values), _formula(values))


@settings(max_examples=300)
@given(st.lists(st.floats(width=32, allow_nan=False), min_size=1, max_size=50))
def test_any_float32_matches(values: list[float]) -> None:
    arr = np.array(values, dtype=F32)
    np.testing.assert_array_equal(_looked_up(arr), _formula(arr))


@settings(max_examples=200)
@given(
    st.lists(
        st.floats(-1e6, 1e6, width=32) | st.floats(-8.0, 8.0, width=32),
        min_size=1,
        max_size=50,
    )
)
def test_any_grid_publishes_as_before(values: list[float]) -> None:
    grid = _grid(np.array(values, dtype=F32))
    np.testing.assert_array_equal(grid_to_msg_fields(grid).data, _old_scale_data(grid))


# ------------------------------------------------------------- the pipeline


def _grid(values: NDArray[np.float32], **thresholds: float) -> OccupancyGrid:
    return OccupancyGrid(values.reshape(1, -1), resolution=1.0, **thresholds)


def test_unknown_cells_are_minus_one_across_blocks() -> None:
    # More cells than one block of the look-up, not a multiple of it.
    rng = np.random.default_rng(3)
    logodds = rng.uniform(-8.0, 8.0, (301, 251)).astype(F32)
    logodds[rng.random(logodds.shape) < 0.3] = 0.0
    logodds[rng.random(logodds.shape) < 0.05] = -0.0
    grid = OccupancyGrid(logodds, resolution=0.05)
    data = grid_to_msg_fields(grid).data
    np.testing.assert_array_equal(data, _old_scale_data(grid))
    np.testing.assert_array_equal(data == -1, (logodds == 0.0).ravel())
    assert data.dtype == np.int8 and not data.flags.writeable


def test_one_cell_and_one_column() -> None:
    for logodds in (np.array([[2.0]], dtype=F32), np.linspace(-7, 7, 9, dtype=F32)[:, None]):
        grid = OccupancyGrid(logodds, resolution=0.1)
        np.testing.assert_array_equal(grid_to_msg_fields(grid).data, _old_scale_data(grid))


def test_grid_is_not_modified() -> None:
    rng = np.random.default_rng(4)
    logodds = rng.uniform(-8.0, 8.0, (70, 1000)).astype(F32)
    grid = OccupancyGrid(logodds, resolution=0.05)
    grid_to_msg_fields(grid)
    np.testing.assert_array_equal(grid.logodds, logodds)


def test_trinary_mode_is_unchanged() -> None:
    rng = np.random.default_rng(5)
    logodds = rng.uniform(-8.0, 8.0, (40, 30)).astype(F32)
    logodds[::7] = 0.0
    grid = OccupancyGrid(logodds, resolution=0.05)
    expected = np.full(grid.shape, -1, dtype=np.int8)
    expected[grid.occupied()] = 100
    expected[grid.free()] = 0
    np.testing.assert_array_equal(grid_to_msg_fields(grid, mode="trinary").data, expected.ravel())


def test_band_excluding_one_half_publishes_its_unknown_pixels_as_minus_one(
    tmp_path: Path,
) -> None:
    # Pixels 0..255 in a map whose thresholds (free 0.6, occupied 0.9) class p = 0.5 free:
    # its unknown pixels read as the band's middle, not log-odds 0.
    image = tmp_path / "map.pgm"
    image.write_bytes(pgm_bytes(np.arange(256, dtype=np.uint8).reshape(16, 16)))
    yaml_path = tmp_path / "map.yaml"
    yaml_path.write_text(
        yaml.safe_dump(
            {
                "image": str(image),
                "resolution": 0.05,
                "origin": [0.0, 0.0, 0.0],
                "negate": 0,
                "occupied_thresh": 0.9,
                "free_thresh": 0.6,
            }
        )
    )
    grid = read_map(yaml_path)
    middle = grid.logodds[grid.unknown()]
    assert middle.size and np.all(middle == middle[0]) and middle[0] != 0.0
    data = grid_to_msg_fields(grid).data
    np.testing.assert_array_equal(data, _old_scale_data(grid))
    np.testing.assert_array_equal(data == -1, grid.unknown().ravel())
    # The same log-odds in a grid whose thresholds make them known stay a percentage.
    known = OccupancyGrid(grid.logodds, resolution=0.05)
    np.testing.assert_array_equal(grid_to_msg_fields(known).data, _old_scale_data(known))
    assert (grid_to_msg_fields(known).data[grid.unknown().ravel()] != -1).all()


def test_real_map_publishes_as_before(shared_data: Path) -> None:
    folder = shared_data / "ros-map-server-maps"
    yamls = sorted(folder.rglob("*.yaml"))
    if not yamls:
        pytest.skip("no map in ros-map-server-maps")
    for path in yamls[:3]:
        try:
            grid = read_map(path)
        except (ValueError, TypeError, OSError):
            continue
        np.testing.assert_array_equal(grid_to_msg_fields(grid).data, _old_scale_data(grid))


# ---------------------------------------------------------------- the cost


def test_scale_mode_has_no_float64_grids() -> None:
    # The formula's float64 probabilities and exp (8 bytes a cell each) are gone:
    # the int8 data, the message's copy of it and cache-sized blocks remain.
    # (The formula peaked at 16 bytes a cell.)
    rng = np.random.default_rng(6)
    grid = OccupancyGrid(rng.uniform(-8.0, 8.0, (1000, 1000)).astype(F32), resolution=0.05)
    peak, fields = peak_bytes(lambda: grid_to_msg_fields(grid))
    assert peak / grid.logodds.size < 4.0
    assert fields.data.size == grid.logodds.size
