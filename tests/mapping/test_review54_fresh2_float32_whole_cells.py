"""A length that is whole (or half) cells of a float32 resolution is that many (review 54, FRESH2).

bcb53cd counts cells of a float32 resolution (a ROS message's) in the decimal
it stands for, so that 10 m at float32 0.01 m (0.00999999978) are 1000 cells as
at the YAML's 0.01. A length that is a whole number of the float32's *own*
cells was counted in the decimal's too, and where the float32 lies above its
decimal (0.05, 0.1, 0.025, 0.3) ``n * resolution`` is a little more than ``n``
decimal cells: ``OccupancyGrid.empty(width=r, height=r, resolution=r)`` at
``r = float(np.float32(0.05))`` had 2 x 2 cells, ``width = n * resolution``
``n + 1`` columns (the docstring: ``n`` for any ``n``), a grid's own width and
height at its resolution one more row and column, and so did
``rasterize_polygons``' bounds and ``sample_field``'s window; the scan
matcher's pre-search took ``k + 1`` steps for ``k`` cells. Where the float32
lies below (0.01, 0.03), ``LocalGrid.from_points`` rounded ``2.5 *
resolution`` (2.5 of its cells exactly) down to 2 half cells. bcb53cd's parent
counted all of these as the resolution's own cells, as now.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit._shared.float32 import length_in_cells
from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid, ScanMatcher, rasterize_polygons
from navkit.planning import ConicAttraction, sample_field

#: Decimals whose float32 lies above them (first four) and below them (last three).
DECIMALS = (0.05, 0.1, 0.025, 0.3, 0.01, 0.03, 0.7)
CELLS = (1, 2, 3, 7, 10, 99, 100, 1000, 4096)


def _single(decimal: float) -> float:
    return float(np.float32(decimal))


def test_the_premise_float32_on_both_sides_of_its_decimal() -> None:
    assert all(_single(d) > d for d in DECIMALS[:4])
    assert all(_single(d) < d for d in DECIMALS[4:])


@pytest.mark.parametrize("decimal", DECIMALS)
def test_n_cells_of_a_float32_resolution_are_n_cells(decimal: float) -> None:
    res = _single(decimal)
    for n in CELLS:
        grid = OccupancyGrid.empty(width=n * res, height=res, resolution=res)
        assert grid.shape == (1, n), (decimal, n)


@pytest.mark.parametrize("decimal", DECIMALS)
def test_a_grid_of_its_own_width_and_height_has_its_shape(decimal: float) -> None:
    res = _single(decimal)
    for size in (1.0, 2.5, 10.0, 17.3):
        grid = OccupancyGrid.empty(width=size, height=0.5 * size, resolution=res)
        again = OccupancyGrid.empty(width=grid.width, height=grid.height, resolution=res)
        assert again.shape == grid.shape, (decimal, size)


@pytest.mark.parametrize("decimal", DECIMALS)
def test_the_decimal_still_counts_as_bcb53cd_made_it(decimal: float) -> None:
    # bcb53cd's case stays: lengths that are whole cells of the decimal.
    res = _single(decimal)
    for n in CELLS:
        grid = OccupancyGrid.empty(width=n * decimal, height=decimal, resolution=res)
        assert grid.shape == (1, n), (decimal, n)
    assert OccupancyGrid.empty(width=10.0, height=10.0, resolution=_single(0.01)).shape == (
        1000,
        1000,
    )


@pytest.mark.parametrize("decimal", DECIMALS)
def test_rasterized_bounds_of_whole_float32_cells(decimal: float) -> None:
    res = _single(decimal)
    obstacle = box(2.5 * res, 2.5 * res, 5.5 * res, 5.5 * res)
    got = rasterize_polygons(obstacle, bounds=(0.0, 0.0, 40 * res, 10 * res), resolution=res)
    assert got.shape == (10, 40)
    assert int(got.occupied().sum()) == 16  # cells 2 to 5 each way, partly covered at 2 and 5


@pytest.mark.parametrize("decimal", DECIMALS)
def test_a_sampled_window_of_whole_float32_cells(decimal: float) -> None:
    res = _single(decimal)
    field = ConicAttraction((0.0, 0.0))
    for n in (1, 10, 120):
        sampled = sample_field(
            field, xlim=(-1.0, -1.0 + n * res), ylim=(0.0, 2 * res), resolution=res
        )
        assert sampled.shape == (2, n), (decimal, n)


@pytest.mark.parametrize("decimal", DECIMALS)
def test_a_local_grid_of_half_float32_cells_rounds_up(decimal: float) -> None:
    res = _single(decimal)
    for k in range(0, 12):
        for half, want in ((k * res, k), ((k + 0.5) * res, k + 1)):
            grid = LocalGrid.from_points(np.zeros((0, 2)), half_width=half, resolution=res)
            assert grid.size == 2 * want + 1, (decimal, k, half)
    # bcb53cd's case stays: half cells of the decimal round up too.
    for k in range(0, 12):
        grid = LocalGrid.from_points(
            np.zeros((0, 2)), half_width=(k + 0.5) * decimal, resolution=res
        )
        assert grid.size == 2 * k + 3, (decimal, k)


def test_the_pre_search_takes_whole_float32_cells_as_steps(monkeypatch: pytest.MonkeyPatch) -> None:
    import navkit.mapping._scan_matcher as matcher_module

    seen: list[object] = []
    real = matcher_module.__dict__["correlative_search"]

    def spy(*args: object) -> float:
        seen.append(args[7])  # steps_xy
        return float(real(*args))

    monkeypatch.setattr(matcher_module, "correlative_search", spy)
    walls = np.zeros((60, 60), dtype=bool)
    walls[:, 50] = True
    scan = LaserScan(
        np.full(21, 0.2), angle_min=-0.2, angle_increment=0.02, range_min=0.01, range_max=5.0
    )
    res = _single(0.01 * 5)  # float32 0.05, above its decimal
    grid = OccupancyGrid.from_occupancy(walls, resolution=res, origin=(-1.5, -1.5, 0.0))
    for steps in (1, 3, 6):
        matcher = ScanMatcher(search_distance=steps * res, search_angle=0.0, levels=1)
        matcher.match(grid, scan, (0.0, 0.0, 0.0))
    assert seen == [1, 3, 6]


@settings(max_examples=400, deadline=None)
@given(
    mantissa=st.integers(1, 999_999),
    exponent=st.integers(-9, 3),
    n=st.integers(1, 1_000_000),
)
def test_whole_cells_of_the_float32_and_of_its_decimal(
    mantissa: int, exponent: int, n: int
) -> None:
    # Any decimal of up to 6 significant digits (what float32 keeps) from 1e-9 to 1e9 m.
    decimal = float(f"{mantissa}e{exponent}")
    res = _single(decimal)
    for length in (n * res, n * decimal):
        cells = length_in_cells(length, res)
        assert np.ceil(cells - (1e-9 + 4 * 2.0**-52 * cells)) == n, (decimal, n, length)
    for length in ((n + 0.5) * res, (n + 0.5) * decimal):
        half = length_in_cells(length, res, halves=True)
        assert abs(half - (n + 0.5)) <= 1e-9 + 4 * 2.0**-52 * half, (decimal, n, length)


def test_a_float64_resolution_is_its_own_cells() -> None:
    # No float32 value (0.05 written in Python), or one standing for no short decimal.
    for res in (0.05, 0.01 * (1 + 1e-7), 0.00244140625, _single(1 / 81)):
        for length in (1.0, 10.0, 0.3, 7 * res):
            assert length_in_cells(length, res) == length / res
