"""Field D*'s path walk calls ``hypot`` only where a step needs it.

Review 53 (FDWALK) made the walk two compiled functions, and the walk alone
about 10 % slower (the 8-connected one 1.5 times). libm's ``hypot`` was about
40 % of a walk's time, and many of its calls had a zero side: a step along a
grid line, a crossing point at an edge's end. FDWALK2 writes those as the
other side's magnitude, which is what ``hypot`` returns (C99 Annex F): the
paths stay bit for bit (checked against the trees before on the MovingAI maps
and random grids).

Speed is measured in ``benchmarks/``; these tests pin the work instead, with
the kernels run as Python (``NUMBA_DISABLE_JIT=1``) so that the walk's calls
can be counted, and check the shortcut against the compiled ``hypot``.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled
from navkit.planning import FieldDStar

#: Plans 8-connected and interpolated with the kernels run as Python, counting
#: the ``hypot`` calls (those with a zero side apart).
_PROBE = """
import json
import math
import numpy as np
from navkit.planning import FieldDStar
from navkit.planning.grid import _field_path_kernels as walk
zero_sides = []
hypot_calls = []
real_hypot = math.hypot
def hypot(a, b):
    hypot_calls.append(1)
    if a == 0.0 or b == 0.0:
        zero_sides.append([a, b])
    return real_hypot(a, b)
walk.hypot = hypot
rng = np.random.default_rng(5353)
costs = rng.choice([1.0, 1.5, 2.0, 3.25, 10.0, np.inf], size=(10, 12))
costs[0, :] = 1.0
costs[:, -1] = 2.0
points = []
for interpolate in (False, True):
    planner = FieldDStar(costs, interpolate=interpolate, smooth=False)
    points.append(np.asarray(planner.plan((0, 0), (10, 12)).points).tolist())
print(json.dumps({"zero": zero_sides, "calls": len(hypot_calls),
                  "points": points}))
"""


def _probe() -> dict[str, list[list[float]] | list[int] | int]:
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    out = subprocess.run(
        [sys.executable, "-c", _PROBE], check=True, capture_output=True, text=True, env=env
    )
    result: dict[str, list[list[float]] | list[int] | int] = json.loads(
        out.stdout.strip().splitlines()[-1]
    )
    return result


@pytest.fixture(scope="module")
def probe() -> dict[str, list[list[float]] | list[int] | int]:
    return _probe()


def test_no_hypot_is_called_with_a_zero_side(probe: dict) -> None:
    calls = probe["calls"]
    assert isinstance(calls, int) and calls > 0  # the diagonal steps, the crossings
    # Before: every step along a grid line and every crossing at an edge's end.
    assert probe["zero"] == []


def test_the_probed_walks_reach_the_goal(probe: dict) -> None:
    for points in probe["points"]:
        nodes = np.asarray(points) + 0.5  # grid frame: node - 0.5
        assert nodes[0].tolist() == [0.0, 0.0]
        assert nodes[-1].tolist() == [10.0, 12.0]


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: no compiled hypot")
def test_compiled_hypot_of_a_zero_side_is_the_other_magnitude() -> None:
    # The shortcut the walk takes, against the hypot its kernels call (libm's,
    # not Python's), on the values its steps meet: node differences, fractions
    # of a cell and their complements, and extremes.
    import numba

    @numba.njit
    def both(values: np.ndarray, out: np.ndarray) -> None:
        for k in range(values.shape[0]):
            out[2 * k] = math.hypot(values[k], 0.0)
            out[2 * k + 1] = math.hypot(-0.0, values[k])

    rng = np.random.default_rng(53)
    extremes = [5e-324, 1e-300, 1e300, np.inf]
    values = np.concatenate(
        [rng.uniform(-2.0, 2.0, 1000), 1.0 - rng.uniform(0.0, 1.0, 1000), np.arange(-3.0, 4.0)]
    )
    values = np.append(values, extremes)
    out = np.empty(2 * values.shape[0])
    both(values, out)
    assert np.array_equal(out.view(np.int64), np.repeat(np.abs(values), 2).view(np.int64))


def test_the_8_connected_and_interpolated_walks_match_the_probe(probe: dict) -> None:
    # The compiled walk takes the same nodes as the Python one on the 8-connected
    # graph (no rounding-sensitive crossing points there).
    rng = np.random.default_rng(5353)
    costs = rng.choice([1.0, 1.5, 2.0, 3.25, 10.0, np.inf], size=(10, 12))
    costs[0, :] = 1.0
    costs[:, -1] = 2.0
    path = FieldDStar(costs, interpolate=False, smooth=False).plan((0, 0), (10, 12))
    assert np.asarray(path.points).tolist() == probe["points"][0]
