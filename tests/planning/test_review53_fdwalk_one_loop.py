"""Field D*'s path walk compiled as two functions, and its straight steps against an oracle.

Review 53 (FDWALK) cut what a first ``FieldDStar`` use compiles for the path
walk (issue 17: a cold plan + ``update_costs`` + ``replan`` within 3 s of CPU):
the straight corner step (``_descend``) became a mode of ``_candidates``,
picked by the walk's one candidate loop, and ``_candidates`` reads every node
value, pays every grid edge and writes every row at one site each, with the
edge minimum, the settled-value test and the grid-edge cost written in (they
were helpers ``_edge_min``, ``_settled_value`` and ``_line_cost``). Six
compiled functions became two; the paths stayed bit for bit (checked against
the tree before the change on the MovingAI maps and random grids).

The corner mode is the whole of an 8-connected walk (``interpolate=False``):
its path is checked here against Dijkstra on the node graph, written here
independently of the planner (an axis move pays the cheaper of the two cells
beside its edge, a diagonal one √2 times the cell it crosses).
"""

from __future__ import annotations

import heapq
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled
from navkit.errors import NoPathError
from navkit.planning import FieldDStar

#: A first plan, cost update and replan (the cold-start benchmark's Field D* entry),
#: then the walk module's dispatchers that compiled a signature.
_FIRST_USE = """
import json
import numpy as np
from numba.core.dispatcher import Dispatcher
from navkit.planning import FieldDStar
from navkit.planning.grid import _field_path_kernels as walk
costs = np.ones((10, 10))
costs[3:7, 5] = 3.0
planner = FieldDStar(costs)
planner.plan((0, 0), (10, 7))
planner.update_costs([(3, 1), (3, 2)], np.inf)
planner.replan()
names = sorted(name for name, value in vars(walk).items()
               if isinstance(value, Dispatcher) and value.signatures
               and value.py_func.__module__ == walk.__name__)
print(json.dumps(names))
"""


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: nothing is compiled")
def test_a_first_use_compiles_the_walk_as_two_functions(tmp_path: Path) -> None:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))  # empty: everything compiles
    out = subprocess.run(
        [sys.executable, "-c", _FIRST_USE], check=True, capture_output=True, text=True, env=env
    )
    names = json.loads(out.stdout.strip().splitlines()[-1])
    # Before review 53: also _descend, _edge_min, _settled_value and _line_cost.
    assert names == ["_candidates", "extract_path"]


def _cell(costs: np.ndarray, r: int, c: int) -> float:
    rows, cols = costs.shape
    return float(costs[r, c]) if 0 <= r < rows and 0 <= c < cols else math.inf


def _octile_oracle(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> float:
    """Least cost from node ``start`` to node ``goal`` on the 8-connected node graph."""
    rows, cols = costs.shape
    best = {start: 0.0}
    heap = [(0.0, start)]
    while heap:
        d, (i, j) = heapq.heappop(heap)
        if (i, j) == goal:
            return d
        if d > best[(i, j)]:
            continue
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                ni, nj = i + di, j + dj
                if (di, dj) == (0, 0) or not (0 <= ni <= rows and 0 <= nj <= cols):
                    continue
                if di and dj:
                    step = math.sqrt(2.0) * _cell(costs, min(i, ni), min(j, nj))
                elif di:  # along column j: cells (r, j - 1) and (r, j)
                    r = min(i, ni)
                    step = min(_cell(costs, r, j - 1), _cell(costs, r, j))
                else:  # along row i: cells (i - 1, c) and (i, c)
                    c = min(j, nj)
                    step = min(_cell(costs, i - 1, c), _cell(costs, i, c))
                if step == math.inf:
                    continue
                nd = d + step
                if nd < best.get((ni, nj), math.inf):
                    best[(ni, nj)] = nd
                    heapq.heappush(heap, (nd, (ni, nj)))
    return math.inf


@pytest.mark.parametrize("seed", range(6))
def test_the_8_connected_walk_steps_to_neighbours_along_a_least_cost_path(seed: int) -> None:
    rng = np.random.default_rng(5300 + seed)
    rows, cols = (int(v) for v in rng.integers(4, 24, size=2))
    levels = [1.0, 1.0, 1.5, 2.0, 3.25, 10.0, math.inf]
    costs = rng.choice(levels, size=(rows, cols))
    checked = 0
    for _ in range(8):
        passable = np.argwhere(np.isfinite(costs))
        if len(passable) < 2:
            break
        a, b = (passable[k] for k in rng.choice(len(passable), size=2, replace=False))
        start = (int(a[0]), int(a[1]))
        goal = (int(b[0]) + 1, int(b[1]) + 1)  # the far corner of a passable cell
        expected = _octile_oracle(costs, start, goal)
        planner = FieldDStar(costs, interpolate=False, smooth=False)
        if expected == math.inf:
            with pytest.raises(NoPathError):
                planner.plan(start, goal)
            continue
        path = planner.plan(start, goal)
        nodes = np.asarray(path.points) + 0.5  # grid frame: node - 0.5
        assert nodes[0].tolist() == [float(start[0]), float(start[1])]
        assert nodes[-1].tolist() == [float(goal[0]), float(goal[1])]
        moves = np.diff(nodes, axis=0)
        # Every step is a move to one of the 8 neighbouring nodes.
        assert np.all(np.abs(moves) <= 1.0) and np.all(np.abs(moves).sum(axis=1) >= 1.0)
        assert np.array_equal(nodes, np.round(nodes))
        assert path.cost == pytest.approx(expected, rel=1e-12)
        # A replan with nothing changed walks the same nodes.
        again = planner.replan()
        assert np.array_equal(np.asarray(again.points), np.asarray(path.points))
        checked += 1
    assert checked >= 1
