"""Potential fields at UTM coordinates: the forces at the origin, bit for bit (review 54).

A field's force and potential depend on differences of positions only (point minus
goal, point minus obstacle), each exact when the two are close (Sterbenz). The scene
here is built at a UTM offset (x ~ 4.5e5 m, y ~ 5.4e6 m, floats 5.8e-11 and
9.3e-10 m apart) and moved to the origin by subtracting it (exact too), so both hold
the same geometry and every field gives the same numbers bit for bit: per point and,
above 2**18 point-obstacle pairs, through the k-d tree. A field computing
``|q|² - 2 q·o + |o|²`` or ``q - goal`` after scaling would lose up to 1e-3 m² at
UTM, and this would fail.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning.reactive import (
    BlendedAttraction,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
)

OFFSET = np.array([450000.123456, 5400000.654321])


def _fields(goal: np.ndarray, obstacles: np.ndarray) -> list[PotentialField]:
    return [
        ParaboloidAttraction(goal),
        ConicAttraction(goal, threshold_radius=0.5),
        BlendedAttraction(goal),
        PiecewiseAttraction(goal, goal_radius=0.2),
        KhatibRepulsion(obstacles, influence_radius=0.8),
        PiecewiseRepulsion(obstacles, obstacle_radius=0.1, spread=0.5),
    ]


@pytest.mark.parametrize(("points", "obstacles"), [(2000, 20), (400, 700)])
def test_fields_at_utm_are_the_fields_at_the_origin(points: int, obstacles: int) -> None:
    rng = np.random.default_rng(points)
    far_q = rng.uniform(-3.0, 3.0, (points, 2)) + OFFSET
    far_goal = np.array([1.0, 0.5]) + OFFSET
    far_obstacles = rng.uniform(-3.0, 3.0, (obstacles, 2)) + OFFSET
    near = _fields(far_goal - OFFSET, far_obstacles - OFFSET)
    far = _fields(far_goal, far_obstacles)
    q = far_q - OFFSET
    for at_origin, at_utm in zip(near, far, strict=True):
        force = at_origin.force(q)
        assert np.abs(force).max() > 0.0
        assert np.array_equal(at_utm.force(far_q), force), type(at_utm).__name__
        assert np.array_equal(at_utm.potential(far_q), at_origin.potential(q))
