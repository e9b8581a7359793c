"""Simulated LiDAR against ir-sim, and the closed loop against real time (issue 13).

Run with ``python -m pytest benchmarks/test_bench_sim.py --benchmark-only``.

LiDAR scans, one 360-beam scan with a 12 m range per call, on the same worlds
and the same poses (16 per world, cycled):

* ``room``: an empty 20 x 20 m room (its four walls);
* ``polygons100`` / ``polygons500``: that room with 100 or 500 random convex
  polygons (4 to 8 vertices, 0.2 to 0.6 m across, seeded);
* ``willow``: the Willow Garage map (found as navkit's ``find_data`` finds
  it: ``$NAVKIT_DATA``, then ``shared/data`` nearby; 566 x 608 cells of
  0.1 m). navkit walks its cells (not-free cells block, see
  ``World(unknown_blocks=True)``); ir-sim gets the map's walls, the not-free
  cells next to a free one, as an obstacle-map image, which it turns into the
  outline of those cells. From a free cell both meet the same first blocked
  cell.

Contestants:

* ``navkit``: ``Lidar(noise=None).scan(world, pose)``, the public call
  (returns a ``LaserScan``);
* ``irsim``: the pip package ``ir-sim`` (module ``irsim``), an environment
  built from a YAML world with ``irsim.make(..., headless=True)``; each call is
  its robot's ``lidar2d`` ``step(state)`` (its LiDAR gathers the segments of
  the obstacles near the beams with shapely and intersects them in NumPy).
  Skipped when ir-sim is not installed.

``test_ranges_agree`` checks that both see the same distances (to 1e-9 m) on
every world and pose before the timings mean anything.

The closed loop: a differential robot (0.2 m round footprint, wheels limited in
speed and acceleration, encoders at 50 Hz, IMU at 100 Hz) with a 360-beam LiDAR
at 10 Hz (paper noise), control at 20 Hz and ``PlanarFusion`` on the Willow
Garage map, driven 18.8 m down a corridor by a go-to-goal controller on the
fused pose; physics at 100 Hz. ``extra_info["real_time_factor"]`` is simulated
seconds per second of wall time.
"""

from __future__ import annotations

import functools
import math
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import shapely
from PIL import Image
from scipy.ndimage import binary_dilation
from shapely.geometry import Polygon, box

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import Imu, Lidar, Observation, Robot, Simulation, WheelEncoders, World
from test_bench_astar import shared_data

WILLOW = "ros-map-server-maps/willow_garage_2010/willow-2010-02-18-0.10.yaml"
ROOM = 20.0
RANGE_MAX = 12.0
N_POSES = 16
WORLDS = ["room", "polygons100", "polygons500", "willow"]


# ---------------------------------------------------------------- worlds
def random_polygons(n: int, poses: list[Pose2D], seed: int) -> list[Polygon]:
    """``n`` convex polygons in the room, at least 0.8 m from every pose, none overlapping."""
    rng = np.random.default_rng(seed)
    out: list[Polygon] = []
    keep_out = [shapely.Point(p.x, p.y).buffer(0.8) for p in poses]
    while len(out) < n:
        cx, cy = rng.uniform(0.5, ROOM - 0.5, 2)
        k = int(rng.integers(4, 9))
        angles = np.sort(rng.uniform(0.0, 2.0 * math.pi, k))
        radius = rng.uniform(0.1, 0.3)
        poly = Polygon(
            np.column_stack((cx + radius * np.cos(angles), cy + radius * np.sin(angles)))
        ).convex_hull
        if poly.area < 0.01 or any(poly.intersects(z) for z in keep_out):
            continue
        if any(poly.intersects(q) for q in out):
            continue
        out.append(poly)
    return out


def room_poses(seed: int) -> list[Pose2D]:
    rng = np.random.default_rng(seed)
    return [
        Pose2D(float(x), float(y), float(th))
        for x, y, th in zip(
            rng.uniform(1.0, ROOM - 1.0, N_POSES),
            rng.uniform(1.0, ROOM - 1.0, N_POSES),
            rng.uniform(-math.pi, math.pi, N_POSES),
            strict=True,
        )
    ]


@functools.cache
def willow_grid() -> OccupancyGrid:
    return OccupancyGrid.load(shared_data(WILLOW))


