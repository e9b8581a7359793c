"""navkit's grid planners' kernels run with numba's bounds checks on (review 36, lead).

numba does not check array indices by default: a kernel indexing past an array's end
reads or writes other memory silently (a mutant of the ray cast's scratch window did,
and only a guard-band test saw it: review 36, MUTANT7). As the simulator's and the EKF's
kernels already are (review 35), A* (this session's integer queue, grown several times),
jump point search on shapes not a multiple of 64, one-row and one-column grids, distance
fields, and Field D* plans, cost updates and replans run here in a fresh process with
``NUMBA_BOUNDSCHECK=1`` and an empty cache of its own, where any out-of-bounds index
raises ``IndexError`` (the runner first checks that they are on).
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from subprocess_probe import bounds_checked

_SCRIPT = textwrap.dedent(
    """
    import numpy as np
    from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field
    from navkit.errors import NoPathError


    rng = np.random.default_rng(11)
    # Shapes not a multiple of 64 (JPS bit tables), one row, one column, edges as start/goal.
    for shape in [(1, 70), (70, 1), (65, 130), (3, 3)]:
        costs = np.where(rng.random(shape) < 0.2, np.inf, 1.0)
        costs[0, 0] = costs[-1, -1] = costs[-1, 0] = 1.0
        for method in ("astar", "jps"):
            for cut in (False, True):
                try:
                    astar(costs, (0, 0), (shape[0] - 1, shape[1] - 1), method=method,
                          corner_cutting=cut)
                except NoPathError:
                    pass
        distance_field(costs, (shape[0] - 1, 0))
    # Weighted costs; 4-connectivity; a heuristic weight; the queue grown several times
    # (an open 400 x 400 grid with a zero-weight heuristic: Dijkstra's frontier).
    weighted = 1.0 + rng.random((400, 400)) * 5.0
    weighted[rng.random((400, 400)) < 0.1] = np.inf
    weighted[0, 0] = weighted[-1, -1] = 1.0
    for conn in (4, 8):
        try:
            astar(weighted, (0, 0), (399, 399), connectivity=conn, heuristic_weight=0.0)
            astar(weighted, (399, 399), (0, 0), connectivity=conn, heuristic_weight=2.0)
        except NoPathError:
            pass
        distance_field(weighted, (200, 200), connectivity=conn)
    planner = AStarPlanner(np.where(rng.random((200, 300)) < 0.3, np.inf, 1.0), corner_cutting=True,
                           method="jps")
    for _ in range(20):
        s = tuple(int(v) for v in rng.integers(0, (200, 300)))
        t = tuple(int(v) for v in rng.integers(0, (200, 300)))
        try:
            planner.plan(s, t)
        except (NoPathError, ValueError):
            pass
    # Field D*: a plan, cost updates at the edges and mid-path, replans.
    fd_costs = 1.0 + rng.random((60, 80)) * 3.0
    fd_costs[20:40, 30] = np.inf
    fd = FieldDStar(fd_costs)
    fd.plan((0.0, 0.0), (60.0, 80.0))
    replanned = 0
    for cells in ([(0, 0)], [(30, 31), (31, 31), (30, 32)], [(10, 50)], [(59, 79)]):
        fd.update_costs(cells, [np.inf] * len(cells) if cells != [(0, 0)] else [2.0])
        try:
            fd.replan()
            replanned += 1
        except (NoPathError, ValueError):
            pass  # the goal's corner blocked last: its kept goal is refused
    assert replanned == 3, replanned
    from navkit.planning.grid import _workspace
    assert _workspace._local.heap.size > 2 * 4096, _workspace._local.heap.size  # grown

    print("in bounds")
    """
)


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_planning_kernels_stay_in_bounds(tmp_path: Path) -> None:
    assert bounds_checked(_SCRIPT, tmp_path) == ["in bounds"]
