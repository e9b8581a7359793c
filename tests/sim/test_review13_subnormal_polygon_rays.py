"""A polygon world with a subnormal vertex coordinate (review 13, degenerate-input lens).

Found by hypothesis in ``test_random_polygon_worlds_match_shapely``: two triangles
sharing the vertex (cos 1, sin 1), one with its base at y = 2.225e-313 (a subnormal
float). The beam at 0.349 rad from (0.1234567891, -0.3456789123) reads 1.0107 m
where shapely's ray through the union meets the boundary at 0.9422 m. Review 14
found navkit right and the oracle wrong: the beam crosses y = 2.225e-313 at
x = 1.0732, inside the base from (1, 2.225e-313) to (1.25, 2.225e-313), at exactly
1.0106975248263297 m, and passes 2.7 cm below the vertex (1, 2.225e-313) that
GEOS 3.14 reports as the crossing (its segment intersection, computed with
products that underflow for subnormal coordinates, falls back to the segment's
nearest end point). For bases at y = 1e-308 or 2.225e-313 GEOS gives that end
point, for 1e-320, 1e-300 or 0 the right point. These tests use an exact oracle
(rational arithmetic on the edges) instead.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Polygon

from hypothesis_twins import slow_twin
from navkit.sim import World

ORIGIN = (0.1234567891, -0.3456789123)
ANGLE = -math.pi + 40 * (2 * math.pi / 72)
#: Subnormal, tiny normal and zero coordinates, of either sign.
TINY = [0.0, 5e-324, -5e-324, 1e-320, 2.225e-313, -2.225e-313, 1e-310, 1e-308, -1e-308,
        2.2250738585072014e-308, 1e-300]  # fmt: skip


def _shapely_range(union: shapely.Geometry, angle: float, reach: float) -> float:
    """Distance from ORIGIN along ``angle`` to the union's boundary (inf: none)."""
    end = (ORIGIN[0] + reach * math.cos(angle), ORIGIN[1] + reach * math.sin(angle))
    hit = LineString([ORIGIN, end]).intersection(union.boundary)
    if hit.is_empty:
        return math.inf
    return float(shapely.distance(shapely.points(ORIGIN), hit))


def exact_range(polygons: list[Polygon], angle: float, reach: float) -> float:
    """Exact distance (then rounded) from ORIGIN along ``angle`` to the first polygon edge.

    From outside every polygon the first edge a beam meets is on the boundary of
    their union. Rational arithmetic on the float inputs (the beam's direction is
    the float ``(cos, sin)`` of ``angle``, as navkit casts it): nothing underflows.
    """
    dx, dy = Fraction(math.cos(angle)), Fraction(math.sin(angle))
    ox, oy = Fraction(ORIGIN[0]), Fraction(ORIGIN[1])
    best: Fraction | None = None
    for poly in polygons:
        ring = [(Fraction(x), Fraction(y)) for x, y in poly.exterior.coords]
        for (ax, ay), (bx, by) in itertools.pairwise(ring):
            ex, ey = bx - ax, by - ay
            den = dx * ey - dy * ex
            if den == 0:
                continue  # parallel: a beam along an edge meets its ends first
            wx, wy = ax - ox, ay - oy
            t = (wx * ey - wy * ex) / den
            u = (wx * dy - wy * dx) / den
            if 0 <= u <= 1 and 0 <= t <= reach and (best is None or t < best):
                best = t
    return math.inf if best is None else float(best)


def _pair(tiny: float) -> list[Polygon]:
    first = Polygon([(1.0, 0.0), (math.cos(1.0), math.sin(1.0)), (math.cos(2.0), math.sin(2.0))])
    second = Polygon([(1.0, tiny), (1.25, tiny), (math.cos(1.0), math.sin(1.0))])
    return [first, second]


@pytest.mark.parametrize("tiny", TINY)
def test_a_subnormal_vertex_does_not_move_the_hit(tiny: float) -> None:
    polygons = _pair(tiny)
    want = exact_range(polygons, ANGLE, 40.0)
    # The second triangle's base, at x = 1.0732: 6.8 cm beyond shapely's 0.9422 m
    # (where the beam is 2.7 cm below the vertex (1, tiny)).
    assert want == pytest.approx(1.0106975248263297, abs=1e-15)
    y_at_vertex = ORIGIN[1] + (1.0 - ORIGIN[0]) * math.tan(ANGLE)
    assert y_at_vertex == pytest.approx(-0.0266, abs=1e-4)
    got = World(polygons).raycast((*ORIGIN, 0.0), [ANGLE], range_max=40.0)[0]
    assert got == pytest.approx(want, abs=1e-9)


def test_the_same_world_without_the_subnormal_is_right() -> None:
    first = Polygon([(1.0, 0.0), (math.cos(1.0), math.sin(1.0)), (math.cos(2.0), math.sin(2.0))])
    second = Polygon([(1.0, 0.0), (1.25, 0.0), (math.cos(1.0), math.sin(1.0))])
    angle = -math.pi + 40 * (2 * math.pi / 72)
    want = _shapely_range(shapely.union_all([first, second]), angle, 40.0)
    got = World([first, second]).raycast((*ORIGIN, 0.0), [angle], range_max=40.0)[0]
    assert np.isclose(got, want, rtol=0.0, atol=1e-9)
    assert want == pytest.approx(exact_range([first, second], angle, 40.0), abs=1e-12)


@st.composite
def _triangles(draw: st.DrawFn) -> Polygon:
    """A triangle right of the origin with its base's ends at tiny |y| (subnormals)."""
    x1 = draw(st.floats(1.0, 2.9))
    x2 = draw(st.floats(x1 + 0.05, 3.0))
    y1, y2 = draw(st.sampled_from(TINY)), draw(st.sampled_from(TINY))
    apex_x = draw(st.floats(0.5, 3.5))
    apex_y = draw(st.sampled_from([-1.0, 1.0])) * draw(st.floats(0.3, 1.0))
    return Polygon([(x1, y1), (x2, y2), (apex_x, apex_y)])


@settings(max_examples=25, deadline=None)
@given(st.lists(_triangles(), min_size=1, max_size=3))
def test_subnormal_polygon_worlds_match_the_exact_rays(polygons: list[Polygon]) -> None:
    angles = np.linspace(-math.pi, math.pi, 72, endpoint=False)
    with np.errstate(all="ignore"):  # GEOS's union may warn about subnormal arithmetic
        world = World(polygons)
    got = world.raycast((*ORIGIN, 0.0), angles, range_max=40.0)
    want = np.array([exact_range(polygons, a, 40.0) for a in angles])
    np.testing.assert_array_equal(np.isfinite(got), np.isfinite(want))
    finite = np.isfinite(want)
    np.testing.assert_allclose(got[finite], want[finite], rtol=0.0, atol=1e-9)


test_subnormal_polygon_worlds_match_the_exact_rays_thoroughly = slow_twin(
    test_subnormal_polygon_worlds_match_the_exact_rays, max_examples=200
)
