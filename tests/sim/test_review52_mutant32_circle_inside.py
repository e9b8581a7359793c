"""A polygon inside a circle is as far from it as its farthest vertex allows (review 52, MUTANT32).

``_to_circle`` measures a polygon footprint's farthest vertex from the
circle's centre with products of the offsets (review 51 wrote ``x ** 2`` as
``x * x``). The existing tests place a polygon inside a circle only where the
offsets' two axes could be swapped unseen: a mutant measuring the vertex's
``y`` offset from the centre's ``x`` survived. Here the robot stands off
both axes of the centre, turned, with its footprint's vertices at different
distances.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.sim import Circle, World

SQUARE = [[-0.1, -0.1], [0.3, -0.1], [0.3, 0.2], [-0.1, 0.2]]


def _far(pose: tuple[float, float, float], centre: tuple[float, float]) -> float:
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    return max(
        math.hypot(x + c * u - s * v - centre[0], y + s * u + c * v - centre[1]) for u, v in SQUARE
    )


@pytest.mark.parametrize("seed", range(4))
def test_inside_a_circle_the_clearance_is_the_radius_less_the_farthest_vertex(seed: int) -> None:
    rng = np.random.default_rng(seed)
    centre = (float(rng.uniform(-2.0, 2.0)), float(rng.uniform(-2.0, 2.0)))
    world = World([Circle(centre, 2.0)])
    for _ in range(10):
        pose = (
            centre[0] + float(rng.uniform(-1.0, 1.0)),
            centre[1] + float(rng.uniform(-1.0, 1.0)),
            float(rng.uniform(-math.pi, math.pi)),
        )
        want = 2.0 - _far(pose, centre)
        assert want > 0.0
        assert world.clearance(SQUARE, pose) == pytest.approx(want, rel=0.0, abs=1e-12)
