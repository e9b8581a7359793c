"""The SE(2) helpers are typed once, not copied into every kernel calling them (review 51).

Issue 17 (first-use compilation). ``navkit._shared.se2``'s angle wrap, SE(2)
exponential and pose integration were numba IR-level inlined helpers
(``inline="always"``): numba copied each into every kernel calling it and typed
and lowered the copy there again (the wrap at eight sites of ``navkit warmup``,
the exponential at four, each with its two ``sinc``). They are now compiled once
and inlined by LLVM. ``x ** 2`` in the simulator's circle distances and pure
pursuit's one-point path made numba compile its integer power loop, written as
products now (the same floats). The results are the same bit for bit, also
when a numba cache warmed by the release before is used (its cached kernels of
files not edited since still hold the old copies).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import navkit
from navkit._shared.angles import wrap_float
from navkit.control._path_following_kernels import circle_exit
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.sim import Circle, World

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at
from subprocess_probe import cold_outcome

#: In a fresh process with an empty cache: what numba's inline pass copied and
#: which functions it compiled, while the kernels calling the SE(2) helpers and
#: the former ``** 2`` sites are compiled.
_FIRST_USE = """
import collections, json
from navkit._shared.jit import load_numba
load_numba()
from numba.core import compiler_machinery, inline_closurecall

copies = collections.Counter()
compiled = set()
inline = inline_closurecall.InlineWorker.inline_function

def counted(self, caller_ir, block, i, function, arg_typs=None):
    copies[function.__module__ + "." + function.__qualname__] += 1
    return inline(self, caller_ir, block, i, function, arg_typs)

run_pass = compiler_machinery.PassManager._runPass

def recorded(self, index, pss, state):
    func = state.func_id.func
    compiled.add(func.__module__ + "." + func.__qualname__)
    return run_pass(self, index, pss, state)

inline_closurecall.InlineWorker.inline_function = counted
compiler_machinery.PassManager._runPass = recorded
import numpy as np
from navkit._shared import se2
from navkit.control._path_following_kernels import circle_exit
from navkit.geometry import Pose2D, Twist2D, integrate, rollout
from navkit.sim import Circle, World

integrate(Pose2D(0.0, 0.0, 3.0), Twist2D(1.0, 0.0, 2.0), 0.5)
rollout(Pose2D(0.0, 0.0, 0.0), np.ones((3, 3)), np.full(3, 0.1))
world = World([Circle((2.0, 0.0), 0.5)])
square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
world.clearance(0.15, (0.0, 0.0, 0.0))
world.clearance(square, (0.0, 0.0, 0.0))
circle_exit(0.0, 0.0, np.array([[1.0, 0.0]]), np.zeros(1), 0.0, 0.5)
names = ("wrap_scalar", "exp_body", "integrate_scalar")
print(json.dumps({
    "se2_copies": {k: n for k, n in copies.items() if k.startswith("navkit._shared.se2.")},
    "integer_power": sorted(c for c in compiled if "int_power" in c),
    "signatures": {name: len(getattr(se2, name).signatures) for name in names},
}))
"""


def test_se2_helpers_are_typed_once_and_no_integer_power_is_compiled() -> None:
    got = cold_outcome(_FIRST_USE)
    assert got == {
        # integrate_kernel and rollout_kernel call integrate_scalar: typed once, for both.
        "signatures": {"wrap_scalar": 1, "exp_body": 1, "integrate_scalar": 1},
        # Only the bodies numba still inlines into the one compiled body: sinc twice
        # into exp_body, compose_scalar once into integrate_scalar.
        "se2_copies": {"navkit._shared.se2.sinc": 2, "navkit._shared.se2.compose_scalar": 1},
        "integer_power": [],
    }


def test_wrap_inside_kernels_is_the_python_wrap() -> None:
    # integrate with no translation: the heading th + omega*dt, wrapped in the kernel
    # (compose_scalar's wrap_scalar, inlined by LLVM), against the Python wrap.
    rng = np.random.default_rng(51)
    headings = [math.pi, -math.pi, 0.0, -0.0, 3.0, 1e3, -1e6, *rng.uniform(-50.0, 50.0, 40)]
    for th in headings:
        for omega in (0.0, 1.5, -7.25, 2.0 * math.pi):
            start = Pose2D(0.0, 0.0, float(th))  # its heading wrapped already
            got = integrate(start, Twist2D(0.0, 0.0, omega), 0.5)
            assert got.theta == wrap_float(start.theta + omega * 0.5), (th, omega)


def test_circle_distances_are_the_products_of_the_offsets() -> None:
    # A disc outside a circle: its distance to the circle's boundary is
    # d - radius - r with d the centre distance, rounded as sqrt(dx*dx + dy*dy).
    rng = np.random.default_rng(7)
    for cx, cy in rng.uniform(-3.0, 3.0, (30, 2)):
        world = World([Circle((float(cx), float(cy)), 0.25)])
        x, y = 1.7, -0.3
        d = math.sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy))
        want = max(d - 0.1 - 0.25, 0.0) if d + 0.1 >= 0.25 else 0.25 - (d + 0.1)
        assert world.clearance(0.1, (x, y, 0.0)) == want
    # A one-point path: its point is at least the radius away, or none is (-1).
    point = np.array([[0.3, 0.4]])
    assert circle_exit(0.0, 0.0, point, np.zeros(1), 0.0, 0.5) == 0.0
    assert circle_exit(0.0, 0.0, point, np.zeros(1), 0.0, math.nextafter(0.5, 1.0)) == -1.0


#: Runs the simulator's run kernels (a disc and a polygon, steps long for the
#: footprint: the checks along each step), the fusion filter (its angle wraps) and
#: a rollout; prints digests of what they computed.
_RESULTS = """
import hashlib, json
import numpy as np
from shapely.geometry import box
from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, Twist2D, rollout
from navkit.kinematics import DiffDrive
from navkit.sim import Circle, Imu, Robot, Simulation, WheelEncoders, World

