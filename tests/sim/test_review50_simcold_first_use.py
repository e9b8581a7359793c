"""The simulator's first use compiles none of numba's ``min``/``max``/``int`` overloads (review 50).

Issue 17 (any entry point's first use <= 3 s with an empty numba cache):
numba compiles each call of the ``min``, ``max`` and ``int`` builtins as an
overload of its own, once per argument types and process (a few hundredths
of a second each, plus their typing at every call site). The simulator's
clearance, LiDAR, swept-step and run kernels now write them out as selects
(``b if b > a else a`` for ``max(a, b)``, numba's own comparison and order,
so the results are the same bit for bit) and ``np.int64``. Slow: a fresh
process with an empty cache compiles a disc and a polygon robot's runs in a
world of segments and circles and in one with a grid and a moving obstacle,
and LiDAR and clearance queries in both.
"""

from __future__ import annotations

import pytest

from subprocess_probe import COMPILES_LISTED, cold_outcome

_FIRST_USE = COMPILES_LISTED + """
import json
import numpy as np
from shapely.geometry import box
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, Lidar, MovingObstacle, Robot, Simulation, World
occupied = np.zeros((30, 40), dtype=bool)
occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
moving = MovingObstacle.constant_velocity(0.2, start_xy=(3.0, 2.0), velocity_xy=(-0.1, 0.0))
worlds = [
    World([box(0.0, 0.0, 4.0, 3.0).exterior, Circle((2.5, 2.0), 0.2)]),
    World(grid=grid, moving=[moving]),
]
square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
diff = DiffDrive(track=0.3, wheel_radius=0.05)
for world in worlds:
    for footprint in (0.15, square):
        robot = Robot(drive=diff, footprint=footprint, lidar=Lidar(n_beams=16),
                      max_wheel_acceleration=40.0)
        Simulation(world, robot, lambda _obs: Twist2D(0.4, 0.0, 0.2), start=(1.0, 1.0, 0.0),
                   goal=(1.5, 1.2), duration=0.3).run()
        dash = Robot(drive=diff, footprint=footprint, encoders=None)
        Simulation(world, dash, lambda _obs: Twist2D(4.0, 0.0, 0.0), start=(1.0, 1.0, 0.0),
                   rate=10.0, control_rate=10.0, duration=0.3).run()
        world.clearance(footprint, (1.0, 1.0, 0.0))
    world.raycast((1.0, 1.0, 0.0), np.linspace(-3.0, 3.0, 9), range_max=5.0)
print(json.dumps(compiled))
"""


@pytest.mark.slow
def test_simulator_first_use_compiles_no_builtin_min_max_int_overload() -> None:
    compiled = [tuple(row) for row in cold_outcome(_FIRST_USE)]
    ours = {name for module, name in compiled if module.startswith("navkit.sim.")}
    # The kernels this checks were compiled here, for both footprints and both worlds.
    for kernel in (
        "run_segment",
        "run_edge_segment",
        "footprint_clearance",
        "edge_clearance",
        "_occupancy_distance",
        "_cast_occupancy",
        "cast_edge_rays",
        "_sweep_static",
    ):
        assert kernel in ours, sorted(ours)
    overloads = ("ol_min", "ol_max", "ol_int")
    builtins = sorted(
        f"{module}.{name}" for module, name in compiled
        if module == "numba.cpython.builtins" and name.split(".")[0] in overloads
    )  # fmt: skip
    assert builtins == [], builtins