@functools.cache
def scene(name: str) -> dict[str, Any]:
    """The world, poses and ir-sim description of one benchmark world."""
    walls = box(0.0, 0.0, ROOM, ROOM).exterior
    if name == "willow":
        grid = willow_grid()
        free = grid.free()
        rng = np.random.default_rng(7)
        # Poses on free cells at least 0.5 m from anything that is not free.
        clear = ~binary_dilation(~free, iterations=5)
        cells = np.argwhere(clear)
        picks = cells[rng.choice(len(cells), N_POSES, replace=False)]
        poses = [
            Pose2D(*grid.cell_to_world(c), float(rng.uniform(-math.pi, math.pi))) for c in picks
        ]
        # The walls: blocked cells next to free space.
        wall_cells = ~free & binary_dilation(free, structure=np.ones((3, 3), dtype=bool))
        return {"world": World(grid=grid), "poses": poses, "walls": wall_cells, "grid": grid}
    poses = room_poses(3)
    if name == "room":
        polys: list[Polygon] = []
    else:
        polys = random_polygons(int(name.removeprefix("polygons")), poses, seed=11)
    return {"world": World([walls, *polys]), "poses": poses, "polygons": polys}


def irsim_env(name: str, folder: Path) -> Any:
    """An ir-sim environment of the same world, built from a YAML file in ``folder``."""
    irsim = pytest.importorskip("irsim")
    import yaml

    sc = scene(name)
    lidar = {
        "name": "lidar2d",
        "range_min": 0.0,
        "range_max": RANGE_MAX,
        "angle_range": 2.0 * math.pi,
        "number": 360,
        "noise": False,
    }
    far = [-50.0, -50.0, 0.0]  # the robot itself stays out of the way
    cfg: dict[str, Any] = {
        "robot": [
            {
                "kinematics": {"name": "diff"},
                "shape": {"name": "circle", "radius": 0.05},
                "state": far,
                "sensors": [lidar],
            }
        ],
    }
    if name == "willow":
        grid = sc["grid"]
        image = np.where(sc["walls"], 0, 255).astype(np.uint8)[::-1]  # top row = highest y
        png = folder / "willow_walls.png"
        Image.fromarray(image).save(png)
        cfg["world"] = {
            "width": grid.width,
            "height": grid.height,
            "offset": [grid.origin.x, grid.origin.y],
            "obstacle_map": str(png),
        }
    else:
        obstacles: list[dict[str, Any]] = [
            {
                "shape": {
                    "name": "linestring",
                    "vertices": [[0, 0], [ROOM, 0], [ROOM, ROOM], [0, ROOM], [0, 0]],
                },
                "state": [0, 0, 0],
            }
        ]
        for poly in sc["polygons"]:
            verts = np.asarray(poly.exterior.coords)[:-1].tolist()
            obstacles.append({"shape": {"name": "polygon", "vertices": verts}, "state": [0, 0, 0]})
        cfg["world"] = {"width": ROOM, "height": ROOM}
        cfg["obstacle"] = obstacles
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(cfg))
    return irsim.make(str(path), headless=True, log_level="WARNING")


@pytest.fixture(scope="module")
def irsim_envs() -> Any:
    with tempfile.TemporaryDirectory() as folder:
        cache: dict[str, Any] = {}

        def get(name: str) -> Any:
            if name not in cache:
                cache[name] = irsim_env(name, Path(folder))
            return cache[name]

        yield get


def _state(pose: Pose2D) -> np.ndarray:
    return np.array([[pose.x], [pose.y], [pose.theta]])


# ------------------------------------------------------------- agreement
@pytest.mark.parametrize("name", WORLDS)
def test_ranges_agree(name: str, irsim_envs: Any) -> None:
    """navkit and ir-sim measure the same distances on the same worlds and poses."""
    sc = scene(name)
    lidar = irsim_envs(name).robot.lidar
    angles = np.asarray(lidar.angle_list, dtype=np.float64)
    for pose in sc["poses"]:
        lidar.step(_state(pose))
        theirs = np.asarray(lidar.range_data, dtype=np.float64)
        hit = np.asarray(lidar.valid) | (theirs < RANGE_MAX)
        ours = sc["world"].raycast(pose, angles, range_max=RANGE_MAX)
        assert np.array_equal(np.isfinite(ours), hit)
        np.testing.assert_allclose(ours[hit], theirs[hit], rtol=0.0, atol=1e-9)