def digest(*arrays):
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    return h.hexdigest()

world = World([box(0.0, 0.0, 4.0, 3.0).exterior, box(3.0, 0.5, 3.5, 1.0), Circle((2.5, 2.0), 0.2)])
diff = DiffDrive(track=0.3, wheel_radius=0.05)
out = {}
for name, footprint, speed, estimator in (
    ("disc", 0.15, 0.4, PlanarFusion()),
    ("square", [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]], 4.0, None),
):
    sim = Simulation(
        world, Robot(drive=diff, footprint=footprint, encoders=WheelEncoders(rate=20.0),
                     imu=Imu(rate=20.0)),
        lambda _o, speed=speed: Twist2D(speed, 0.0, 0.7), start=(1.0, 1.0, 0.0), rate=20.0,
        control_rate=10.0, duration=3.0, estimator=estimator, seed=3,
    )
    trace = sim.run()
    out[name] = [trace.metrics.reason, len(trace), trace.metrics.collisions,
                 digest(trace.times, trace.poses, trace.estimates, trace.commands)]
twists = np.random.default_rng(2).normal(size=(500, 3)) * 3.0
out["rollout"] = digest(rollout(Pose2D(0.5, -0.5, 3.1), twists, np.full(500, 0.1)))
print(json.dumps(out))
"""

#: The release before review 51 (the SE(2) helpers inlined by numba).
_BEFORE = "6da406b"


@pytest.mark.slow
def test_a_cache_warmed_by_the_release_before_gives_the_same_results(tmp_path: Path) -> None:
    before = made_at(_BEFORE, _RESULTS, tmp_path)  # warms tmp_path/numba with the old tree
    src = Path(navkit.__file__).resolve().parents[1]  # the tree under test
    ran = []
    for cache in (tmp_path / "numba", tmp_path / "fresh"):
        env = {**os.environ, "PYTHONPATH": str(src), "NUMBA_CACHE_DIR": str(cache)}
        done = subprocess.run(
            [sys.executable, "-c", _RESULTS], capture_output=True, check=True, text=True,
            env=env, timeout=600,
        )  # fmt: skip
        ran.append(json.loads(done.stdout))
    assert ran[0] == before
    assert ran[1] == before
