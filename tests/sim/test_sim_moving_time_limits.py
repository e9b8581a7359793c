"""Moving obstacles at the limits of time and speed: finite positions or a ValueError naming why."""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.sim import Lidar, MovingObstacle, World


def _obstacle(path: list[tuple[float, float]], times: list[float], after: str) -> MovingObstacle:
    return MovingObstacle(0.2, np.array(path), np.array(times), after=after)  # type: ignore[arg-type]


def _extend(start: tuple[float, float], velocity: tuple[float, float]) -> MovingObstacle:
    return MovingObstacle.constant_velocity(0.2, start_xy=start, velocity_xy=velocity)


@pytest.mark.parametrize("t", [1e300, -1e300, 1.7e308, 2e9, 1e9 * (1 + 1e-15) + 1.0])
def test_position_at_beyond_the_time_limit_raises_naming_t(t: float) -> None:
    ob = _extend((0.0, 0.0), (1e3, 1.0))
    with pytest.raises(ValueError, match=r"\bt must lie within"):
        ob.position_at(t)
    with pytest.raises(ValueError, match=r"\bt must lie within"):
        ob.geometry_at(t)


@pytest.mark.parametrize("after", ["stop", "loop", "extend"])
def test_world_queries_beyond_the_time_limit_raise_naming_t(after: str) -> None:
    ob = _obstacle([(1.0, 0.0), (2.0, 0.0)], [0.0, 1.0], after)
    world = World([], moving=[ob])
    calls: list[Callable[[], object]] = [
        lambda: world.raycast([0.0, 0.0, 0.0], [0.0], range_max=5.0, t=1e300),
        lambda: world.clearance(0.1, (0.0, 0.0, 0.0), t=-1e300),
        lambda: world.collides(0.1, (0.0, 0.0, 0.0), t=2e9),
        lambda: Lidar(n_beams=4, noise=None).scan(world, (0.0, 0.0, 0.0), t=1e300),
    ]
    for query in calls:
        with pytest.raises(ValueError, match=r"\bt must lie within"):
            query()


@settings(max_examples=50, deadline=None)
@given(
    start=st.tuples(st.floats(-999e3, 999e3), st.floats(-999e3, 999e3)),
    velocity=st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)),
    t=st.floats(-1e9, 1e9),
)
# The speed limit from a start where start + velocity rounds: refused before (a
# thorough-profile draw; see the test below).
@example(start=(-24.31534649296816, 0.0), velocity=(-1000.0, 0.0), t=0.0)
def test_constant_velocity_positions_are_finite_and_exact_within_the_limits(
    start: tuple[float, float], velocity: tuple[float, float], t: float
) -> None:
    ob = _extend(start, velocity)
    x, y = ob.position_at(t)
    # Reference: the documented motion, waiting at start_xy before t = 0.
    tt = max(t, 0.0)
    assert math.isfinite(x) and math.isfinite(y)
    # The velocity is stored as the difference of two waypoints (t = 0 and 1 s),
    # exact to a rounding of start_xy + velocity_xy, which t then scales.
    for got, s0, v in ((x, start[0], velocity[0]), (y, start[1], velocity[1])):
        tol = 4 * np.finfo(float).eps * ((abs(s0) + abs(v)) * (1.0 + tt) + abs(v * tt))
        assert abs(got - (s0 + v * tt)) <= tol
    # The world places it at the same position and its distances stay finite.
    world = World([], moving=[ob])
    clearance = world.clearance(0.1, (0.0, 0.0, 0.0), t=t)
    assert math.isfinite(clearance)
    # To the obstacle's boundary circle (radius 0.2), less the robot's radius 0.1.
    expected = max(abs(math.hypot(x, y) - 0.2) - 0.1, 0.0)
    assert clearance == pytest.approx(expected, rel=1e-9, abs=1e-6)


test_constant_velocity_positions_are_finite_and_exact_within_the_limits_thoroughly = slow_twin(
    test_constant_velocity_positions_are_finite_and_exact_within_the_limits, max_examples=200
)


def test_extend_with_a_last_leg_too_fast_raises() -> None:
    # 1e6 m in one subnormal second: the velocity overflows, positions were inf/NaN.
    with pytest.raises(ValueError, match="after='extend' needs the last leg"):
        _obstacle([(0.0, 0.0), (1e6, 0.0)], [0.0, 5e-324], "extend")
    with pytest.raises(ValueError, match="after='extend' needs the last leg"):
        _obstacle([(0.0, 0.0), (0.0, 0.0), (0.0, 1.1)], [0.0, 1.0, 1.001], "extend")
    # The same legs are fine when the obstacle stops or loops (it stays on its path).
    ob = _obstacle([(0.0, 0.0), (1e6, 0.0)], [0.0, 5e-324], "stop")
    assert np.isfinite(ob.position_at(1e9)).all()
    # At the limit itself: accepted, finite at the far end of time.
    edge = _obstacle([(0.0, 0.0), (1e3, -1e3)], [0.0, 1.0], "extend")
    assert edge.position_at(1e9).tolist() == [1e12, -1e12]


def test_constant_velocity_at_the_speed_limit_is_accepted_wherever_it_starts() -> None:
    # Velocities within ±1e3 m/s are accepted (documented), but the two waypoints'
    # difference may round beyond the velocity: from x = -24.3 at -1e3 m/s the leg
    # is -1000.0000000000001 m/s, which the constructor's check of a caller's last
    # leg refused ("after='extend' needs the last leg ... at most 1000 m/s").
    start = (-24.31534649296816, 0.0)
    for velocity in ((-1e3, 0.0), (-1e3, 1e3)):
        ob = _extend(start, velocity)
        leg = ob.path_xy[1] - ob.path_xy[0]
        assert leg[0] == -1000.0000000000001  # the case: the waypoints' leg is too fast
        assert ob.after == "extend"
        for t in (0.5, 1e9):
            # start_xy + velocity_xy · t, correctly rounded twice (documented).
            want = [s0 + v * t for s0, v in zip(start, velocity, strict=True)]
            for obstacle in (ob, copy.deepcopy(ob), pickle.loads(pickle.dumps(ob))):
                assert obstacle.position_at(t).tolist() == want
        world = World([], moving=[ob])
        assert world.clearance(0.1, (0.0, 0.0, 0.0), t=1e9) == pytest.approx(
            math.hypot(*ob.position_at(1e9)) - 0.3, rel=1e-12
        )


def test_constant_velocity_second_waypoint_out_of_range_names_its_arguments() -> None:
    with pytest.raises(ValueError, match=r"start_xy \+ velocity_xy"):
        _extend((1e6, 0.0), (1.0, 0.0))
