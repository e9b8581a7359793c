"""User code written the way navkit's docstrings and docs/ call the public API.

Not collected by pytest: ``tests/test_review10_user_typing.py`` runs ``mypy --strict``
on it, so an annotation narrower than the documented input (e.g. ``NDArray`` where
array_like is accepted) or a public name a type checker cannot see fails the test.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from typing_extensions import assert_type

from navkit.behaviours import BehaviourTarget, GameState, attack
from navkit.estimation import CompassCalibration, compass_to_yaw
from navkit.geometry import (
    ImuInBase,
    Pose2D,
    angle_diff,
    quaternion_to_yaw,
    wrap_angle,
    yaw_to_quaternion,
)
from navkit.kinematics import tick_delta, ticks_to_distance
from navkit.mapping import LaserScan
from navkit.planning import *  # noqa: F403  (a user's star import must see the names)
from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
)
from navkit.sim import Circle


def star_import() -> None:
    # Names reached only through the star import above.
    assert_type(astar([[1.0, 1.0]], (0, 0), (0, 1)), Path2D)  # noqa: F405
    assert_type(AStarPlanner([[1.0, 1.0]]), AStarPlanner)  # noqa: F405


def array_like_constructors() -> None:
    scan = LaserScan(
        [1.0, 2.0, math.inf],
        angle_min=0.0,
        angle_increment=math.pi / 2,
        range_min=0.1,
        range_max=5.0,
        intensities=(1, 2, 3),
    )
    assert_type(scan.to_points(Pose2D(0.0, 0.0, 0.0)), NDArray[np.float64])
    Circle((1.0, 2.0), 0.5, solid=False)
    BehaviourTarget((1.0, 0.0), [[0.5, 0.5]])
    state = GameState(
        robot_xy=(0.0, 0.0),
        ball_xy=[1.0, 0.0],
        teammates_xy=[[2.0, 2.0]],
        opponents_xy=[[3.0, 0.0]],
        own_goal_xy=(-4.5, 0.0),
        opponent_goal_xy=(4.5, 0.0),
        possession_radius=0.3,
    )
    attack(state)
    ImuInBase(yaw_to_quaternion(0.5), [0.0, 0.0, 0.2], [[0.0, -1.0, 9.8]][0])


def fields() -> None:
    total = ConicAttraction((5.0, 0.0), m=1.0) + KhatibRepulsion(
        [[1.0, 0.0]], influence_radius=2.0
    )
    assert_type(total, CompositeField)
    assert_type(len(total.fields), int)
    ParaboloidAttraction([1.0, 1.0], k_att=2.0)
    BlendedAttraction((1.0, 1.0), threshold_radius=0.5)
    PiecewiseAttraction((1.0, 1.0), spread=1.0)
    PiecewiseRepulsion([(0.0, 1.0)], delta=1.0)


def scalar_or_array_results() -> None:
    # A list or tuple gives an array, one quaternion a float: the results are used as such.
    q = [0.0, 0.0, math.sin(0.25), math.cos(0.25)]
    assert_type(round(quaternion_to_yaw(q), 6), float)
    assert_type(round(quaternion_to_yaw(tuple(q)), 6), float)
    assert_type(quaternion_to_yaw([q, [0.0, 0.0, 0.0, 0.0]]), NDArray[np.float64])
    assert_type(compass_to_yaw([10.0, 350.0], initial_deg=20.0), NDArray[np.float64])
    assert_type(compass_to_yaw((170.0, 190.0), unwrap=True), NDArray[np.float64])
    assert_type(CompassCalibration()([45.0, 135.0]), NDArray[np.float64])
    assert_type(wrap_angle([3.0, 4.0]), NDArray[np.float64])
    assert_type(wrap_angle([[3, 4]]), NDArray[np.float64])
    assert_type(angle_diff([0.1, 0.2], 0.3), NDArray[np.float64])
    assert_type(angle_diff(0.3, (0.1, 0.2)), NDArray[np.float64])
    distances = ticks_to_distance([1024, 2048], ticks_per_rev=2048, wheel_radius=0.1)
    assert_type(distances, NDArray[np.float64])
    assert_type(tick_delta([65535, 0], 2, bits=16), NDArray[np.int64])
    assert_type(tick_delta(5, (65534,), bits=16), NDArray[np.int64])
    # As the docstrings call them.
    quaternion_to_yaw([q, q]).round(6)
    compass_to_yaw([10.0, 350.0], initial_deg=20.0).round(4)
    distances.round(3)
    # Scalars and arrays keep their types.
    assert_type(wrap_angle(4.0), float)
    assert_type(compass_to_yaw(90.0), float)
    assert_type(tick_delta(65535, 2, bits=16), int)
    assert_type(quaternion_to_yaw(np.array([q])), "float | NDArray[np.float64]")


def array_like_records() -> None:
    GreedyStep((10, 12), (0.2, 0.0), g=0.2, h=1.8, candidates=440)  # noqa: F405
    Path2D([[0, 0], [1, 1], [1, 2]], "grid", cost=2.414, length=2.414, expanded=3)  # noqa: F405
    SampledField(  # noqa: F405
        [0.5, 1.5], [0.5], [[1.0, 2.0]], np.zeros((1, 2, 2)), resolution=1.0
    )
    assert_type(CompositeField([]).potential([0.0, 0.0]), NDArray[np.float64])
    CompositeField(field for field in [ConicAttraction((1.0, 0.0))])


def cells_may_be_lists_or_numpy_integers() -> None:
    astar([[1.0, 1.0]], np.unravel_index(0, (1, 2)), [0, 1])  # noqa: F405


def cells_are_pairs_of_ints() -> None:
    # Never run: a type checker must flag a cell that is not a sequence of integers (with
    # --strict an ignore that silences nothing is itself an error).
    astar([[1.0, 1.0]], (0.5, 0.0), (0, 1))  # type: ignore[arg-type]  # noqa: F405
    AStarPlanner([[1.0, 1.0]]).plan((0, 0), [0, 1.0])  # type: ignore[list-item]  # noqa: F405
    distance_field([[1.0, 1.0]], "0, 1")  # type: ignore[arg-type]  # noqa: F405
