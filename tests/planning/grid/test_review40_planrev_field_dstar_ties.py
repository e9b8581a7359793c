"""Field D*'s replans equal fresh plans bit for bit where values tie (review 40, PLANREV).

``FieldDStar.replan`` promises the path a fresh plan on the current costs
returns, and its notes say why: every node value the walk reads is settled
first, so a repaired plan reads exactly the values a fresh plan reads. The
stateful test (``test_review11_stateful_field_dstar.py``) checks replans
against fresh plans to 1e-9 on random costs. Ties are where exactness could
break: on grids of one cost, and mirror-symmetric ones, many nodes' values
are reached by routes equal in exact arithmetic but summed in other orders,
and a repair expands its nodes in another order than a fresh search (other
keys after the start moves, the km offset in them). Here the paths must be
the same arrays and costs bit for bit, and so must every node value settled
in both planners (key below the start's).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.planning import FieldDStar

SQRT2 = math.sqrt(2.0)
Outcome = tuple[np.ndarray, float] | str


def outcome(planner: FieldDStar, method: str, *args: object) -> Outcome:
    try:
        path = getattr(planner, method)(*args)
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__
    return path.points.copy(), path.cost


def settled(planner: FieldDStar, start: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Node values, and where a node is consistent with its key below the start's."""
    rows, cols = planner._nrows, planner._ncols
    g = np.asarray(planner._g).reshape(rows, cols)
    rhs = np.asarray(planner._rhs).reshape(rows, cols)
    i, j = np.mgrid[0:rows, 0:cols]
    dr, dc = np.abs(i - start[0]), np.abs(j - start[1])
    h = planner._hscale * (np.maximum(dr, dc) + (SQRT2 - 1.0) * np.minimum(dr, dc))
    end = g[start] * (1.0 - 1e-9)
    return g, (g == rhs) & (np.minimum(g, rhs) + h < end)


@pytest.mark.parametrize("options", [{}, {"interpolate": False}, {"lookahead": False}])
def test_replans_on_tied_grids_are_fresh_plans_bit_for_bit(options: dict[str, bool]) -> None:
    rng = np.random.default_rng(40)
    compared = 0
    for trial in range(12):
        n = int(rng.integers(8, 33))
        cost = float(rng.choice([1.0, 2.0, 3.7]))
        costs = np.full((n, n), cost)
        if trial % 2:
            # Mirror-symmetric obstacles (both axes).
            blocked = rng.random((n, n)) < 0.1
            blocked |= blocked[::-1] | blocked[:, ::-1] | blocked[::-1, ::-1]
            costs[blocked] = np.inf
        start = (int(rng.integers(n + 1)), int(rng.integers(n + 1)))
        goal = (n - start[0], n - start[1])  # the mirror image: symmetric routes tie
        planner = FieldDStar(costs, **options)
        got = outcome(planner, "plan", start, goal)
        if isinstance(got, str) or start == goal:
            continue
        current = costs.copy()
        for _ in range(6):
            points = got[0] if not isinstance(got, str) else np.array([[n / 2, n / 2]])
            k = int(rng.integers(points.shape[0]))
            after = points[min(k + 1, points.shape[0] - 1)]
            p = points[k] + rng.random() * (after - points[k])
            cell = (int(np.clip(round(p[0]), 0, n - 1)), int(np.clip(round(p[1]), 0, n - 1)))
            # Block, restore or change a cell near the path, with its mirror image.
            value = float(rng.choice([np.inf, cost, 2.0 * cost]))
            cells = np.array([cell, (n - 1 - cell[0], n - 1 - cell[1])])
            planner.update_costs(cells, value)
            current[tuple(cells.T)] = value
            if rng.random() < 0.3:
                moved = (int(rng.integers(n + 1)), int(rng.integers(n + 1)))
                got = outcome(planner, "replan", moved)
                if got != "ValueError":
                    start = moved
                else:
                    got = outcome(planner, "replan")
            else:
                got = outcome(planner, "replan")
            fresh = FieldDStar(current, **options)
            want = outcome(fresh, "plan", start, goal)
            if isinstance(got, str) or isinstance(want, str):
                assert got == want
                continue
            np.testing.assert_array_equal(got[0], want[0])
            assert got[1] == want[1]
            g_repaired, done_repaired = settled(planner, start)
            g_fresh, done_fresh = settled(fresh, start)
            both = done_repaired & done_fresh
            np.testing.assert_array_equal(g_repaired[both], g_fresh[both])
            compared += int(both.sum())
    assert compared > 1000
