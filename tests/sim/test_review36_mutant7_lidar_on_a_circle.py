"""A LiDAR on a circle's boundary reads 0 on every beam (mutation review, session 40).

A beam from a point on an obstacle's boundary touches it at once: as from the
face of a blocked cell or a polygon's edge, every beam from a point on a
circle reads 0, those pointing into the circle too. A mutant of the ray-circle
intersection that took a first crossing at exactly ``t = 0`` for none (``t <= 0``
for ``t < 0``) and went on to the far side of the circle survived the LiDAR
tests: none puts the sensor exactly on a circle.

Oracle: geometry. The sensors sit on circles where the arithmetic is exact
(integer coordinates on a circle of integer radius: Pythagorean triples).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.sim import Circle, World

# Points on the circle of radius 5 about (1, -2), exactly.
_ON = [(6.0, -2.0), (1.0, 3.0), (-4.0, -2.0), (4.0, 2.0), (-2.0, -6.0), (5.0, -5.0)]


@pytest.mark.parametrize("solid", [False, True])
@pytest.mark.parametrize("point", _ON)
def test_a_sensor_on_a_circle_reads_zero_on_every_beam(
    point: tuple[float, float], solid: bool
) -> None:
    world = World(Circle(np.array([1.0, -2.0]), 5.0, solid=solid))
    angles = np.linspace(-math.pi, math.pi, 24, endpoint=False)
    ranges = world.raycast((*point, 0.3), angles, range_max=20.0)
    assert ranges.tolist() == [0.0] * angles.shape[0]
    assert not np.signbit(ranges).any()


def test_a_sensor_just_inside_a_ring_reads_the_ring_ahead() -> None:
    """From a hair inside the ring each beam reads the distance to where it leaves."""
    world = World(Circle(np.array([1.0, -2.0]), 5.0, solid=False))
    point = np.array([6.0 - 1e-9, -2.0])
    angles = np.array([0.0, math.pi, math.pi / 2, 3.0])
    got = world.raycast((*point, 0.0), angles, range_max=20.0)
    for a, r in zip(angles, got, strict=True):
        d = np.array([math.cos(a), math.sin(a)])
        w = point - np.array([1.0, -2.0])
        b = float(w @ d)
        want = -b + math.sqrt(b * b - (float(w @ w) - 25.0))  # the exit: inside the ring
        assert r == pytest.approx(want, abs=1e-7)
