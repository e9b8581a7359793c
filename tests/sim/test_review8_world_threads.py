"""One World shared by threads: every query and run gives what it gives alone.

The queries placed the moving obstacles in work arrays of the world and read
them after (another thread could move them in between), the LiDAR scanner the
world caches per LiDAR wrote its ranges into one buffer, two simulations
sharing a world placed its obstacles in the same arrays, and shapely's
prepared solids were queried by threads at once (heap corruption).
"""

from __future__ import annotations

import math
import pickle
import subprocess
import sys
import textwrap
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Lidar, MovingObstacle, Robot, Simulation, World

THREADS = 8


@pytest.fixture(autouse=True)
def _switch_often() -> Iterator[None]:
    """Threads switch every microsecond: races show at once."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        yield
    finally:
        sys.setswitchinterval(old)


def _moving_world() -> World:
    ball = MovingObstacle.constant_velocity(0.5, start_xy=(2.0, 4.0), velocity_xy=(0.5, 0.0))
    square = MovingObstacle(
        box(-0.3, -0.3, 0.3, 0.3), np.array([[6.0, 1.0], [6.0, 7.0]]), np.array([0.0, 8.0]),
        after="loop",
    )  # fmt: skip
    return World([box(0, 0, 10, 8).exterior], moving=[ball, square])


def _same_in_threads(task: Callable[[Any], Any], args: list[Any]) -> int:
    """How many of the threaded results differ from the single-threaded ones."""
    alone = [task(a) for a in args]

    def chunk(k: int) -> list[Any]:
        return [task(a) for a in args[k::THREADS]]

    with ThreadPoolExecutor(THREADS) as pool:
        chunks = list(pool.map(chunk, range(THREADS)))
    together = [chunks[i % THREADS][i // THREADS] for i in range(len(args))]
    return sum(
        not np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)
        for a, b in zip(alone, together, strict=True)
    )


TIMES = [0.013 * k for k in range(6000)]


def test_raycasts_at_different_times_from_threads() -> None:
    world = _moving_world()
    angles = np.linspace(-math.pi, math.pi, 8, endpoint=False)

    def cast(t: float) -> Any:
        return world.raycast((1.0, 4.0, 0.0), angles, range_max=20.0, t=t)

    assert _same_in_threads(cast, TIMES) == 0


def test_clearances_and_collisions_at_different_times_from_threads() -> None:
    world = _moving_world()

    def query(t: float) -> Any:
        return world.clearance(0.1, (3.0, 4.0, 0.0), t=t), world.collides(0.5, (4.0, 4.0, 0.0), t=t)

    assert _same_in_threads(query, TIMES) == 0


@pytest.mark.parametrize("moving", [True, False], ids=["moving", "static"])
def test_scans_of_one_lidar_from_threads(moving: bool) -> None:
    # Without moving obstacles too: the scanner the world keeps for the LiDAR
    # wrote every scan's ranges into one buffer.
    world = _moving_world() if moving else World([box(0, 0, 10, 8).exterior])
    lidar = Lidar(n_beams=90, range_max=20.0, angle_jitter=0.01, dropout=0.05)

    def scan(k: int) -> Any:
        pose = (1.0 + 0.01 * (k % 7), 4.0, 0.1 * k)
        return lidar.scan(world, pose, t=TIMES[k], seed=k).ranges

    assert _same_in_threads(scan, list(range(300))) == 0


def test_simulations_sharing_a_world_run_in_threads() -> None:
    world = _moving_world()
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    robot = Robot(drive=drive, footprint=0.2, lidar=Lidar(n_beams=30, rate=100.0, noise=None))

    def run(k: int) -> Any:
        def turn(obs: Any) -> Twist2D:
            return Twist2D(0.3, 0.0, 0.2 * math.sin(obs.t + k))

        trace = Simulation(
            world, robot, turn, start=(1.0 + 0.5 * k, 2.5, 0.1 * k), duration=3.0,
            stop_at_goal=False, end_on_collision=False, record_scans=True, seed=k,
        ).run()  # fmt: skip
        return np.concatenate([trace.poses.ravel(), *(s.scan.ranges for s in trace.scans)])

    assert _same_in_threads(run, list(range(16))) == 0


@pytest.mark.slow
def test_collides_with_a_large_solid_from_threads() -> None:
    # Threads querying the world's prepared solid at once corrupted the heap: the
    # interpreter aborted or hung, in about half of the runs of this test (hence
    # a process of its own).
    script = textwrap.dedent(
        """
        import math, sys
        from concurrent.futures import ThreadPoolExecutor
        import numpy as np
        from shapely.geometry import Polygon
        from navkit.sim import World
        rng = np.random.default_rng(0)
        angle = np.sort(rng.uniform(0.0, 2.0 * math.pi, 3000))
        radius = 5.0 + rng.uniform(0.0, 1.0, angle.size)
        ring = np.c_[radius * np.cos(angle), radius * np.sin(angle)]
        points = rng.uniform(-4.0, 4.0, (64, 2))
        alone = [World([Polygon(ring)]).collides(0.01, (x, y, 0.0)) for x, y in points]
        sys.setswitchinterval(1e-6)
        for _ in range(300):
            world = World([Polygon(ring)])
            with ThreadPoolExecutor(16) as pool:
                got = list(pool.map(lambda p: world.collides(0.01, (p[0], p[1], 0.0)), points))
            assert got == alone
        print("same")
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=False
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "same"


def test_a_world_pickled_with_the_old_work_arrays_loads() -> None:
    # Worlds pickled before placements were published whole held three more slots.
    world = _moving_world()
    slots = {name: getattr(world, name) for name in World.__slots__ if hasattr(world, name)}
    slots.pop("_placed", None)
    slots.update(
        _dyn_segs=np.zeros_like(world._dyn_base_segs),
        _dyn_circles=np.zeros_like(world._dyn_base_circles),
        _moving_t=0.0,  # a stale note: the arrays above are not at t = 0
    )

    class _Old:
        def __reduce__(self) -> tuple[Any, ...]:
            return object.__new__, (World,), (None, slots)

    loaded = pickle.loads(pickle.dumps(_Old()))
    angles = np.linspace(-math.pi, math.pi, 16, endpoint=False)
    for t in (0.0, 1.0, 3.3):
        np.testing.assert_array_equal(
            loaded.raycast((1.0, 4.0, 0.0), angles, range_max=20.0, t=t),
            world.raycast((1.0, 4.0, 0.0), angles, range_max=20.0, t=t),
        )
        assert loaded.clearance(0.1, (3.0, 4.0, 0.0), t=t) == world.clearance(
            0.1, (3.0, 4.0, 0.0), t=t
        )
