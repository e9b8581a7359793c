"""Fields at sub-normal and extremely small offsets: finite forces of the documented size.

A point a few sub-normals (5e-324 m each) from a goal or an obstacle has an offset
whose ``hypot`` rounds by up to a factor of √2, so dividing the offset by it gave a
"direction" of length up to √2 and a force up to 41 % too strong (too weak for
other offsets). The force's magnitude is the radial law's and its direction the
offset's, however small the offset.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import LaserScan
from navkit.planning import (
    BlendedAttraction,
    ConicAttraction,
    KhatibRepulsion,
    PiecewiseRepulsion,
    PotentialField,
    repulsive_force_from_scan,
)

SUB = 5e-324  # the smallest positive float64

# Offsets from the centre, in units of SUB (exact multiples are sub-normal for small
# counts) or as plain tiny numbers.
counts = st.integers(-(2**20), 2**20)
tiny = st.sampled_from([1e-320, 1e-310, 2.2e-308, 1e-300, 1e-200, 1e-20])


def _fields() -> list[tuple[str, PotentialField, float, float]]:
    """(name, field centred at the origin, expected |F| near it, sign: -1 pulls, +1 pushes)."""
    khatib = KhatibRepulsion(np.zeros((1, 2)), k_rep=2.0, influence_radius=0.5)
    blended = BlendedAttraction(np.zeros(2))
    # Blended: the radial terms at d -> 0 (the paraboloid's gradient vanishes there),
    # taken from the formula at a small but normal distance. With the defaults they
    # push outward: the field's minimum lies 3.75 mm from the goal (documented).
    ref = blended.force([[1e-200, 0.0]])[0]
    near = float(np.hypot(*ref))
    piecewise = PiecewiseRepulsion(np.zeros((1, 2)), delta=3.0, obstacle_radius=0.2)
    return [
        ("khatib", khatib, 2.0 * (1e9 - 2.0) * 1e18, 1.0),  # saturated at 1e-9 m
        ("piecewise", piecewise, 3.0, 1.0),
        ("conic", ConicAttraction(np.zeros(2), m=1.5, u_trans=2.0), 3.0, -1.0),
        ("blended", blended, near, math.copysign(1.0, float(ref[0]))),
    ]


FIELDS = _fields()


@pytest.mark.parametrize(("name", "field", "magnitude", "sign"), FIELDS,
                         ids=[f[0] for f in FIELDS])
@settings(max_examples=50)
@given(i=counts, j=counts)
def test_force_at_subnormal_offsets_has_the_radial_magnitude(
    name: str, field: PotentialField, magnitude: float, sign: float, i: int, j: int
) -> None:
    assume((i, j) != (0, 0))
    x, y = i * SUB, j * SUB
    force = field.force([[x, y]])[0]
    assert np.all(np.isfinite(force))
    assert math.hypot(force[0] / magnitude, force[1] / magnitude) == pytest.approx(1.0, rel=1e-12)
    # Along the offset: the cross product of the force with (i, j) vanishes.
    ux, uy = force / magnitude
    norm = math.hypot(i, j)
    assert ux * j / norm - uy * i / norm == pytest.approx(0.0, abs=1e-12)
    assert sign * (ux * i + uy * j) > 0.0


test_force_at_subnormal_offsets_has_the_radial_magnitude_thoroughly = slow_twin(
    test_force_at_subnormal_offsets_has_the_radial_magnitude, max_examples=300
)


@pytest.mark.parametrize("v", [SUB, 3 * SUB, 1e-320, 1e-310])
def test_the_corner_cases_that_were_off(v: float) -> None:
    # (v, v): hypot(5e-324, 5e-324) is 5e-324, so the old direction was (1, 1), √2 long.
    for _, field, magnitude, _ in FIELDS:
        force = field.force([[v, v], [-v, 2 * v]])
        assert np.hypot(force[:, 0], force[:, 1]) / magnitude == pytest.approx([1.0, 1.0],
                                                                              rel=1e-12)


@given(d=tiny, sx=st.sampled_from([1.0, -1.0]), sy=st.sampled_from([1.0, -1.0]))
def test_tiny_normal_offsets_still_exact(d: float, sx: float, sy: float) -> None:
    field = KhatibRepulsion(np.zeros((1, 2)))
    x, y = sx * d * 0.6, sy * d * 0.8
    # The offset's direction, computed after an exact scaling out of the sub-normals.
    big_x, big_y = x * 2.0**600, y * 2.0**600
    norm = math.hypot(big_x, big_y)
    force = field.force([[x, y]])[0]
    assert force / ((1e9 - 1.0) * 1e18) == pytest.approx([big_x / norm, big_y / norm], rel=1e-12)


def test_obstacle_exactly_on_the_point_is_documented() -> None:
    # d == 0: +inf potential, no force from that obstacle (no direction).
    field = KhatibRepulsion(np.array([[0.0, 0.0], [SUB, 0.0]]))
    force = field.force([[0.0, 0.0]])[0]
    assert field.potential([[0.0, 0.0]])[0] == math.inf
    assert force[0] == pytest.approx(-(1e9 - 1.0) * 1e18, rel=1e-12)
    assert force[1] == 0.0


@pytest.mark.parametrize("r", [SUB, 1e-320, 1e-310, 1e-300, 1e-12])
def test_scan_with_subnormal_ranges_saturates(r: float) -> None:
    scan = LaserScan(np.array([r, r]), angle_min=0.0, angle_increment=math.pi / 2,
                     range_min=0.0, range_max=10.0)
    force = repulsive_force_from_scan(scan, k_rep=1.0, influence_radius=1.0)
    push = (1e9 - 1.0) * 1e18
    assert force == pytest.approx([-push, -push], rel=1e-12)
