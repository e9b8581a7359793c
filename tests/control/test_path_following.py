"""The trackers' shared polyline geometry: arc length, projection, lookahead, curvature."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Point

from hypothesis_twins import slow_twin
from navkit.control._path_following import (
    Polyline,
    as_world_path,
    bounded,
    pursuit_curvature,
    wrap,
)
from navkit.planning import Path2D

coord = st.floats(-5.0, 5.0, allow_nan=False)
points = st.lists(st.tuples(coord, coord), min_size=2, max_size=8)


def test_arc_length_drops_duplicates() -> None:
    line = Polyline(np.array([[0.0, 0.0], [0.0, 0.0], [3.0, 4.0], [3.0, 4.0], [3.0, 5.0]]))
    assert line.points_xy.tolist() == [[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]]
    assert line.cum.tolist() == [0.0, 5.0, 6.0]
    assert line.length == 6.0
    assert not line.points_xy.flags.writeable


def test_one_point_path() -> None:
    line = Polyline(np.array([[1.0, 2.0], [1.0, 2.0]]))
    assert line.length == 0.0
    assert line.point_at(3.0) == (1.0, 2.0)
    assert line.project(4.0, 6.0, 0.0, 1.0) == (0.0, 5.0)
    assert line.circle_exit(0.0, 0.0, 0.0, 1.0) == 0.0  # 2.2 m away
    assert line.circle_exit(1.0, 1.5, 0.0, 1.0) is None  # 0.5 m away


def test_point_at() -> None:
    line = Polyline(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]))
    assert line.point_at(-1.0) == (0.0, 0.0)
    assert line.point_at(1.5) == (1.5, 0.0)
    assert line.point_at(2.5) == (2.0, 0.5)
    assert line.point_at(9.0) == (2.0, 2.0)


def test_projection_window_keeps_loops_in_order() -> None:
    """On a closed loop the start and the end coincide: the window picks the start."""
    t = np.linspace(0.0, 2 * math.pi, 101)
    line = Polyline(np.column_stack([np.sin(t), 1.0 - np.cos(t)]))
    s, d = line.project(0.0, -0.01, 0.0, 2.0)
    assert s == pytest.approx(0.0, abs=1e-12)
    assert d == pytest.approx(0.01)
    # Late in the loop, the same point projects onto the end.
    s_end, _ = line.project(0.0, -0.01, line.length - 1.0, line.length)
    assert s_end == pytest.approx(line.length)


def test_projection_stops_where_the_path_leaves_the_robot() -> None:
    """A 1.6 m square loop and a point 1 cm beside its start: the end of the loop is
    nearer, but the path first leads more than the detour away from the point."""
    line = Polyline(np.array([[0.0, 0.0], [0.4, 0.0], [0.4, 0.4], [0.0, 0.4], [0.0, 0.0]]))
    assert line.project(0.0, 0.01, 0.0, 2.0) == pytest.approx((1.59, 0.0))
    assert line.project(0.0, 0.01, 0.0, 2.0, detour=0.25) == pytest.approx((0.0, 0.01))
    # Up to s_free the whole path is searched, the detour only counts from it on:
    # at s_free = 1.4 the path is 0.19 m from the point, within the detour of the
    # start's 0.01 m, and the search goes on to the loop's end; at s_free = 1.3 it
    # is 0.29 m away, a detour, and the search stops there (review 38: tested at
    # the next vertex only, it went on, and a vertex added at 1.31 m stopped it).
    assert line.project(0.0, 0.01, 0.0, 2.0, detour=0.25, s_free=1.4) == pytest.approx(
        (1.59, 0.0)
    )
    assert line.project(0.0, 0.01, 0.0, 2.0, detour=0.25, s_free=1.3) == pytest.approx(
        (0.0, 0.01)
    )
    # A path that only wiggles within the detour is searched to the window's end.
    wiggle = Polyline(np.array([[0.0, 0.0], [0.1, 0.1], [0.2, 0.0], [0.3, 0.1], [0.4, 0.0]]))
    assert wiggle.project(0.4, 0.0, 0.0, 1.0, detour=0.25) == pytest.approx(
        (wiggle.length, 0.0)
    )


@settings(max_examples=50, deadline=None)
@given(points, coord, coord)
def test_projection_matches_shapely(pts: list[tuple[float, float]], x: float, y: float) -> None:
    line = Polyline(np.array(pts))
    if line.length == 0.0:
        return
    s, d = line.project(x, y, 0.0, line.length)
    assert 0.0 <= s <= line.length
    ref = LineString(line.points_xy).distance(Point(x, y))
    if math.isfinite(ref):  # shapely gives inf for segments of ~1e-188 m
        assert d == pytest.approx(ref, abs=1e-9)
    px, py = line.point_at(s)
    assert math.hypot(px - x, py - y) == pytest.approx(d, abs=1e-9)


test_projection_matches_shapely_thoroughly = slow_twin(
    test_projection_matches_shapely, max_examples=200
)


@settings(max_examples=50, deadline=None)
@given(points, st.floats(0.0, 1.0), st.floats(0.01, 3.0), coord, coord)
def test_circle_exit_is_the_first_crossing(
    pts: list[tuple[float, float]], frac: float, radius: float, x: float, y: float
) -> None:
    """The lookahead point is ``radius`` away and every path point before it is nearer;
    None means every point from ``s0`` on is nearer."""
    line = Polyline(np.array(pts))
    s0 = frac * line.length
    s = line.circle_exit(x, y, s0, radius)
    if s is None:
        for u in np.linspace(s0, line.length, 200):
            qx, qy = line.point_at(float(u))
            assert math.hypot(qx - x, qy - y) < radius + 1e-9
        return
    assert s0 - 1e-12 <= s <= line.length
    px, py = line.point_at(s)
    dist = math.hypot(px - x, py - y)
    if s > s0:
        assert dist == pytest.approx(radius, abs=1e-7)
        for u in np.linspace(s0, s, 50)[:-1]:
            qx, qy = line.point_at(float(u))
            assert math.hypot(qx - x, qy - y) <= radius + 1e-7
    else:
        assert dist >= radius - 1e-9


test_circle_exit_is_the_first_crossing_thoroughly = slow_twin(
    test_circle_exit_is_the_first_crossing, max_examples=200
)


def test_pursuit_curvature() -> None:
    assert pursuit_curvature(1.0, 0.0) == 0.0
    assert pursuit_curvature(0.0, 2.0) == pytest.approx(1.0)  # a half circle of radius 1
    assert pursuit_curvature(1.0, -1.0) == pytest.approx(-1.0)
    assert pursuit_curvature(0.01, 0.01) == 0.0  # too close (Nav2's 0.001 m² guard)


def test_wrap() -> None:
    assert wrap(math.pi) == math.pi
    assert wrap(-math.pi) == math.pi
    assert wrap(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap(0.3) == 0.3


def test_bounded() -> None:
    assert bounded(2.0, "x", 0.0, 3.0) == 2.0
    assert bounded(0.0, "x", 0.0, 3.0, include_lo=True) == 0.0
    with pytest.raises(ValueError, match=r"x must be in \(0, 3\]"):
        bounded(0.0, "x", 0.0, 3.0)
    with pytest.raises(ValueError, match="x must be in"):
        bounded(3.5, "x", 0.0, 3.0)
    with pytest.raises(TypeError, match="x"):
        bounded("1", "x", 0.0, 3.0)


def test_as_world_path_inputs() -> None:
    pts = np.array([[0.0, 0.0], [1.0, 1.0]])
    out = as_world_path(pts)
    assert out.tolist() == pts.tolist()
    out[0, 0] = 9.0
    assert pts[0, 0] == 0.0  # a copy
    world = Path2D(pts, "world", cost=1.4, length=1.4, expanded=0)
    assert as_world_path(world).tolist() == pts.tolist()
    assert as_world_path([(0, 0), (1, 2)]).dtype == np.float64


@pytest.mark.parametrize(
    ("bad", "error", "match"),
    [
        (np.empty((0, 2)), ValueError, "at least one point"),
        ([], ValueError, "path"),
        ([[0.0, np.nan]], ValueError, "finite"),
        ([[0.0, np.inf]], ValueError, "finite"),
        ([0.0, 1.0, 2.0], ValueError, "path"),
        ([[0.0, 1.0, 2.0]], ValueError, "path"),
        ([[2e9, 0.0]], ValueError, "within"),
        ("0 0 1 1", TypeError, "path"),
        ({"x": 1}, TypeError, "path"),
        ([["a", "b"]], TypeError, "path"),
        (None, TypeError, "path"),
        (Path2D([[0, 0], [1, 1]], "grid", cost=1.0, length=1.0, expanded=0), ValueError,
         "world frame"),
    ],
)
def test_as_world_path_rejects(bad: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        as_world_path(bad)
