"""Review 53 (FOUND5): cells counted from a length at a float32 resolution are those of its decimal.

A map from a ROS message carries its resolution as a float32 (0.01 m arrives
as 0.009999999776482582 m). Review 52 took radii in cells of the decimal the
float32 stands for; grid and window sizes still counted the float32's cells:
``OccupancyGrid.empty`` of 10 m at it had 1001 cells where the YAML's 0.01 m
gives 1000, and so did ``rasterize_polygons``' bounds and ``sample_field``'s
window; ``LocalGrid.from_points`` rounded 0.25 m at float32 0.1 (2.4999999627
cells) to 2 half-cells where 0.1 gives 3; the scan matcher's pre-search took 31
steps for 0.3 m at float32 0.01. All count in cells of the decimal now
(``navkit._shared.float32.intended_resolution``, one helper).
"""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import box

from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid, ScanMatcher, rasterize_polygons
from navkit.planning import ConicAttraction, sample_field

#: Decimal resolutions of real maps, some below their float32 (0.01, 0.03), some above (0.05, 0.1).
DECIMALS = (0.01, 0.02, 0.025, 0.03, 0.05, 0.1, 0.15, 0.2, 0.3)
CELLS = (1, 3, 7, 10, 99, 100, 333, 1000, 1001, 4096)


def _single(resolution: float) -> float:
    return float(np.float32(resolution))


def test_the_float32_resolutions_here_are_not_their_decimals() -> None:
    # The test's premise: each of these float32s differs from its decimal, both ways.
    assert all(_single(r) != r for r in DECIMALS)
    assert any(_single(r) < r for r in DECIMALS) and any(_single(r) > r for r in DECIMALS)


@pytest.mark.parametrize("resolution", DECIMALS)
def test_an_empty_grid_has_the_cells_of_its_decimal(resolution: float) -> None:
    for n in CELLS:
        for m in (1, 13):
            width, height = n * resolution, m * resolution
            want = OccupancyGrid.empty(width=width, height=height, resolution=resolution).shape
            assert want == (m, n)
            got = OccupancyGrid.empty(width=width, height=height, resolution=_single(resolution))
            assert got.shape == want, (resolution, n, m)
            assert got.resolution == _single(resolution)  # kept as given


def test_ten_metres_at_a_message_resolution_are_a_thousand_cells() -> None:
    grid = OccupancyGrid.empty(width=10.0, height=10.0, resolution=_single(0.01))
    assert grid.shape == (1000, 1000)
    # Half a cell more is still a cell more.
    grid = OccupancyGrid.empty(width=10.005, height=10.0, resolution=_single(0.01))
    assert grid.shape == (1000, 1001)


def test_a_float64_resolution_counts_its_own_cells() -> None:
    # A resolution that is no float32 value is its own cell: 0.01 * (1 + 1e-9).
    res = 0.01 * (1.0 + 1e-7)
    assert _single(res) != res
    grid = OccupancyGrid.empty(width=10.0, height=1.0, resolution=res)
    assert grid.shape == (100, 1000)  # 999.9999 cells, rounded up
    assert OccupancyGrid.empty(width=10.0001, height=1.0, resolution=0.01).shape == (100, 1001)


@pytest.mark.parametrize("resolution", DECIMALS)
def test_rasterized_bounds_have_the_cells_of_their_decimal(resolution: float) -> None:
    bounds = (0.0, 0.0, 100 * resolution, 10 * resolution)
    # Sides mid-cell: a side on a cell edge touches both cells, and the float32's
    # edges lie a little off the decimal's.
    obstacle = box(2.5 * resolution, 2.5 * resolution, 5.5 * resolution, 5.5 * resolution)
    want = rasterize_polygons(obstacle, bounds=bounds, resolution=resolution)
    got = rasterize_polygons(obstacle, bounds=bounds, resolution=_single(resolution))
    assert got.shape == want.shape == (10, 100)
    assert np.array_equal(got.occupied(), want.occupied())


@pytest.mark.parametrize("resolution", DECIMALS)
def test_a_local_grid_rounds_half_cells_of_its_decimal(resolution: float) -> None:
    for k in range(0, 12):
        for half in (k * resolution, (k + 0.5) * resolution):
            want = LocalGrid.from_points(np.zeros((0, 2)), half_width=half, resolution=resolution)
            got = LocalGrid.from_points(
                np.zeros((0, 2)), half_width=half, resolution=_single(resolution)
            )
            assert got.occupied.shape == want.occupied.shape, (resolution, half)


def test_a_quarter_metre_at_float32_decimetres_is_three_half_cells() -> None:
    grid = LocalGrid.from_points([[0.0, 0.21]], half_width=0.25, resolution=_single(0.1))
    assert grid.occupied.shape == (7, 7)
    assert grid.half_width == 3 * _single(0.1)
    assert np.argwhere(grid.occupied).tolist() == [[5, 3]]  # 0.21 m left: 2 cells up


@pytest.mark.parametrize("resolution", DECIMALS)
def test_a_sampled_window_has_the_cells_of_its_decimal(resolution: float) -> None:
    field = ConicAttraction((0.0, 0.0))
    for n in (1, 10, 120):
        limits = (-1.0, -1.0 + n * resolution)
        want = sample_field(field, xlim=limits, ylim=(0.0, 2 * resolution), resolution=resolution)
        got = sample_field(
            field, xlim=limits, ylim=(0.0, 2 * resolution), resolution=_single(resolution)
        )
        assert got.shape == want.shape == (2, n)
        assert got.resolution == _single(resolution)
        np.testing.assert_allclose(np.diff(got.x), _single(resolution), rtol=1e-9)


def test_twelve_metres_at_a_message_resolution_are_1200_columns() -> None:
    sampled = sample_field(
        ConicAttraction((0.0, 0.0)), xlim=(0.0, 12.0), ylim=(0.0, 0.02), resolution=_single(0.01)
    )
    assert sampled.shape == (2, 1200)


def test_the_pre_search_takes_the_steps_of_the_decimal(monkeypatch: pytest.MonkeyPatch) -> None:
    import navkit.mapping._scan_matcher as matcher_module

    seen: list[object] = []
    real = matcher_module.correlative_search

    def spy(*args: object) -> float:
        seen.append(args[7])  # steps_xy
        return real(*args)

    monkeypatch.setattr(matcher_module, "correlative_search", spy)
    walls = np.zeros((60, 60), dtype=bool)
    walls[:, 50] = True
    scan = LaserScan(
        np.full(21, 0.2), angle_min=-0.2, angle_increment=0.02, range_min=0.01, range_max=5.0
    )
    for resolution in (0.01, _single(0.01)):
        grid = OccupancyGrid.from_occupancy(walls, resolution=resolution, origin=(-0.3, -0.3, 0.0))
        matcher = ScanMatcher(search_distance=0.3, search_angle=0.0, levels=1)
        matcher.match(grid, scan, (0.0, 0.0, 0.0))
    assert seen == [30, 30]
