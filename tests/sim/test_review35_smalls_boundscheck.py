"""The simulator's kernels run with numba's bounds checks on (session 39, SMALLS).

numba does not check array indices by default: a kernel handed an array of the
wrong shape reads or writes other memory, silently (or crashes later). A mutant of
``World._cast`` that allocated the beam directions as (n, 1) instead of (n, 2)
survived every test. These tests run the kernels whose array shapes the Python
layer computes (ray casting, range noise, footprint clearance, moving obstacles;
in the slow test the whole simulation loop) in a fresh process with
``NUMBA_BOUNDSCHECK=1`` and an empty cache of their own, where any out-of-bounds
index raises ``IndexError``; the first also makes that mutant in the process and
checks it is caught.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from subprocess_probe import bounds_checked

_WORLD = textwrap.dedent(
    """
    import inspect, textwrap
    import numpy as np
    from shapely.geometry import LineString, box
    from navkit.geometry import Pose2D
    from navkit.mapping import OccupancyGrid
    from navkit.sim import Circle, Lidar, MovingObstacle, World
    import navkit.sim._world as world_module

    occ = np.zeros((40, 60), dtype=bool)
    occ[5:30, 25:28] = True
    occ[30:33, 5:20] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1, origin=Pose2D(-1.0, -1.0, 0.2))
    movers = [
        MovingObstacle.constant_velocity(0.2, start_xy=(2.0, 1.0), velocity_xy=(0.1, 0.0)),
        MovingObstacle.scripted(
            [(-0.1, -0.1), (0.1, -0.1), (0.0, 0.1)], [(4.0, 2.0), (5.0, 2.0)], speed=0.5,
            after="loop",
        ),
    ]
    walls = [box(-2, -2, 6, 4).exterior, box(3, 0, 3.5, 0.5), Circle((1.0, 2.0), 0.3),
             LineString([(0, -1), (1, -1.5)])]
    world = World(walls, grid=grid, moving=movers)  # both passes of a scan
    edges_only = World([box(-2, -2, 6, 4).exterior])
    grid_only = World([], grid=grid)
    angles = np.linspace(-3.1, 3.1, 37)
    pose = [0.2, 0.3, 0.1]
    ranges = world.raycast(pose, angles, range_max=8.0, t=0.5)
    assert np.isfinite(ranges).all(), ranges
    # Each beam's range is the nearer of the edges' and the grid's, bit for bit (the
    # grid's pass read the first pass's directions); each is the nearer in some beams.
    by_edges = World(walls, moving=movers).raycast(pose, angles, range_max=8.0, t=0.5)
    by_grid = grid_only.raycast(pose, angles, range_max=8.0)
    assert np.array_equal(ranges, np.minimum(by_edges, by_grid))
    assert (by_grid < by_edges).sum() >= 5 and (by_edges < by_grid).sum() >= 5
    assert np.isfinite(edges_only.raycast(pose, angles, range_max=8.0)).all()
    scan = Lidar(n_beams=64).scan(world, pose, seed=1)
    assert scan.ranges.shape == (64,)
    square = [(-0.2, -0.15), (0.2, -0.15), (0.2, 0.15), (-0.2, 0.15)]
    for w in (world, edges_only, grid_only):
        assert w.clearance(square, (0.5, 0.5, 0.3), t=0.5) >= 0.0
        assert w.clearance(0.2, (0.5, 0.5, 0.3)) >= 0.0
        w.collides(square, (0.5, 0.5, 0.3))
    print("in bounds")

    # The mutant that survived: beam directions allocated (n, 1). Compiled with
    # bounds checks, the first pass's write of dirs[k, 1] raises.
    source = textwrap.dedent(inspect.getsource(world_module.World._cast))
    mutated = source.replace("np.empty((angles.shape[0], 2))", "np.empty((angles.shape[0], 1))")
    assert mutated != source, "the mutation site moved: update this test"
    namespace = dict(vars(world_module))
    exec(compile(mutated, world_module.__file__, "exec"), namespace)
    world_module.World._cast = namespace["_cast"]
    try:
        world.raycast(pose, angles, range_max=8.0, t=0.5)
    except IndexError as exc:
        print("mutant caught:", exc)
    """
)

_SIMULATION = textwrap.dedent(
    """
    import numpy as np
    from shapely.geometry import box
    from navkit.estimation import OmniOdometry, PlanarFusion
    from navkit.geometry import Pose2D, Twist2D
    from navkit.kinematics import DiffDrive, OmniDrive
    from navkit.mapping import OccupancyGrid
    from navkit.sim import (
        Circle, Compass, Imu, Lidar, MovingObstacle, Robot, Simulation, WheelEncoders, World,
    )

    occ = np.zeros((40, 60), dtype=bool)
    occ[30:34, 40:44] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1, origin=Pose2D(-1.0, -1.0, 0.0))
    movers = [MovingObstacle.constant_velocity(0.2, start_xy=(4.0, 2.5), velocity_xy=(0.0, -0.1))]
    room = box(-2, -2, 6, 4).exterior
    full = World([room, Circle((1.0, 2.5), 0.3)], grid=grid, moving=movers)
    edges = World([room, Circle((1.0, 2.5), 0.3)])
    square = [(-0.2, -0.15), (0.2, -0.15), (0.2, 0.15), (-0.2, 0.15)]
    omni = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    diff = DiffDrive(track=0.3, wheel_radius=0.05)
    cases = [
        (full, omni, square, OmniOdometry(omni), Twist2D(0.3, 0.05, 0.1)),
        (edges, diff, 0.15, PlanarFusion(), Twist2D(0.3, 0.0, 0.1)),
        (edges, omni, square, None, Twist2D(0.2, -0.1, 0.0)),
    ]
    for world, drive, footprint, estimator, command in cases:
        robot = Robot(
            drive=drive, footprint=footprint, lidar=Lidar(n_beams=32, latency=0.02),
            encoders=WheelEncoders(latency=0.01), compass=Compass(), imu=Imu(),
            max_wheel_acceleration=40.0,
        )
        sim = Simulation(
            world, robot, lambda obs, command=command: command, start=(0.0, 0.0, 0.0),
            goal=(3.0, 0.5), estimator=estimator, duration=2.0, seed=3,
            reference_path=[(0.0, 0.0), (3.0, 0.5)],
        )
        trace = sim.run()
        assert len(trace.times) > 10 and np.isfinite(trace.poses).all()
    print("in bounds")
    """
)


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_world_and_lidar_kernels_stay_in_bounds(tmp_path: Path) -> None:
    lines = bounds_checked(_WORLD, tmp_path)
    assert lines[0] == "in bounds"
    # ... and the harness catches the mutant that no test caught before.
    assert lines[1].startswith("mutant caught: index is out of bounds"), lines


@pytest.mark.slow
def test_the_simulation_loop_stays_in_bounds(tmp_path: Path) -> None:
    # The segment kernels, wheels, encoders, compass, IMU, latency, estimators
    # (OmniOdometry, PlanarFusion), a polygon footprint, moving obstacles, a grid and
    # the cross-track distances: about 12 s of compilation.
    assert bounds_checked(_SIMULATION, tmp_path) == ["in bounds"]
