"""A World does not depend on how its obstacles are listed (review 31, METAMORPH).

The same static obstacles given in another order, or grouped into one multi-part
geometry (a ``MultiPolygon`` of the polygons, a ``GeometryCollection`` of the
polygons and walls), and the moving obstacles in another order, describe the same
world: every query (:meth:`World.raycast`, :meth:`World.clearance`,
:meth:`World.collides`, :meth:`Lidar.scan`) must give the same numbers bit for
bit (the index holds the same edges and circles; a ray's first hit and a
clearance are minima, which do not depend on the order their candidates come
in), and so must a closed-loop :class:`Simulation` run: poses, commands, scans,
events and metrics. review 8 moved and mirrored the world; this is the listing.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import GeometryCollection, LineString, MultiPolygon, box

from hypothesis_twins import slow_twin
from navkit.control import RegulatedPurePursuit
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Circle,
    Lidar,
    MovingObstacle,
    Robot,
    Simulation,
    Trace,
    TrackerController,
    World,
)

ANGLES = np.linspace(-math.pi, math.pi, 97)[:-1]


def _scene(rng: np.random.Generator) -> list[Any]:
    """A room's walls, then boxes, wall segments and circles (solid or not)."""
    obstacles: list[Any] = [box(-6.0, -6.0, 6.0, 6.0).exterior]
    for _ in range(int(rng.integers(2, 9))):
        kind = int(rng.integers(0, 3))
        x, y = rng.uniform(-5.0, 5.0, 2)
        if kind == 0:
            w, h = rng.uniform(0.1, 1.5, 2)
            obstacles.append(box(x, y, x + w, y + h))
        elif kind == 1:
            dx, dy = rng.uniform(-3.0, 3.0, 2)
            obstacles.append(LineString([(x, y), (x + dx, y + dy)]))
        else:
            radius = float(rng.uniform(0.1, 0.8))
            obstacles.append(Circle((x, y), radius, solid=bool(rng.random() < 0.7)))
    return obstacles


def _regrouped(obstacles: list[Any], rng: np.random.Generator) -> list[Any]:
    """The same obstacles, shuffled, with the shapely ones in one or two multi-part geometries."""
    shuffled = [obstacles[i] for i in rng.permutation(len(obstacles))]
    shapes = [o for o in shuffled if not isinstance(o, Circle)]
    circles = [o for o in shuffled if isinstance(o, Circle)]
    polygons = [o for o in shapes if o.geom_type == "Polygon"]
    lines = [o for o in shapes if o.geom_type != "Polygon"]
    if rng.random() < 0.5 and polygons:
        grouped: list[Any] = [MultiPolygon(polygons), *lines]
    else:
        grouped = [GeometryCollection(shapes)]
    return [*circles, *grouped] if rng.random() < 0.5 else [*grouped, *circles]


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_queries_do_not_depend_on_the_listing(seed: int) -> None:
    rng = np.random.default_rng(seed)
    obstacles = _scene(rng)
    world = World(obstacles)
    other = World(_regrouped(obstacles, rng))
    lidar = Lidar(n_beams=45, noise=None, range_min=0.05, range_max=20.0)
    for _ in range(5):
        pose = (*rng.uniform(-6.5, 6.5, 2), float(rng.uniform(-math.pi, math.pi)))
        np.testing.assert_array_equal(
            other.raycast(pose, ANGLES, range_max=20.0), world.raycast(pose, ANGLES, range_max=20.0)
        )
        np.testing.assert_array_equal(
            lidar.scan(other, pose).ranges, lidar.scan(world, pose).ranges
        )
        footprint: Any = box(-0.3, -0.2, 0.3, 0.2)
        if rng.random() < 0.5:
            footprint = float(rng.uniform(0.05, 0.5))
        assert other.clearance(footprint, pose) == world.clearance(footprint, pose)
        assert other.collides(footprint, pose) == world.collides(footprint, pose)


test_queries_do_not_depend_on_the_listing_thoroughly = slow_twin(
    test_queries_do_not_depend_on_the_listing, max_examples=150
)


def _run(world: World) -> Trace:
    tracker = RegulatedPurePursuit()
    tracker.set_path([[0.5, 0.5], [4.0, 0.5], [4.0, 3.5]])
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15, lidar=Lidar(n_beams=90)
    )
    return Simulation(
        world,
        robot,
        TrackerController(tracker, control_rate=20.0, use_estimate=False),
        start=(0.5, 0.5, 0.0),
        goal=(4.0, 3.5),
        duration=20.0,
        record_scans=True,
        seed=3,
    ).run()


def _moving() -> list[MovingObstacle]:
    return [
        MovingObstacle.constant_velocity(0.2, start_xy=(3.0, 2.5), velocity_xy=(-0.3, 0.05)),
        MovingObstacle.constant_velocity(0.3, start_xy=(6.0, 3.0), velocity_xy=(0.0, -0.2)),
        MovingObstacle.scripted(
            0.15, [(1.0, 2.0), (2.0, 2.0), (2.0, 3.0)], speed=0.4, after="loop"
        ),
    ]


def test_a_run_does_not_depend_on_the_listing() -> None:
    statics: list[Any] = [
        box(-1.0, -1.0, 6.0, 5.0).exterior,
        box(2.0, 1.2, 3.0, 2.5),
        Circle((1.5, 2.5), 0.4),
        LineString([(5.0, 0.0), (5.0, 2.0)]),
        box(4.6, 3.0, 5.5, 4.0),
        Circle((0.2, 4.0), 0.3, solid=False),
    ]
    moving = _moving()
    base = _run(World(statics, moving=moving))
    assert base.metrics.distance > 3.0 and len(base.scans) > 50  # a real run, not a stall
    polygons = MultiPolygon([statics[1], statics[4]])
    for world in (
        World(statics[::-1], moving=moving[::-1]),
        World([statics[5], GeometryCollection([statics[3], polygons, statics[0]]), statics[2]],
              moving=moving[1:] + moving[:1]),
    ):  # fmt: skip
        trace = _run(world)
        np.testing.assert_array_equal(trace.times, base.times)
        np.testing.assert_array_equal(trace.poses, base.poses)
        np.testing.assert_array_equal(trace.commands, base.commands)
        assert len(trace.scans) == len(base.scans)
        for a, b in zip(trace.scans, base.scans, strict=True):
            np.testing.assert_array_equal(a.scan.ranges, b.scan.ranges)
        assert trace.events == base.events
        assert repr(trace.metrics) == repr(base.metrics)  # NaN fields compare by their text
