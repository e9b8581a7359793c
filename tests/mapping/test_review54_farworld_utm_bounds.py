"""Rasterising within bounds written in UTM coordinates: whole cells stay whole (review 54).

``rasterize_polygons`` (and ``OccupancyGrid.from_polygons``) round the bounds up to
whole cells, counting ``n`` cells for an extent of ``n * resolution`` "however long
the grid is". Bounds written to the millimetre at a UTM northing (5.1e6 m, floats
9.3e-10 m apart) are each rounded by up to half of that, so their difference can
exceed ``n`` cells by 1.9e-8 cells at 0.05 m, more than the 1e-9 cells the count
forgave: 41 % of such bounds gained a row of cells past the area asked for (at an
easting of 4.5e5 m and 0.01 m cells too), while ``sample_field`` counted the same
window as ``n`` cells. The count now forgives the rounding of the bounds themselves,
``2**-51 (|min| + |max|)`` as ``sample_field`` does.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.affinity import translate
from shapely.geometry import Point, box

from navkit.mapping import OccupancyGrid, rasterize_polygons
from navkit.planning.reactive import ConicAttraction, sample_field


def _decimal_bounds(
    xmin_mm: int, ymin_mm: int, cols: int, rows: int, res_mm: int
) -> tuple[float, float, float, float]:
    """Bounds written to the millimetre: exactly ``cols × rows`` cells of ``res_mm`` mm."""
    return (
        float(Fraction(xmin_mm, 1000)),
        float(Fraction(ymin_mm, 1000)),
        float(Fraction(xmin_mm + cols * res_mm, 1000)),
        float(Fraction(ymin_mm + rows * res_mm, 1000)),
    )


def test_a_northing_given_to_the_millimetre_keeps_its_whole_rows() -> None:
    # 5144394.059 - 5144272.509 is 121.55 m, 2431 cells of 0.05 m; as floats the
    # difference is 121.55000000074506 (2431.0000000149 cells): 2432 rows before.
    bounds = (450000.0, 5144272.509, 450001.0, 5144394.059)
    grid = rasterize_polygons([], bounds=bounds, resolution=0.05)
    assert grid.shape == (2431, 20)
    assert OccupancyGrid.from_polygons([], bounds=bounds, resolution=0.05).shape == (2431, 20)


def test_the_count_is_that_of_sample_field() -> None:
    bounds = (450000.0, 5144272.509, 450001.0, 5144394.059)
    field = sample_field(ConicAttraction((450000.5, 5144300.0)), xlim=(bounds[0], bounds[2]),
                         ylim=(bounds[1], bounds[3]), resolution=0.05)  # fmt: skip
    assert rasterize_polygons([], bounds=bounds, resolution=0.05).shape == field.potential.shape


def test_an_extent_beyond_whole_cells_by_more_than_its_rounding_still_gains_a_cell() -> None:
    # A micrometre past 2431 cells is 2e-5 cells: far above the bounds' rounding.
    bounds = (450000.0, 5144272.509, 450001.0, 5144394.059001)
    assert rasterize_polygons([], bounds=bounds, resolution=0.05).shape == (2432, 20)
    # At the origin nothing changes: 0.3 m at 0.25 m cells is 2 cells.
    assert rasterize_polygons([], bounds=(0, 0, 0.3, 0.3), resolution=0.25).shape == (2, 2)


@settings(max_examples=200, deadline=None)
@given(
    xmin_mm=st.integers(-600_000_000, 600_000_000),
    ymin_mm=st.integers(-9_000_000_000, 9_000_000_000),
    cols=st.integers(1, 400),
    rows=st.integers(1, 400),
    res_mm=st.sampled_from([10, 25, 50, 100]),
)
def test_whole_cells_in_decimal_are_that_many_cells_anywhere(
    xmin_mm: int, ymin_mm: int, cols: int, rows: int, res_mm: int
) -> None:
    bounds = _decimal_bounds(xmin_mm, ymin_mm, cols, rows, res_mm)
    grid = rasterize_polygons([], bounds=bounds, resolution=res_mm / 1000)
    assert grid.shape == (rows, cols)


@settings(max_examples=40, deadline=None)
@given(
    ymin_mm=st.integers(5_000_000_000, 6_000_000_000),
    rows=st.integers(20, 300),
)
def test_a_utm_scene_has_the_cells_of_the_scene_at_the_origin(ymin_mm: int, rows: int) -> None:
    offset = (450_000.0, float(Fraction(ymin_mm, 1000)))
    bounds = _decimal_bounds(450_000_000, ymin_mm, 60, rows, 50)
    shapes = [
        translate(s, *offset)
        for s in (Point(1.51, 0.49).buffer(0.7123), box(0.11, 0.21, 2.89, 0.31))
    ]
    far = rasterize_polygons(shapes, bounds=bounds, resolution=0.05)
    # The same scene moved to the origin (exact: the points lie within a factor 2 of
    # the offset; no edge lies on a cell's edge, where the rounding at UTM decides
    # whether it touches the next cell). There the bounds as rounded at UTM are what
    # they say, and may reach past ``rows`` cells by that rounding: one row more.
    local = tuple(b - offset[i % 2] for i, b in enumerate(bounds))
    near = rasterize_polygons([translate(s, -offset[0], -offset[1]) for s in shapes],
                              bounds=local, resolution=0.05)  # fmt: skip
    assert far.shape == (rows, 60)
    assert near.shape in {(rows, 60), (rows + 1, 60)}
    assert np.array_equal(far.occupied(), near.occupied()[:rows])
