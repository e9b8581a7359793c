"""With numba's JIT disabled, review 48's kernels run as Python without a warning.

Under ``NUMBA_DISABLE_JIT=1`` the kernels are plain Python on NumPy scalars,
which warn where compiled code wraps around silently. Review 48's jump point
search tables first packed 8 flag bytes into 8 bits by a multiplication whose
uint64 product wraps (4aa1210): "overflow encountered in scalar multiply" at
every one-shot ``astar(..., method="jps")``, an exception under ``-W error``
(as in any test suite that turns warnings into errors). The calls here cover
the kernels review 48 changed: the JPS tables at word edges of their bit rows,
the Field D* heap's tournament on key bits, and the simulator's goal test
(FRESH). Each result must also equal the compiled one.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from subprocess_probe import jit_outcome

_CALLS = r"""
import json
import numpy as np
from shapely.geometry import box
import navkit.planning as P
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, World

out = {}
rng = np.random.default_rng(48)
# Rows and columns whose padded bit lines (cells + 2) end around a 64-bit word.
for rows, cols in ((1, 1), (3, 62), (5, 63), (2, 64), (7, 126), (62, 3)):
    grid = np.where(rng.random((rows, cols)) < 0.3, np.inf, 1.0)
    grid[0, :] = grid[:, 0] = grid[:, -1] = 1.0  # a way round the random cells
    path = P.astar(grid, (rows - 1, 0), (rows - 1, cols - 1), method="jps")
    out[f"jps {rows}x{cols}"] = path.cost
grid = np.where(rng.random((9, 11)) < 0.2, np.inf, 1.0 + rng.random((9, 11)))
grid[0, 0] = grid[-1, -1] = 1.0
out["field_dstar"] = P.field_dstar(grid, (0, 0), (9, 11)).cost
sim = Simulation(
    World([box(0.0, 0.0, 3.0, 2.0).exterior]),
    Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15),
    lambda obs: Twist2D(0.4, 0.0, 0.0), start=(0.5, 1.0, 0.0), goal=(0.7, 1.0),
    goal_tolerance=0.05, duration=1.0, rate=50.0, control_rate=10.0,
)
metrics = sim.run().metrics
out["sim"] = [metrics.reached, metrics.time_to_goal]
print(json.dumps(out))
"""


def _run(disable_jit: bool) -> dict[str, object]:
    result: dict[str, object] = jit_outcome(
        _CALLS, disable_jit=disable_jit, warnings_as_errors=True, timeout=600
    )
    return result


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX subprocess environment")
def test_review48_kernels_run_as_python_without_warnings() -> None:
    interpreted = _run(disable_jit=True)
    compiled = _run(disable_jit=False)
    assert interpreted.keys() == compiled.keys()
    assert interpreted.pop("sim") == compiled.pop("sim")
    for name, value in compiled.items():
        assert isinstance(value, float) and np.isfinite(value), name
        assert interpreted[name] == pytest.approx(value, rel=1e-12), name
