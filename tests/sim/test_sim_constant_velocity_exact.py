"""A constant-velocity obstacle is at ``start + velocity · t``, correctly rounded, forever.

Its velocity used to be the difference of its two waypoints (t = 0 and 1 s), which
loses the velocity's bits below ulp(start): positions drifted by up to ulp(start) · t,
about 0.05 m at t = 1e9 s from 1e6 m. Checked against exact rational arithmetic.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapely.geometry import Polygon

from hypothesis_twins import slow_twin
from navkit.sim import Lidar, MovingObstacle, World

coords = st.floats(-1e6, 1e6, allow_nan=False)
speeds = st.floats(-1e3, 1e3, allow_nan=False)
times = st.one_of(st.floats(-1e9, 1e9, allow_nan=False), st.floats(0.0, 1.0))


def exact_position(start: float, velocity: float, t: float) -> Fraction:
    """``start + velocity · max(t, 0)`` in exact arithmetic (it waits before t = 0)."""
    return Fraction(start) + Fraction(velocity) * Fraction(max(t, 0.0))


def two_roundings(start: float, velocity: float, t: float, got: float) -> Fraction:
    """The error bound of ``fl(start + fl(velocity · t))``: half an ulp of each result."""
    product = velocity * max(t, 0.0)
    return Fraction(math.ulp(product) + math.ulp(got)) / 2


@settings(max_examples=40)
@given(start=st.tuples(coords, coords), velocity=st.tuples(speeds, speeds), t=times)
def test_position_is_start_plus_velocity_times_t(
    start: tuple[float, float], velocity: tuple[float, float], t: float
) -> None:
    assume(all(abs(s + v) <= 1e6 for s, v in zip(start, velocity, strict=True)))
    ob = MovingObstacle.constant_velocity(0.2, start_xy=start, velocity_xy=velocity)
    got = ob.position_at(t)
    for axis in range(2):
        exact = exact_position(start[axis], velocity[axis], t)
        error = abs(Fraction(float(got[axis])) - exact)
        assert error <= two_roundings(start[axis], velocity[axis], t, float(got[axis]))


test_position_is_start_plus_velocity_times_t_thoroughly = slow_twin(
    test_position_is_start_plus_velocity_times_t, max_examples=100
)


def test_no_drift_after_a_long_time_far_from_the_origin() -> None:
    # The example of the report: from (999000, -999000) m at 1 mm/s for 1e9 s the old
    # obstacle was 0.047 m off (the waypoints' difference is 0.001 ± 5e-11 m/s).
    ob = MovingObstacle.constant_velocity(0.5, start_xy=(999000.0, -999000.0),
                                          velocity_xy=(-0.001, 0.001))  # fmt: skip
    got = ob.position_at(1e9)
    exact = [exact_position(999000.0, -0.001, 1e9), exact_position(-999000.0, 0.001, 1e9)]
    for g, e in zip(got, exact, strict=True):
        assert abs(Fraction(float(g)) - e) < Fraction(1, 10**9)
    np.testing.assert_array_equal(ob.position_at(-5.0), [999000.0, -999000.0])


def _far_world() -> tuple[World, MovingObstacle, MovingObstacle, np.ndarray]:
    """A disc and a triangle moving together at 1 mm/s from about 1e6 m; where their
    reference point is at t = 1e9 s (float of the exact value)."""
    start, velocity = (999000.0, -999000.0), (-0.001, 0.001)
    disc = MovingObstacle.constant_velocity(0.5, start_xy=start, velocity_xy=velocity)
    triangle = MovingObstacle.constant_velocity(
        Polygon([(0.0, 10.0), (1.0, 10.0), (0.0, 11.0)]), start_xy=start, velocity_xy=velocity
    )
    at = np.array([float(exact_position(s, v, 1e9)) for s, v in zip(start, velocity, strict=True)])
    return World([], moving=[disc, triangle]), disc, triangle, at


def test_world_places_the_obstacles_where_they_are() -> None:
    world, disc, triangle, at = _far_world()
    robot = (at[0] + 5.0, at[1], 0.0)  # 5 m to the east of the disc's centre
    assert world.clearance(0.1, robot, t=1e9) == pytest.approx(5.0 - 0.5 - 0.1, abs=1e-6)
    below = (at[0] + 0.5, at[1] + 9.0, 0.0)  # 1 m below the triangle's bottom edge
    assert world.clearance(0.1, below, t=1e9) == pytest.approx(1.0 - 0.1, abs=1e-6)
    assert world.collides(0.1, (at[0] + 0.2, at[1] + 10.2, 0.0), t=1e9)  # inside the triangle
    assert not world.collides(0.1, (at[0] + 0.9, at[1] + 10.9, 0.0), t=1e9)  # beyond its edge
    scan = Lidar(n_beams=1, fov=0.1, range_min=0.0, range_max=20.0, noise=None).scan(
        world, (at[0] - 3.0, at[1], 0.0), t=1e9
    )
    assert float(scan.ranges[0]) == pytest.approx(2.5, abs=1e-6)
    np.testing.assert_allclose(disc.position_at(1e9), at, rtol=0, atol=1e-9)
    np.testing.assert_allclose(triangle.position_at(1e9), at, rtol=0, atol=1e-9)


def test_copies_keep_the_velocity(duplicate: Callable[[Any], Any]) -> None:
    world, disc, _, at = _far_world()
    twin = duplicate(disc)
    assert twin is not disc
    np.testing.assert_array_equal(twin.position_at(1e9), disc.position_at(1e9))
    np.testing.assert_allclose(twin.position_at(1e9), at, rtol=0, atol=1e-9)
    assert not twin.path_xy.flags.writeable and not twin.times.flags.writeable
    world_twin = duplicate(world)
    robot = (at[0] + 5.0, at[1], 0.0)
    assert world_twin.clearance(0.1, robot, t=1e9) == world.clearance(0.1, robot, t=1e9)


def test_a_pickle_of_the_four_fields_still_loads() -> None:
    # Pickles made before the velocity was kept: the waypoints' velocity, as then.
    ob = MovingObstacle.constant_velocity(0.2, start_xy=(1.0, 2.0), velocity_xy=(0.5, 0.0))
    old = object.__new__(MovingObstacle)
    old.__setstate__([ob.shape, np.array(ob.path_xy), np.array(ob.times), ob.after])
    np.testing.assert_array_equal(old.position_at(4.0), [3.0, 2.0])
    assert not old.path_xy.flags.writeable


def test_waypoint_obstacles_are_unchanged() -> None:
    # Obstacles given by waypoints follow them: the same interpolation as before.
    path, stamps = np.array([(999000.0, 0.0), (999000.001, 0.0)]), np.array([0.0, 1.0])
    ob = MovingObstacle(0.2, path, stamps, after="extend")
    d = 999000.001 - 999000.0
    assert ob.position_at(1e9)[0] == 999000.0 + 1e9 * d
