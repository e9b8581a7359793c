"""User code written the way navkit's docstrings and docs/ call the public API.

Not collected by pytest: ``tests/test_review10_user_typing.py`` runs ``mypy --strict``
on it, so an annotation narrower than the documented input (e.g. ``NDArray`` where
array_like is accepted) or a public name a type checker cannot see fails the test.
"""

from __future__ import annotations

import math
from typing import assert_type

import numpy as np
from numpy.typing import NDArray

from navkit.behaviours import BehaviourTarget, GameState, attack
from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.estimation import CompassCalibration, compass_to_yaw
from navkit.geometry import (
    ImuInBase,
    Pose2D,
    Twist2D,
    angle_diff,
    imu_to_base,
    quaternion_to_yaw,
    wrap_angle,
    yaw_to_quaternion,
)
from navkit.kinematics import DiffDrive, tick_delta, ticks_to_distance
from navkit.mapping import LaserScan, OccupancyGrid, validate_costs
from navkit.mapping.io import (
    BagImu,
    BagOdometry,
    BagScans,
    OccupancyGridMsgFields,
    read_bag_imu,
    read_bag_odometry,
)
from navkit.planning import *  # noqa: F403  (a user's star import must see the names)
from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
)
from navkit.sim import (
    Circle,
    Compass,
    MovingObstacle,
    Observation,
    Reading,
    Robot,
    Simulation,
    World,
)


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


def records_of_bags_and_messages() -> None:
    # Review 11: these records took their arrays as NDArray only, though documented
    # (and converted) as array_like.
    scan = LaserScan([1.0, 2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    BagScans("/scan", "laser", [1.5], [1.6], (scan,))
    eye = np.eye(6)[None]
    BagOdometry(
        "/odom", "odom", "base_link", [0.0], [0.0], [[1.0, 2.0, 0.5]],
        [[0.0, 0.0, 0.0, 1.0]], [[0.3, 0.0, 0.1]], eye, eye,
    )
    cov = np.eye(3)[None]
    BagImu("/imu", "imu_link", [0.0], [0.0], [[0.0, 0.0, 0.0, 1.0]], [[0.0, 0.0, 0.2]],
           [[0.0, 0.0, 9.8]], cov, cov, cov)
    OccupancyGridMsgFields(2, 1, 0.1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), [100, -1])
    MovingObstacle(0.2, [(0, 0), (2, 0), (2, 2)], [1.0, 3.0, 5.0], after="loop")
    MovingObstacle([(0.1, 0.0), (0.0, 0.1), (-0.1, 0.0)], [[0.0, 0.0]], (0.0,))


def documented_examples_as_typed_code() -> None:
    # The typed forms the docs show (review 11), kept type-checking.
    fields = [ConicAttraction((1.0, 0.0)), KhatibRepulsion([[0.5, 0.5]], influence_radius=0.5)]
    total = sum(fields, CompositeField([]))
    assert_type(total, PotentialField)
    total.force([0.0, 0.0])
    imu = imu_to_base(
        yaw_to_quaternion(0.5), [0.0, 0.0, 0.2], [0.0, -1.0, 9.8], mounting=yaw_to_quaternion(0.1)
    )
    assert_type(round(float(quaternion_to_yaw(imu.orientations)), 6), float)
    validate_costs([[1.0, 2.0], [np.inf, 1.5]])
    grid = OccupancyGrid.empty(width=4.0, height=2.0, resolution=0.5)
    grid.cell_to_world([(3, 0), (-0.5, -0.5)])


class CompassHeading:
    """An Estimator written as the ``navkit.sim.Estimator`` docstring writes it."""

    def __init__(self, north: float) -> None:
        self.north, self.readings = north, 0
        self.pose: Pose2D | None = None

    def observe(self, t: float, reading: Reading) -> None:
        self.readings += 1


AnyTracker = FollowTheCarrot | OnOffTracker | RegulatedPurePursuit


class Tracker:
    """The controller of docs/tutorials/controller-loop.md."""

    def __init__(self, tracker: AnyTracker) -> None:
        self.tracker = tracker

    @property
    def done(self) -> bool:
        return self.tracker.done

    def __call__(self, obs: Observation) -> Twist2D:
        return self.tracker.step(obs.true_pose, 0.05)


def simulation_with_typed_callbacks() -> None:
    def forward(obs: Observation) -> Twist2D:
        return Twist2D(0.5, 0.0, 0.0)

    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
                  compass=Compass(rate=10.0))
    trace = Simulation(World(), robot, forward, start=(0.0, 0.0, 0.0), duration=1.0,
                       estimator=CompassHeading(north=math.pi / 2)).run()
    assert_type(trace.metrics.reached, bool)
    trackers: dict[str, AnyTracker] = {"carrot": FollowTheCarrot(max_speed=0.3)}
    Simulation(World(), robot, Tracker(trackers["carrot"]), start=(0.0, 0.0, 0.0))


def wrong_types_the_docs_show_refused() -> None:
    # Never run: the docstrings show these raising TypeError; a type checker flags them too.
    read_bag_odometry("missing.bag", topic=3)  # type: ignore[arg-type]
    read_bag_imu(b"imu.bag")  # type: ignore[arg-type]
