"""A robot in a world with an occupancy grid compiles no kernel for worlds without one.

The check along a long step (``_segment_kernels._sweep_static``) measures the
clearance with ``edge_clearance`` in a world of segments and circles only and
with ``footprint_clearance`` otherwise. numba removes a branch before typing
only where its test is on an argument that is None; the sweep told the kinds
of world apart by ``occ is None``, so its grid variants (an array ``occ``)
kept the other branch and compiled ``edge_clearance`` for the footprint, a
kernel with a Python wrapper that they never ran, and linked its code into
``run_segment`` (review 52, SIMFOOT). The first test runs a disc and a polygon
robot in a grid world in a fresh process with an empty cache and checks that
``edge_clearance`` was not compiled, while a world of segments still compiles
it. The second checks that the sweep still catches a step through a wall in
both kinds of world, and lets a free step pass.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import LineString

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from kernel_signatures import compiled_signatures
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import MovingObstacle, Robot, Simulation, World

SQUARE = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]

SCRIPT = """
import os
os.environ["NUMBA_CACHE_DIR"] = {cache!r}
import numpy as np
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import Robot, Simulation, World

occupied = np.zeros((30, 40), dtype=bool)
occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
world = World(grid=OccupancyGrid.from_occupancy(occupied, resolution=0.1))
drive = DiffDrive(track=0.3, wheel_radius=0.05)
for footprint in {footprints!r}:
    # 4 m/s at 10 Hz: steps long for the footprint, checked along their arc.
    Simulation(
        world, Robot(drive=drive, footprint=footprint, encoders=None, compass=None, imu=None),
        lambda _obs: Twist2D(4.0, 0.0, 0.0), start=(1.0, 1.0, 0.0), rate=10.0,
        control_rate=10.0, duration=0.3,
    ).run()
"""


def test_a_grid_world_compiles_no_clearance_kernel_for_worlds_without_a_grid(
    tmp_path: Path,
) -> None:
    script = SCRIPT.format(cache=str(tmp_path / "cache"), footprints=[0.15, SQUARE])
    signatures = compiled_signatures(script, ["navkit.sim._clearance_kernels",
                                              "navkit.sim._segment_kernels"])  # fmt: skip
    # The run kernel and the check along a step, once per footprint, were compiled here.
    assert len(signatures["_segment_kernels.run_segment"]) == 2, signatures
    assert len(signatures["_segment_kernels._sweep_static"]) == 2, signatures
    assert len(signatures["_clearance_kernels.footprint_clearance"]) == 2, signatures
    # Nothing of a world without a grid.
    assert "_clearance_kernels.edge_clearance" not in signatures, signatures
    assert "_segment_kernels.run_edge_segment" not in signatures, signatures


def test_a_world_of_segments_still_checks_its_steps_with_edge_clearance(tmp_path: Path) -> None:
    script = SCRIPT.replace(
        "world = World(grid=OccupancyGrid.from_occupancy(occupied, resolution=0.1))",
        "from shapely.geometry import box\nworld = World([box(0.0, 0.0, 4.0, 3.0).exterior])",
    ).format(cache=str(tmp_path / "cache"), footprints=[0.15])
    signatures = compiled_signatures(script, ["navkit.sim._clearance_kernels",
                                              "navkit.sim._segment_kernels"])  # fmt: skip
    (sweep,) = signatures["_segment_kernels._sweep_static"]
    # The world's kind is the last argument: True (a literal or a bool), not None.
    assert sweep.endswith((", bool)", ", Literal[bool](True))")), sweep
    assert len(signatures["_clearance_kernels.edge_clearance"]) == 1, signatures
    assert "_clearance_kernels.footprint_clearance" not in signatures, signatures
    assert "_segment_kernels.run_segment" not in signatures, signatures


def _dash(world: World, footprint: object) -> tuple[int, float]:
    """Collisions and final x of a 4 m/s dash along y = 1.5 from x = 0.48, steps of 0.4 m."""
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=footprint,
                  encoders=None, compass=None, imu=None)  # fmt: skip
    trace = Simulation(
        world,
        robot,
        lambda _obs: Twist2D(4.0, 0.0, 0.0),
        start=(0.48, 1.5, 0.0),
        rate=10.0,
        control_rate=10.0,
        duration=0.6,
    ).run()
    collisions = sum(event.kind == "collision" for event in trace.events)
    return collisions, float(trace.poses[-1, 0])


@pytest.mark.parametrize("footprint", [0.15, SQUARE], ids=["disc", "polygon"])
def test_the_check_along_a_step_catches_a_thin_wall_in_either_kind_of_world(
    footprint: object,
) -> None:
    # The 0.4 m steps from x = 0.48 end at 1.28 and 1.68, where a 0.15 m disc (or the
    # 0.1 m half-width square) is clear of a wall at x = 1.52 and of the grid's cells
    # x in [1.45, 1.5): only the check along the step finds them.
    edges = World([LineString([(1.52, 0.0), (1.52, 3.0)])])
    occupied = np.zeros((60, 80), dtype=bool)
    occupied[:, 29] = True
    # A moving obstacle far away: the grid's run kernel with its moving obstacles.
    far = MovingObstacle.constant_velocity(0.1, start_xy=(3.5, 0.3), velocity_xy=(0.0, 0.0))
    grid = World(grid=OccupancyGrid.from_occupancy(occupied, resolution=0.05), moving=[far])
    for world, wall in ((edges, 1.52), (grid, 1.45)):
        collisions, x = _dash(world, footprint)
        assert collisions >= 1, world
        assert x < wall, (world, x)
    free_edges = World([LineString([(0.0, 2.9), (4.0, 2.9)])])
    free_grid = World(grid=OccupancyGrid.from_occupancy(np.zeros((60, 80), dtype=bool),
                                                         resolution=0.05),
                      moving=[far])  # fmt: skip
    for world in (free_edges, free_grid):
        collisions, x = _dash(world, footprint)
        assert collisions == 0, world
        assert x > 2.5, (world, x)
