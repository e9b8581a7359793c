"""The simulator compiles each kernel once, and a scan's passes agree with one another.

A kernel compiled for two argument type sets (read-only next to writable
arrays, int32 next to int64, a literal next to a variable) pays its
compilation twice on first use (issue 17). The first test runs simulations on
every kind of world (segments and circles, occupancy grid, moving obstacles,
all of them, none) with disc and polygon footprints, every drive and sensor,
plus the world's public queries, in a fresh process, and checks that no
simulator kernel was specialised twice, but for the intended variant: a disc
footprint passes None for the polygon's arrays, so that a disc robot compiles
only the disc's distance code and a polygon only the polygon's. Steps long for
the footprint (checked along their arc) are data, not another variant: each
run kernel is compiled once per footprint kind (review 12; it was twice). The
second test checks that a disc robot's first simulation in a world of segments
and circles compiles one run kernel, for the disc, and nothing of the polygon's
or the grid's.

A scan is a pass over the segments and circles and then one over the
occupancy grid (a world compiles only the passes it needs): the other tests
check that a world with every kind of obstacle sees, beam by beam and bit for
bit, the nearest of what worlds with one kind each see.
"""

from __future__ import annotations

import math

import numpy as np
from shapely.geometry import box

from kernel_signatures import compiled_signatures
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, MovingObstacle, World

SCRIPT = """
import numpy as np
from shapely.geometry import box
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import (
    Circle, Compass, Imu, Lidar, MovingObstacle, Robot, Simulation, WheelEncoders, World,
)

occupied = np.zeros((30, 40), dtype=bool)
occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
moving = MovingObstacle.constant_velocity(0.2, start_xy=(3.0, 2.0), velocity_xy=(-0.1, 0.0))
walls = box(0.0, 0.0, 4.0, 3.0).exterior
worlds = [
    World([walls, Circle((2.5, 2.0), 0.2)]),
    World(grid=grid),
    World(moving=[moving]),
    World([walls, box(3.0, 0.5, 3.5, 1.0)], grid=grid, moving=[moving]),
    World([]),
]
diff = DiffDrive(track=0.3, wheel_radius=0.05)
omni = OmniDrive([0.0, 2.0944, 4.1888], wheel_radius=0.05, base_radius=0.2)
square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
robots = [
    Robot(drive=diff, footprint=0.15, lidar=Lidar(n_beams=8), max_wheel_acceleration=40.0),
    Robot(drive=diff, footprint=square, wheel_slip=0.01, lidar=Lidar(n_beams=8),
          encoders=WheelEncoders(), compass=Compass(), imu=Imu()),
    Robot(drive=omni, footprint=0.15, max_wheel_speed=20.0),
]
long_path = np.column_stack([np.linspace(1.0, 2.0, 40), np.ones(40)])  # the chunked kernel
references = ([[1.0, 1.0], [2.0, 1.0]], long_path, [[1.0, 1.0], [2.0, 1.0]])
for world in worlds:
    for robot, reference in zip(robots, references):
        Simulation(
            world, robot, lambda _obs: Twist2D(0.4, 0.0, 0.2), start=(1.0, 1.0, 0.0),
            goal=(1.5, 1.2), duration=0.2, reference_path=reference,
        ).run()
    # Steps of 0.4 m, long for these footprints: the run kernels' checking variants.
    for footprint in (0.15, square):
        Simulation(
            world, Robot(drive=diff, footprint=footprint, encoders=None),
            lambda _obs: Twist2D(4.0, 0.0, 0.0), start=(1.0, 1.0, 0.0), rate=10.0,
            control_rate=10.0, duration=0.3,
        ).run()
    world.clearance(0.15, (1.0, 1.0, 0.0))
    world.clearance(square, (1.0, 1.0, 0.3))
    world.collides(0.15, (1.0, 1.0, 0.0))
    world.raycast((1.0, 1.0, 0.0), np.linspace(-1.0, 1.0, 5), range_max=5.0)
moving.position_at(1.0)
"""


