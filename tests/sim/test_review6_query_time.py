"""Query times: bounded only where moving obstacles need it, alike for every World query."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Circle, Lidar, MovingObstacle, Observation, Robot, Simulation, World

_SQUARE = [(0.2, -0.2), (0.3, -0.2), (0.3, 0.2), (0.2, 0.2)]


def _static_world() -> World:
    walls = box(0.0, 0.0, 4.0, 3.0).exterior
    return World([walls, Circle(np.array([3.0, 2.0]), 0.4), box(2.0, 0.5, 2.5, 1.0)])


def _answers(world: World, t: float) -> tuple[object, ...]:
    lidar = Lidar(n_beams=16, noise=None)
    return (
        world.raycast((1.0, 1.0, 0.3), lidar.angles(), range_max=10.0, t=t).tolist(),
        world.clearance(0.1, (1.0, 1.0, 0.0), t=t),
        world.clearance(_SQUARE, (1.0, 1.0, 0.7), t=t),
        world.collides(0.1, (2.2, 0.7, 0.0), t=t),
        world.collides(_SQUARE, (1.0, 1.0, 0.7), t=t),
        lidar.scan(world, (1.0, 1.0, 0.3), t=t).ranges.tolist(),
    )


@pytest.mark.parametrize("t", [2e9, -2e9, 1e300, -1.7e308, 1e9 * (1 + 1e-15) + 1.0])
def test_a_world_without_moving_obstacles_answers_any_finite_time_alike(t: float) -> None:
    # Without moving obstacles the time is unused: raycast, clearance and collides
    # refused |t| > 1e9 s (a ValueError) where Lidar.scan answered.
    world = _static_world()
    assert _answers(world, t) == _answers(world, 0.0)


@pytest.mark.parametrize("t", [math.nan, math.inf, -math.inf])
def test_a_world_without_moving_obstacles_still_refuses_non_finite_times(t: float) -> None:
    world = _static_world()
    queries: list[Callable[[], object]] = [
        lambda: world.raycast((1.0, 1.0, 0.0), [0.0], range_max=5.0, t=t),
        lambda: world.clearance(0.1, (1.0, 1.0, 0.0), t=t),
        lambda: world.collides(0.1, (1.0, 1.0, 0.0), t=t),
        lambda: Lidar(n_beams=4, noise=None).scan(world, (1.0, 1.0, 0.0), t=t),
    ]
    for query in queries:
        with pytest.raises(ValueError, match=r"\bt must be finite"):
            query()


@pytest.mark.parametrize("t", [2e9, -1e300])
def test_every_query_of_a_world_with_moving_obstacles_refuses_a_time_beyond_the_limit(
    t: float,
) -> None:
    ob = MovingObstacle.constant_velocity(0.2, start_xy=(3.0, 1.0), velocity_xy=(1e-9, 0.0))
    world = World(box(0.0, 0.0, 4.0, 3.0).exterior, moving=[ob])
    queries: list[Callable[[], object]] = [
        lambda: world.raycast((1.0, 1.0, 0.0), [0.0], range_max=5.0, t=t),
        lambda: world.clearance(0.1, (1.0, 1.0, 0.0), t=t),
        lambda: world.collides(0.1, (1.0, 1.0, 0.0), t=t),
        lambda: Lidar(n_beams=4, noise=None).scan(world, (1.0, 1.0, 0.0), t=t),
    ]
    for query in queries:
        with pytest.raises(ValueError, match=r"\bt must lie within ±1e\+09 s"):
            query()
    # ... and within it they answer.
    assert world.clearance(0.1, (1.0, 1.0, 0.0), t=1e9) == pytest.approx(0.9, abs=1e-12)


def test_the_documented_limit_a_moving_obstacle_crossing_within_one_step_is_missed() -> None:
    """The docstrings say moving obstacles are checked only at the steps' ends.

    A thin bar sweeps across a resting robot between two physics steps: no
    collision at 10 Hz physics, one at 1000 Hz, where a step end finds it on
    the robot.
    """
    bar = np.array([(-0.01, -1.0), (0.01, -1.0), (0.01, 1.0), (-0.01, 1.0)])
    # Crosses x = -0.5 .. 0.5 (the robot's disc is x in [-0.2, 0.2]) between
    # t = 1.0 and 1.1 s, then stops far away.
    ob = MovingObstacle.scripted(bar, [(-0.5, 0.0), (0.5, 0.0), (5.0, 0.0)],
                                 times=[1.02, 1.08, 2.0])  # fmt: skip
    world = World(box(-10.0, -10.0, 10.0, 10.0).exterior, moving=[ob])
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, encoders=None)

    def stay(_: Observation) -> Twist2D:
        return Twist2D(0.0, 0.0, 0.0)

    coarse = Simulation(world, robot, stay, start=(0.0, 0.0, 0.0), rate=10.0,
                        control_rate=10.0, duration=3.0).run()  # fmt: skip
    fine = Simulation(world, robot, stay, start=(0.0, 0.0, 0.0), rate=1000.0,
                      control_rate=10.0, duration=3.0).run()  # fmt: skip
    assert coarse.metrics.collisions == 0 and coarse.metrics.reason == "timeout"
    assert fine.metrics.collisions == 1 and fine.metrics.reason == "collision"
    for doc in (Simulation.__doc__, Simulation.run.__doc__, World.__doc__):
        assert doc is not None and "only at the end of each" in " ".join(doc.split())


@pytest.mark.parametrize("speed", [1e-300, 1e-4])
def test_a_speed_too_slow_for_the_time_limit_is_named(speed: float) -> None:
    # The times derived from it were refused as "times", an argument never given.
    with pytest.raises(ValueError, match=r"^speed .* too slow"):
        MovingObstacle.scripted(0.1, [(-1e6, -1e6), (1e6, 1e6)], speed=speed)
    ob = MovingObstacle.scripted(0.1, [(-1e6, -1e6), (1e6, 1e6)], speed=1e-2)
    assert ob.times[-1] == pytest.approx(2e6 * np.sqrt(2.0) / 1e-2)
