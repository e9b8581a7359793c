"""One vocabulary for the simulator (session 15's audit, rows 7, 11, 13 and 17).

* ``Simulation(goal_radius=, goal_yaw_tolerance=)`` are now ``goal_tolerance=``
  and ``yaw_tolerance=``, the controllers' names.
* ``MovingObstacle.scripted(shape, waypoints_xy, *, loop=)`` is now
  ``scripted(shape, path_xy, *, after=)``, the class's own words (and so
  ``after="extend"`` can be asked for).
* ``Lidar.scan(rng=)`` is now ``seed=``, as ``Simulation``.
* ``WheelEncoders.counts()`` is now ``ticks()``, what ``EncoderReading.ticks`` holds.

The old names still work, give the same results and warn ``DeprecationWarning``;
an old and a new name together are a ``TypeError``.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Circle,
    Lidar,
    MovingObstacle,
    Observation,
    Robot,
    Simulation,
    WheelEncoders,
    World,
)

ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.4, 0.0, 0.3)


def _sim(**options: Any) -> Simulation:
    return Simulation(World(), ROBOT, _forward, start=(0.0, 0.0, 0.0), duration=4.0, **options)


# --- Simulation(goal_tolerance=, yaw_tolerance=) ---------------------------------------


def test_simulation_new_names_are_used_without_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        loose = _sim(goal=(0.5, 0.1, 0.2), goal_tolerance=0.3, yaw_tolerance=math.pi).run()
        tight = _sim(goal=(0.5, 0.1, 0.2), goal_tolerance=0.3, yaw_tolerance=0.01).run()
    assert loose.metrics.reached
    # The heading requirement delays (or prevents) arriving.
    assert not tight.metrics.reached or tight.metrics.time_to_goal > loose.metrics.time_to_goal


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ({"goal_radius": 0.3}, {"goal_tolerance": 0.3}),
        ({"goal_yaw_tolerance": 0.5}, {"yaw_tolerance": 0.5}),
    ],
)
def test_simulation_old_names_warn_and_give_the_same_run(
    old: dict[str, float], new: dict[str, float]
) -> None:
    (old_name,) = old
    (new_name,) = new
    goal = {"goal": (0.5, 0.1, 0.2), "goal_tolerance": 0.3}
    goal.update(new)
    want = _sim(**goal).run()
    del goal[new_name]
    goal.update(old)
    with pytest.warns(DeprecationWarning, match=f"{old_name} is deprecated.*use {new_name}") as rec:
        sim = _sim(**goal)
    assert rec[0].filename == __file__
    got = sim.run()
    np.testing.assert_array_equal(got.poses, want.poses)
    assert got.metrics.time_to_goal == want.metrics.time_to_goal
    with pytest.raises(TypeError, match=f"both {new_name} and its old name {old_name}"):
        _sim(goal=(0.5, 0.1, 0.2), **old, **{new_name: 0.2})


def test_simulation_errors_name_the_keyword_the_caller_wrote() -> None:
    with pytest.raises(ValueError, match=r"^goal_tolerance must"):
        _sim(goal=(1.0, 0.0), goal_tolerance=0.0)
    with pytest.raises(ValueError, match=r"^yaw_tolerance needs a goal with a heading"):
        _sim(goal=(1.0, 0.0), yaw_tolerance=0.1)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r"^goal_radius must"):
        _sim(goal=(1.0, 0.0), goal_radius=2e6)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r"^goal_yaw_tolerance"):
        _sim(goal=(1.0, 0.0, 0.0), goal_yaw_tolerance=4.0)


# --- MovingObstacle.scripted(path_xy, after=) ------------------------------------------

PATH = [(0.0, 0.0), (2.0, 0.0)]


def test_scripted_takes_after_including_extend() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ob = {a: MovingObstacle.scripted(0.2, path_xy=PATH, speed=0.5, after=a)
              for a in ("stop", "loop", "extend")}  # fmt: skip
    assert [ob[a].after for a in ("stop", "loop", "extend")] == ["stop", "loop", "extend"]
    np.testing.assert_array_equal(ob["stop"].position_at(5.0), [2.0, 0.0])
    np.testing.assert_array_equal(ob["loop"].position_at(5.0), [0.5, 0.0])
    np.testing.assert_array_equal(ob["extend"].position_at(5.0), [2.5, 0.0])
    with pytest.raises(ValueError, match="after"):
        MovingObstacle.scripted(0.2, PATH, speed=0.5, after="bounce")  # type: ignore[arg-type]


@pytest.mark.parametrize("loop", [True, False])
def test_scripted_loop_warns_and_means_after(loop: bool) -> None:
    want = MovingObstacle.scripted(0.2, PATH, speed=0.5, after="loop" if loop else "stop")
    with pytest.warns(DeprecationWarning, match="loop is deprecated.*use after") as rec:
        got = MovingObstacle.scripted(0.2, PATH, speed=0.5, loop=loop)
    assert rec[0].filename == __file__
    assert got.after == want.after
    np.testing.assert_array_equal(got.times, want.times)
    with pytest.raises(TypeError, match="both after and its old name loop"):
        MovingObstacle.scripted(0.2, PATH, speed=0.5, loop=loop, after="extend")
    with pytest.raises(TypeError, match="loop"):
        MovingObstacle.scripted(0.2, PATH, speed=0.5, loop="yes")  # type: ignore[arg-type]


def test_scripted_waypoints_xy_warns_and_means_path_xy() -> None:
    want = MovingObstacle.scripted(0.2, PATH, times=[0.0, 1.0])
    with pytest.warns(DeprecationWarning, match="waypoints_xy is deprecated.*use path_xy") as rec:
        got = MovingObstacle.scripted(0.2, waypoints_xy=PATH, times=[0.0, 1.0])
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(got.path_xy, want.path_xy)
    np.testing.assert_array_equal(got.times, want.times)
    with pytest.raises(TypeError, match="both path_xy and its old name waypoints_xy"):
        MovingObstacle.scripted(0.2, PATH, waypoints_xy=PATH, times=[0.0, 1.0])
    with pytest.raises(TypeError, match="path_xy"):
        MovingObstacle.scripted(0.2, times=[0.0, 1.0])


def test_scripted_errors_name_the_keyword_the_caller_wrote() -> None:
    with pytest.raises(ValueError, match=r"^path_xy must not repeat"):
        MovingObstacle.scripted(0.2, [(0.0, 0.0), (0.0, 0.0)], speed=1.0)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r"^waypoints_xy must"):
        MovingObstacle.scripted(0.2, waypoints_xy=[(0.0, 0.0), (0.0, 0.0)], speed=1.0)


# --- Lidar.scan(seed=) ------------------------------------------------------------------

WORLD = World(Circle((0.0, 0.0), 3.0, solid=False))
LIDAR = Lidar(n_beams=16, dropout=0.2)


def test_lidar_scan_seed_is_the_randomness() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a = LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=3).ranges
        b = LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=np.random.default_rng(3)).ranges
        c = LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=4).ranges
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c, equal_nan=True)


def test_lidar_scan_rng_warns_and_gives_the_same_scan() -> None:
    want = LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=3).ranges
    with pytest.warns(DeprecationWarning, match="rng is deprecated.*use seed") as rec:
        got = LIDAR.scan(WORLD, (0.5, 0.0, 0.0), rng=3).ranges
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(got, want)
    with pytest.raises(TypeError, match="both seed and its old name rng"):
        LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=3, rng=3)
    with pytest.raises(ValueError, match=r"^seed must be >= 0"):
        LIDAR.scan(WORLD, (0.5, 0.0, 0.0), seed=-1)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r"^rng must be >= 0"):
        LIDAR.scan(WORLD, (0.5, 0.0, 0.0), rng=-1)


# --- WheelEncoders.ticks() --------------------------------------------------------------


def test_wheel_encoders_ticks_and_its_deprecated_alias() -> None:
    encoders = WheelEncoders(ticks_per_rev=1024, bits=10)
    angles = np.array([0.5, 2.0, -0.0001]) * 2.0 * math.pi  # turns
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ticks = encoders.ticks(angles)
    assert ticks.tolist() == [512, 0, 1023]
    with pytest.warns(DeprecationWarning, match="counts is deprecated.*WheelEncoders.ticks") as rec:
        counts = encoders.counts(angles)
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(counts, ticks)