def test_every_simulator_kernel_is_compiled_for_one_signature() -> None:
    signatures = compiled_signatures(SCRIPT, [f"navkit.sim.{name}" for name in (
        "_clearance_kernels", "_lidar_kernels", "_moving_kernels", "_polyline_distance_kernels",
        "_segment_kernels", "_wheel_kernels",
    )] + ["navkit._shared.se2"])  # fmt: skip
    # The kernels Python calls (a cached caller loads its callees' code with it).
    for name in ("_lidar_kernels.cast_edge_rays", "_lidar_kernels.cast_occupancy_rays",
                 "_lidar_kernels.apply_range_noise", "_segment_kernels.run_segment",
                 "_segment_kernels.run_edge_segment", "_clearance_kernels.footprint_clearance",
                 "_clearance_kernels.edge_clearance", "_moving_kernels.place_moving",
                 "_polyline_distance_kernels.point_polyline_distances",
                 "_polyline_distance_kernels.point_polyline_distances_chunked"):  # fmt: skip
        assert name in signatures, name
    twice = {
        name: sigs for name, sigs in signatures.items()
        if len(sigs) > 4 or not all(
            _disc_and_polygon(a, b) for k, a in enumerate(sigs) for b in sigs[k + 1:]
        )
    }  # fmt: skip
    assert not twice, twice
    # Both footprints were simulated: the footprint kernels hold one of each.
    for name in ("_clearance_kernels.footprint_clearance", "_clearance_kernels.edge_clearance"):
        assert len(signatures[name]) == 2, signatures[name]
    # The run kernels hold one of each too: steps long for the footprint (the script's
    # 0.4 m steps) are checked in the same compilation as the others (review 12).
    for name in ("_segment_kernels.run_segment", "_segment_kernels.run_edge_segment"):
        assert len(signatures[name]) == 2, signatures[name]
    # Callees show only where this process compiled them (a cached caller loads
    # their code with its own): at most the check along a step once per footprint and
    # kind of world, and the SE(2) arc once for the whole simulator (se2's
    # integrate_scalar since review 51, where _wheel_kernels.arc_pose was).
    assert len(signatures.get("_segment_kernels._sweep_static", [])) <= 4
    assert "_wheel_kernels.arc_pose" not in signatures
    assert len(signatures.get("se2.integrate_scalar", [])) <= 1


DISC_SCRIPT = """
from shapely.geometry import box
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Circle, Lidar, Robot, Simulation, World

world = World([box(0.0, 0.0, 4.0, 3.0).exterior, Circle((2.5, 2.0), 0.2)])
robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15,
              lidar=Lidar(n_beams=8), encoders=None)
# Steps of 4 mm (0.4 m/s at 100 Hz) are short for a 0.15 m disc; steps of 0.4 m
# (4 m/s at 10 Hz) are long: checked along their arc, by the same compiled kernel.
for speed, rate in ((0.4, 100.0), (4.0, 10.0)):
    Simulation(
        world, robot, lambda _obs, v=speed: Twist2D(v, 0.0, 0.2), start=(1.0, 1.0, 0.0),
        rate=rate, control_rate=10.0, duration=0.3,
    ).run()
"""


def test_a_disc_robot_among_segments_compiles_one_run_kernel_for_the_disc() -> None:
    signatures = compiled_signatures(DISC_SCRIPT, [f"navkit.sim.{name}" for name in (
        "_clearance_kernels", "_segment_kernels",
    )])  # fmt: skip
    # One run kernel, once, whether or not the steps are long for the footprint.
    (run,) = signatures["_segment_kernels.run_edge_segment"]
    # body_verts and verts (the 18th and 19th arguments) are None: no polygon code.
    assert _arguments(run)[17:19] == ["none", "none"], run
    assert all(
        _arguments(sig)[4:6] == ["none", "none"]
        for sig in signatures["_clearance_kernels.edge_clearance"]
    )
    # Neither the grid's and moving obstacles' kernels nor the polygon's helpers.
    for name in (
        "_segment_kernels.run_segment",
        "_clearance_kernels.footprint_clearance",
        "_clearance_kernels._segment_segment",
        "_clearance_kernels._inside_polygon",
    ):
        assert name not in signatures, name