# ------------------------------------------------------------- timings
def _cycle(poses: list[Pose2D]) -> Any:
    state = {"k": 0}

    def next_pose() -> Pose2D:
        state["k"] = (state["k"] + 1) % len(poses)
        return poses[state["k"]]

    return next_pose


@pytest.mark.parametrize("name", WORLDS)
def test_scan_navkit(benchmark: Any, name: str) -> None:
    sc = scene(name)
    world = sc["world"]
    lidar = Lidar(noise=None, range_max=RANGE_MAX)
    nxt = _cycle(sc["poses"])
    # The timed call is the ray cast that test_ranges_agree checks against ir-sim
    # (compiled here, outside the timer).
    for pose in sc["poses"]:
        scan = lidar.scan(world, pose)
        want = world.raycast(pose, scan.angles(), range_max=RANGE_MAX)
        np.testing.assert_allclose(scan.ranges, want, rtol=0.0, atol=1e-9)
    benchmark.group = f"lidar scan: {name}"
    scan = benchmark(lambda: lidar.scan(world, nxt()))
    assert len(scan) == 360


@pytest.mark.parametrize("name", WORLDS)
def test_scan_irsim(benchmark: Any, name: str, irsim_envs: Any) -> None:
    sc = scene(name)
    lidar = irsim_envs(name).robot.lidar
    states = [_state(p) for p in sc["poses"]]
    k = {"i": 0}

    def step() -> None:
        k["i"] = (k["i"] + 1) % len(states)
        lidar.step(states[k["i"]])

    benchmark.group = f"lidar scan: {name}"
    benchmark(step)


# ------------------------------------------------------------ closed loop
START = Pose2D(35.35, 19.65, 0.0)
GOAL = (27.25, 2.65)


class GoToGoal:
    """Turn toward the goal, then drive at it, on the estimated pose."""

    def __init__(self, goal: tuple[float, float]) -> None:
        self.goal = goal

    def __call__(self, obs: Observation) -> Twist2D:
        pose = obs.estimate if obs.estimate is not None else obs.true_pose
        dx = self.goal[0] - pose.x
        dy = self.goal[1] - pose.y
        heading = (math.atan2(dy, dx) - pose.theta + math.pi) % (2.0 * math.pi) - math.pi
        omega = max(-1.5, min(1.5, 2.0 * heading))
        v = 0.0 if abs(heading) > 0.5 else min(0.5, math.hypot(dx, dy))
        return Twist2D(v, 0.0, omega)


def closed_loop() -> Simulation:
    grid = willow_grid()
    world = World(grid=grid)
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.2,
        max_wheel_speed=20.0,
        max_wheel_acceleration=40.0,
        wheel_slip=0.01,
        encoders=WheelEncoders(ticks_per_rev=2048, bits=16, rate=50.0),
        imu=Imu(gyro_noise=0.005, accel_noise=0.05, rate=100.0),
        lidar=Lidar(n_beams=360, rate=10.0),
    )
    heading = math.atan2(GOAL[1] - START.y, GOAL[0] - START.x)
    start = Pose2D(START.x, START.y, heading)
    fusion = PlanarFusion(x0=[start.x, start.y, start.theta, 0.0, 0.0, 0.0], t0=0.0)
    return Simulation(
        world,
        robot,
        GoToGoal(GOAL),
        start=start,
        goal=GOAL,
        goal_tolerance=0.2,
        estimator=fusion,
        rate=100.0,
        control_rate=20.0,
        duration=120.0,
        seed=1,
    )


def test_closed_loop_willow(benchmark: Any) -> None:
    closed_loop().run()  # compile outside the timer
    benchmark.group = "closed loop: Willow Garage, diff robot, LiDAR 10 Hz, control 20 Hz"
    trace = benchmark.pedantic(
        Simulation.run, setup=lambda: ((closed_loop(),), {}), rounds=5, iterations=1
    )
    m = trace.metrics
    assert m.reached and m.collisions == 0
    benchmark.extra_info["simulated_s"] = m.duration
    if benchmark.stats is not None:  # None under --benchmark-disable
        benchmark.extra_info["real_time_factor"] = m.duration / benchmark.stats.stats.median
