"""Grid searches after tens of millions of earlier ones (review 28, the long-run lens).

Each thread's A* scratch marks its records with the stamp of the search that
wrote them; the stamp grows by 2 a search and is stored shifted left by 4 in an
int32, so after about 6.7e7 searches (a 10 Hz replanner for 77 days) it must
start again, with the records cleared, before it overflows. The run up to there
is simulated by setting the thread's stamp just below the limit: searches on
either side of the restart give the results of a fresh thread, bit for bit.
(Without the restart, measured: the search at the limit misread its records and
asked for a 32 GiB queue.)
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning.grid import AStarPlanner, astar
from navkit.planning.grid import _workspace as workspace


def _grid() -> np.ndarray:
    rng = np.random.default_rng(28)
    # Costs from 1 to 1000: too wide for the bucket queue, so the distance field
    # runs Dijkstra on the same scratch as A*.
    grid = np.where(rng.random((40, 50)) < 0.2, np.inf, 1.0 + 999.0 * rng.random((40, 50)))
    grid[0, 0] = grid[-1, -1] = 1.0
    return grid


def test_searches_across_the_stamp_restart_are_fresh_searches(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    grid = _grid()
    planner = AStarPlanner(grid)
    # A workspace of the test's own: setting this thread's stamp back afterwards
    # would leave it below the marks these searches wrote, and later searches in
    # the process (other tests') misread them (review 35: a flaky "no path").
    monkeypatch.setattr(workspace, "_local", workspace._ThreadWorkspace())
    monkeypatch.setattr(workspace._local, "stamp", 0)
    expected = astar(grid, (0, 0), (39, 49))
    field = planner.distance_field((39, 49))
    limit = workspace._STAMP_LIMIT
    # The stamp only grows between restarts (a stamp set back would read the
    # records of later searches as this one's): set once, then search on.
    monkeypatch.setattr(workspace._local, "stamp", limit - 12)
    stamps = []
    for _ in range(5):
        path = astar(grid, (0, 0), (39, 49))
        stamps.append(workspace._local.stamp)
        assert path.cost == expected.cost
        assert path.expanded == expected.expanded
        assert np.array_equal(path.cells, expected.cells)
        assert np.array_equal(planner.distance_field((39, 49)), field)
        stamps.append(workspace._local.stamp)
    assert max(stamps) + 1 < limit  # never a mark at or beyond the limit
    assert stamps[0] == limit - 10 and min(stamps) == 2  # it restarted on the way