def _arguments(signature: str) -> list[str]:
    """The argument types of a signature's string ``(t1, t2, ...)``, split at top level."""
    out: list[str] = []
    depth = 0
    start = 1
    for k, char in enumerate(signature):
        if char in "([":
            depth += 1
        elif char in ")]":
            depth -= 1
        if (char == "," and depth == 1) or (char == ")" and depth == 0):
            out.append(signature[start:k].strip())
            start = k + 1
    return [arg for arg in out if arg]


def _disc_and_polygon(first: str, second: str) -> bool:
    """Whether two signatures differ only in arguments that are None in one of them."""
    a, b = _arguments(first), _arguments(second)
    differ = [(x, y) for x, y in zip(a, b, strict=True) if x != y] if len(a) == len(b) else None
    return bool(differ) and all("none" in (x, y) for x, y in differ)


def _worlds() -> dict[str, World]:
    rng = np.random.default_rng(3)
    occupied = rng.random((40, 50)) < 0.04
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    walls = [box(0.0, 0.0, 5.0, 4.0).exterior]
    walls += [box(x, y, x + 0.3, y + 0.2) for x, y in rng.uniform(0.3, 3.5, (12, 2))]
    circle = Circle((2.5, 2.0), 0.3)
    moving = [
        MovingObstacle.constant_velocity(0.25, start_xy=(3.0, 2.5), velocity_xy=(-0.2, 0.1)),
        MovingObstacle.constant_velocity(
            box(-0.2, -0.1, 0.2, 0.1), start_xy=(1.0, 3.0), velocity_xy=(0.1, -0.1)
        ),
    ]
    return {
        "edges": World([*walls, circle]),
        "grid": World(grid=grid),
        "moving": World(moving=moving),
        "all": World([*walls, circle], grid=grid, moving=moving),
        "edges+grid": World([*walls, circle], grid=grid),
        "grid+moving": World(grid=grid, moving=moving),
    }


def _nearest(*scans: np.ndarray) -> np.ndarray:
    return np.minimum.reduce(scans)


def test_a_scan_of_every_kind_is_the_nearest_of_each_kind() -> None:
    worlds = _worlds()
    rng = np.random.default_rng(4)
    angles = np.linspace(-math.pi, math.pi, 180, endpoint=False)
    for _ in range(25):
        pose = (rng.uniform(-0.5, 5.5), rng.uniform(-0.5, 4.5), rng.uniform(-math.pi, math.pi))
        t = float(rng.uniform(0.0, 8.0))
        range_max = float(rng.choice([0.7, 3.0, 12.0]))
        scan = {
            name: w.raycast(pose, angles, range_max=range_max, t=t) for name, w in worlds.items()
        }
        # inf (nothing in range) is the largest value: the nearest of the kinds.
        expected = _nearest(scan["edges"], scan["grid"], scan["moving"])
        np.testing.assert_array_equal(scan["all"], expected)
        np.testing.assert_array_equal(scan["edges+grid"], _nearest(scan["edges"], scan["grid"]))
        np.testing.assert_array_equal(scan["grid+moving"], _nearest(scan["grid"], scan["moving"]))
        assert np.all((scan["all"] < range_max) | (scan["all"] == np.inf))


def test_a_scan_of_an_empty_world_sees_nothing() -> None:
    world = World([])
    ranges = world.raycast((0.0, 0.0, 0.0), np.linspace(-1.0, 1.0, 7), range_max=4.0)
    assert ranges.shape == (7,)
    assert np.all(ranges == np.inf)
