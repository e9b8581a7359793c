"""``rasterize_polygons`` on geometries that shapely calls invalid (review 25, lower layers).

GEOS's predicates are undefined on invalid geometries, and the prepared ones the
rasteriser uses went wrong on the commonest of them: a MultiPolygon whose parts
overlap (``MultiPolygon(walls)`` of crossing walls). The overlap was left free:
100 cells of two 5 m squares overlapping by 3 m at 0.25 m, a hole in the walls
that a planner could use; a part nested in another became a hole. Such a
geometry is now rasterised part by part (the cells touching its parts are the
cells touching their union). A single polygon whose ring crosses itself is read
as before, as ``shapely.make_valid`` repairs it.
"""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import (
    GeometryCollection,
    LineString,
    MultiPolygon,
    Point,
    Polygon,
    box,
)

from navkit.mapping import OccupancyGrid, rasterize_polygons
from subprocess_probe import probe_outcome

BOUNDS = (0.0, 0.0, 10.0, 10.0)


def _cells(geometries: object, resolution: float = 0.25) -> np.ndarray:
    return rasterize_polygons(geometries, bounds=BOUNDS, resolution=resolution).occupied()


def test_overlapping_squares_of_one_multipolygon_leave_no_hole() -> None:
    a, b = box(1.0, 1.0, 6.0, 6.0), box(3.0, 3.0, 9.0, 9.0)
    multi = MultiPolygon([a, b])
    assert not multi.is_valid  # the parts overlap
    want = _cells([a, b])
    got = _cells(multi)
    np.testing.assert_array_equal(got, want)
    # The overlap's inner cells, which the prepared predicates had left free.
    assert got[13:23, 13:23].all()


# Boxes on a 0.125 m lattice, each at least 1 m wide, inside the bounds.
_corner = st.integers(0, 56).map(lambda k: k * 0.125)
_size = st.integers(8, 24).map(lambda k: k * 0.125)
_box = st.tuples(_corner, _corner, _size, _size).map(
    lambda t: box(t[0], t[1], t[0] + t[2], t[1] + t[3])
)


@settings(max_examples=60, deadline=None)
@given(parts=st.lists(_box, min_size=2, max_size=4), resolution=st.sampled_from([0.25, 0.4, 0.5]))
def test_a_multipolygon_occupies_the_cells_of_its_parts(
    parts: list[Polygon], resolution: float
) -> None:
    want = _cells(parts, resolution)
    union = shapely.unary_union(parts)  # valid, whatever the overlaps
    np.testing.assert_array_equal(_cells(MultiPolygon(parts), resolution), want)
    np.testing.assert_array_equal(_cells(union, resolution), want)
    # Nested in a collection, as from shapely's set operations on mixed shapes.
    nested = GeometryCollection([MultiPolygon(parts), Point(-5.0, -5.0)])
    np.testing.assert_array_equal(_cells(nested, resolution), want)
    # The same through OccupancyGrid.from_polygons.
    grid = OccupancyGrid.from_polygons(MultiPolygon(parts), bounds=BOUNDS, resolution=resolution)
    np.testing.assert_array_equal(grid.occupied(), want)


def test_crossing_walls_of_one_multipolygon_are_whole() -> None:
    walls = MultiPolygon([box(0.0, 4.0, 10.0, 6.0), box(4.0, 0.0, 6.0, 10.0)])
    got = _cells(walls)
    np.testing.assert_array_equal(got, _cells(list(walls.geoms)))
    assert got[16:24, 16:24].all()  # the crossing


def test_a_part_nested_in_another_is_not_a_hole() -> None:
    multi = MultiPolygon([box(1.0, 1.0, 9.0, 9.0), box(3.0, 3.0, 7.0, 7.0)])
    assert not multi.is_valid  # nested shells
    # Before: 288 of the outer square's 324 cells at 0.5 m, the inner square free.
    np.testing.assert_array_equal(_cells(multi, 0.5), _cells(box(1.0, 1.0, 9.0, 9.0), 0.5))


def test_single_invalid_polygons_and_degenerate_lines_are_rasterised_as_before() -> None:
    # A bow-tie (a square's corners out of order: the ring crosses itself) is read
    # as make_valid's two triangles, as before; inside a MultiPolygon too.
    bow_tie = Polygon([(1.0, 1.0), (9.0, 9.0), (9.0, 1.0), (1.0, 9.0)])
    assert not bow_tie.is_valid
    repaired = _cells(shapely.make_valid(bow_tie))
    np.testing.assert_array_equal(_cells(bow_tie), repaired)
    np.testing.assert_array_equal(_cells(MultiPolygon([bow_tie])), repaired)
    # A zero-length line is invalid to shapely (too few points); GEOS tests it as
    # its point.
    dot = LineString([(5.1, 5.1), (5.1, 5.1)])
    assert not dot.is_valid
    assert _cells(dot).sum() == 1
    # Parts sharing an edge (invalid as a MultiPolygon): the cells of both.
    touching = MultiPolygon([box(1.0, 1.0, 2.0, 2.0), box(2.0, 1.0, 3.0, 2.0)])
    np.testing.assert_array_equal(_cells(touching), _cells(list(touching.geoms)))


def test_the_geometries_are_not_modified_nor_left_prepared() -> None:
    multi = MultiPolygon([box(1.0, 1.0, 6.0, 6.0), box(3.0, 3.0, 9.0, 9.0)])
    wkb = multi.wkb
    _cells([multi])
    assert multi.wkb == wkb
    assert not shapely.is_prepared(multi)
    assert not any(shapely.is_prepared(part) for part in multi.geoms)


_SHARED_BY_THREADS = """
import json, threading
import numpy as np
from shapely.geometry import Point
from navkit.mapping import rasterize_polygons

ring = Point(5, 5).buffer(4, quad_segs=64).difference(Point(5, 5).buffer(2))
want = rasterize_polygons([ring], bounds=(0, 0, 10, 10), resolution=0.1).occupied()
start = threading.Barrier(4)
same = []

def work():
    start.wait()
    for _ in range(10):
        got = rasterize_polygons([ring], bounds=(0, 0, 10, 10), resolution=0.1).occupied()
        same.append(bool(np.array_equal(got, want)))

threads = [threading.Thread(target=work) for _ in range(4)]
for t in threads:
    t.start()
for t in threads:
    t.join()
print(json.dumps(same))
"""


def test_threads_sharing_a_geometry_get_its_cells() -> None:
    # In a child process: before, this crashed it.
    assert probe_outcome(_SHARED_BY_THREADS) == [True] * 40


def test_a_prepared_geometry_stays_prepared() -> None:
    disc = Point(5.0, 5.0).buffer(2.0)
    shapely.prepare(disc)
    want = _cells(Point(5.0, 5.0).buffer(2.0))
    np.testing.assert_array_equal(_cells(disc), want)
    assert shapely.is_prepared(disc)
