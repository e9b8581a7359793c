"""Long physics steps: no robot passes through a wall or into a solid; LiDAR inside a solid.

A step is checked at its end and, when it is long for the footprint (a point of
the footprint moves farther than the radius of a disc inside it), along its
arc too: a fast robot or a low physics rate used to carry a robot through a
thin wall or wholly into a solid polygon or disc without a collision, in every
kind of world (segments and circles only, with an occupancy grid, with moving
obstacles). A LiDAR inside a solid reads 0 on every beam, as inside a blocked
grid cell (it read the solid's far side).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Polygon, box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import (
    Circle,
    Controller,
    Lidar,
    MovingObstacle,
    Observation,
    Robot,
    Simulation,
    Trace,
    World,
)

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
OMNI = OmniDrive([0.0, 2.0944, 4.1888], wheel_radius=0.05, base_radius=0.2)
WALL_X = 1.0
THIN_WALL = LineString([(WALL_X, -3.0), (WALL_X, 3.0)])
#: Far from everything: a moving obstacle makes the simulation use its full kernel.
FAR_BALL = MovingObstacle.constant_velocity(0.1, start_xy=(-5.0, 5.0), velocity_xy=(0.0, 0.1))


def robot(footprint: object, drive: DiffDrive | OmniDrive = DIFF) -> Robot:
    # No encoders: their 50 Hz default may not exceed the low physics rates used here.
    return Robot(drive=drive, footprint=footprint, encoders=None)


def twist(vx: float, vy: float = 0.0, omega: float = 0.0) -> Controller:
    def controller(_obs: Observation) -> Twist2D:
        return Twist2D(vx, vy, omega)

    return controller


def run(
    world: World,
    bot: Robot,
    start: tuple[float, float, float],
    controller: Controller | None = None,
    **options: Any,
) -> Trace:
    """A run at 5 Hz (physics and control) for 3 s, by default at 2 m/s straight ahead."""
    settings_: dict[str, Any] = {"rate": 5.0, "control_rate": 5.0, "duration": 3.0, **options}
    return Simulation(
        world, bot, controller or twist(2.0), start=start, **settings_
    ).run()


def grid_wall() -> OccupancyGrid:
    """A 5 cm thick wall (one column of cells) over x in [0.5, 0.55]."""
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[:, 30] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05, origin=(-1.0, -1.0, 0.0))


# ------------------------------------------------------------------ the simulation
@pytest.mark.parametrize(
    "world",
    [
        World(THIN_WALL),  # a wall line
        World(box(WALL_X, -3.0, WALL_X + 0.05, 3.0)),  # a thin solid polygon
        World(box(WALL_X, -3.0, WALL_X + 3.0, 3.0)),  # a solid the robot lands inside
        World([THIN_WALL], moving=[FAR_BALL]),  # the full kernel, without a grid
        World([box(WALL_X, -3.0, WALL_X + 3.0, 3.0)], grid=OccupancyGrid.from_occupancy(
            np.zeros((4, 4), dtype=bool), resolution=0.1, origin=(-5.0, -5.0, 0.0))),
    ],
    ids=["line", "thin-polygon", "into-solid", "with-moving", "with-grid"],
)
def test_a_fast_disc_stops_at_the_wall_instead_of_passing_it(world: World) -> None:
    # 0.4 m per step, a 0.1 m disc: ends of steps at x = 0.03, 0.43, 0.83, 1.23, ...
    # none of which touches the wall at x = 1 (the old check saw no collision).
    trace = run(world, robot(0.1), (0.03, 0.0, 0.0))
    assert trace.metrics.reason == "collision"
    assert trace.metrics.collisions == 1
    assert trace.metrics.min_clearance == 0.0
    x, y, theta = trace.poses[-1]
    # It stops where it first touches the wall, on the near side, not past it.
    assert world.collides(0.1, (x, y, theta))
    assert x < WALL_X
    assert x > 0.83  # after the last free end of a step
    assert np.all(trace.poses[:, 0] < WALL_X)


def test_a_fast_disc_does_not_pass_through_a_solid_circle() -> None:
    # Ends of steps at 1.63 and 2.03 lie wholly inside the disc of radius 0.6.
    world = World(Circle(np.array([2.0, 0.0]), 0.6))
    trace = run(world, robot(0.1), (0.03, 0.0, 0.0))
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(0.1, (x, y, theta))
    assert 1.23 < x < 2.0 - 0.6


def test_a_fast_robot_does_not_leave_a_circular_room() -> None:
    """A non-solid circle is a wall: from its centre, 1.6 m steps would jump its rim."""
    room = World(Circle(np.array([0.0, 0.0]), 1.0, solid=False))
    trace = run(room, robot(0.05), (0.0, 0.0, 0.0), twist(8.0))
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert room.collides(0.05, (x, y, theta))
    assert x < 1.0


def test_a_fast_robot_does_not_pass_a_thin_grid_wall() -> None:
    world = World(grid=grid_wall())
    # 0.4 m per step, a 0.05 m disc: step ends at 0.4 and 0.8 are both free.
    trace = run(world, robot(0.05), (0.0, 0.0, 0.0))
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(0.05, (x, y, theta))
    assert x < 0.5


def test_a_fast_polygon_robot_does_not_pass_a_thin_wall() -> None:
    # A footprint 0.1 m deep in the direction of travel, 0.4 m wide.
    plank = [[-0.05, -0.2], [0.05, -0.2], [0.05, 0.2], [-0.05, 0.2]]
    world = World(THIN_WALL)
    trace = run(world, robot(plank), (0.03, 0.0, 0.0))
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(plank, (x, y, theta))
    assert x < WALL_X


def test_a_spinning_stick_does_not_sweep_through_a_post() -> None:
    """Rotation counts: the tips of a 1 m stick turning 0.6 rad per step move 0.3 m."""
    stick = [[-0.5, -0.01], [0.5, -0.01], [0.5, 0.01], [-0.5, 0.01]]
    # A post between the stick's first two headings (0 and 0.6 rad), clear of both.
    post = Circle(np.array([0.4 * math.cos(0.3), 0.4 * math.sin(0.3)]), 0.02)
    world = World(post)
    assert not world.collides(stick, (0.0, 0.0, 0.0))
    assert not world.collides(stick, (0.0, 0.0, 0.6))
    trace = run(
        world, robot(stick), (0.0, 0.0, 0.0), twist(0.0, omega=6.0), rate=10.0,
        duration=0.5,  # headings up to 3 rad: none of the steps' ends touches the post
    )  # fmt: skip
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(stick, (x, y, theta))
    assert 0.0 < theta < 0.6


def test_an_omnidirectional_robot_sliding_sideways_stops_at_the_wall() -> None:
    world = World(LineString([(-3.0, WALL_X), (3.0, WALL_X)]))
    trace = run(world, robot(0.1, OMNI), (0.0, 0.03, 0.0), twist(0.0, 2.0))
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(0.1, (x, y, theta))
    assert y < WALL_X


def test_without_ending_on_collision_the_robot_stays_on_its_side() -> None:
    world = World([THIN_WALL, box(-3.0, -3.0, 5.0, 3.0).exterior])
    trace = run(world, robot(0.1), (0.03, 0.0, 0.0), end_on_collision=False)
    assert trace.metrics.reason == "timeout"
    # Pushing on against the wall is one collision; the robot is held before it.
    assert trace.metrics.collisions == 1
    assert np.all(trace.poses[:, 0] < WALL_X - 0.1)
    assert trace.poses[-1][0] == pytest.approx(0.83)


def test_a_step_ending_in_contact_is_recorded_as_before() -> None:
    """The sweep is checked only when the end of the step is free: that end is the pose."""
    world = World(THIN_WALL)
    # Step ends at 0.1, 0.5, 0.9: the last overlaps the wall by 0.1 m.
    trace = run(world, robot(0.2), (0.1, 0.0, 0.0))
    assert trace.metrics.reason == "collision"
    assert trace.poses[-1][0] == pytest.approx(0.9, abs=1e-12)


@settings(max_examples=60)
@given(
    radius=st.floats(0.02, 0.3),
    speed=st.floats(0.5, 6.0),
    rate=st.floats(1.0, 40.0),
    heading=st.floats(-1.0, 1.0),
    gap=st.floats(0.01, 2.0),
    thick=st.booleans(),
)
def test_no_straight_run_crosses_a_wall(
    radius: float, speed: float, rate: float, heading: float, gap: float, thick: bool
) -> None:
    """Driving straight at a wall always ends touching it, never past it nor inside it."""
    start_x = WALL_X - radius - gap
    wall = box(WALL_X, -50.0, WALL_X + 20.0, 50.0) if thick else LineString(
        [(WALL_X, -50.0), (WALL_X, 50.0)]
    )
    world = World(wall)
    reach_wall = (gap + 0.1) / (speed * math.cos(heading))
    trace = run(
        world, robot(radius), (start_x, 0.0, heading), twist(speed), rate=rate,
        control_rate=rate, duration=reach_wall + 3.0 / rate,
    )  # fmt: skip
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    # On the wall's boundary (a footprint inside the solid would be clear of it)...
    assert world.clearance(radius, (x, y, theta)) <= 1e-12
    # ... where a step ends overlapping it, or earlier; free on the near side before.
    assert np.all(trace.poses[:-1, 0] + radius < WALL_X)


# ------------------------------------------------------------------ the LiDAR
def lidar(range_min: float = 0.0) -> Lidar:
    return Lidar(n_beams=16, noise=None, range_min=range_min)


ANGLES = np.linspace(-math.pi, math.pi, 16, endpoint=False)


@pytest.mark.parametrize(
    ("world", "origin"),
    [
        (World(box(0.0, 0.0, 2.0, 2.0)), (1.0, 1.3)),
        (World(Circle(np.array([5.0, 5.0]), 1.0)), (5.2, 4.9)),
        (World([box(0.0, 0.0, 2.0, 1.0), box(1.0, 0.0, 3.0, 1.0)]), (1.5, 0.5)),  # overlap
        (World(moving=[MovingObstacle.constant_velocity(
            box(-0.5, -0.5, 0.5, 0.5), start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.0))]),
         (2.1, 0.2)),
        (World(moving=[FAR_BALL]), (-5.0, 5.25)),
        (World(grid=grid_wall()), (0.52, 0.0)),
    ],
    ids=["polygon", "circle", "overlapping", "moving-polygon", "moving-disc", "grid"],
)
def test_a_lidar_inside_a_solid_reads_zero_on_every_beam(
    world: World, origin: tuple[float, float]
) -> None:
    pose = (*origin, 0.3)
    np.testing.assert_array_equal(world.raycast(pose, ANGLES, range_max=10.0, t=2.0), 0.0)
    scan = lidar().scan(world, pose, t=2.0)
    np.testing.assert_array_equal(scan.ranges, 0.0)
    # Too close for a sensor with a minimum range, as REP 117 reports it.
    scan = lidar(range_min=0.1).scan(world, pose, t=2.0)
    assert np.all(scan.ranges == -np.inf)


def test_a_lidar_outside_the_solids_is_unchanged() -> None:
    """In a hole, inside a non-solid circle, beside a solid: the nearest boundary."""
    holed = Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (3, 1), (3, 3), (1, 3)]])
    world = World([holed, Circle(np.array([10.0, 0.0]), 2.0, solid=False)])
    ranges = world.raycast((2.0, 1.5, 0.0), [0.0, math.pi / 2, math.pi], range_max=10.0)
    np.testing.assert_allclose(ranges, [1.0, 1.5, 1.0], rtol=0.0, atol=1e-12)
    ranges = world.raycast((10.5, 0.0, 0.0), [0.0, math.pi], range_max=10.0)
    np.testing.assert_allclose(ranges, [1.5, 2.5], rtol=0.0, atol=1e-12)
    ranges = world.raycast((5.0, 3.0, 0.0), [0.0, math.pi], range_max=10.0)
    np.testing.assert_allclose(ranges, [np.inf, 1.0], rtol=0.0, atol=1e-12)


def test_the_lidar_agrees_with_shapely_on_inside_and_outside() -> None:
    """Random origins among overlapping and holed polygons and discs (both walk directions)."""
    rng = np.random.default_rng(7)
    shapes: list[Polygon] = []
    for _ in range(40):
        cx, cy = rng.uniform(0.0, 10.0, 2)
        k = int(rng.integers(3, 8))
        angles = np.sort(rng.uniform(0.0, 2.0 * math.pi, k))
        r = rng.uniform(0.2, 1.2, k)
        poly = Polygon(np.column_stack((cx + r * np.cos(angles), cy + r * np.sin(angles))))
        if poly.is_valid:
            shapes.append(poly)
    shapes.append(box(2.0, 2.0, 8.0, 8.0).difference(box(3.0, 3.0, 7.0, 7.0)))
    discs = [Circle(rng.uniform(0.0, 10.0, 2), float(rng.uniform(0.1, 0.8))) for _ in range(15)]
    world = World([*shapes, *discs, box(-1.0, -1.0, 11.0, 11.0).exterior])
    solid = shapely.union_all(
        [*shapes, *(shapely.Point(c.center_xy).buffer(c.radius, quad_segs=256) for c in discs)]
    )
    n_inside = 0
    for x, y in rng.uniform(-0.5, 10.5, (400, 2)):
        if shapely.distance(solid.boundary, shapely.Point(x, y)) < 1e-3:
            continue  # a disc's polygon stands in for it to about 2e-5 m
        inside = bool(shapely.contains_xy(solid, x, y))
        ranges = world.raycast((x, y, 0.0), ANGLES, range_max=30.0)
        n_inside += inside
        assert np.all(ranges == 0.0) == inside, (x, y)
        assert np.any(ranges == 0.0) == inside, (x, y)
    assert 50 < n_inside < 350


def test_inside_is_exact_on_a_vertex_s_horizontal_and_along_long_edges() -> None:
    """The even-odd count along the origin's row: a vertex on it counts once; edges spanning
    many cells of the index count once."""
    diamond = Polygon([(0.0, 5.0), (5.0, 0.0), (10.0, 5.0), (5.0, 10.0)])
    # Many small squares make the index cells small beside the diamond's long edges.
    specks = [box(x, 12.0, x + 0.05, 12.05) for x in np.linspace(0.0, 10.0, 60)]
    world = World([diamond, *specks])
    beams = ANGLES
    for x in (0.5, 2.0, 4.999, 5.0, 7.5, 9.5):  # on the horizontal through two vertices
        np.testing.assert_array_equal(world.raycast((x, 5.0, 0.0), beams, range_max=30.0), 0.0)
    for x in (-1.0, 10.5):
        assert np.all(world.raycast((x, 5.0, 0.0), beams, range_max=30.0) > 0.0)
    for y in (0.5, 9.5):  # near the bottom and top vertices, inside and out
        np.testing.assert_array_equal(world.raycast((5.0, y, 0.0), beams, range_max=30.0), 0.0)
        assert np.all(world.raycast((5.6, y, 0.0), beams, range_max=30.0) > 0.0)
