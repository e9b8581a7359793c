"""FieldDStar's worked examples and its random-test bound, as its Notes quote them (review 49).

The Notes say that with the defaults the path's cost was at most 1 % above the
8-connected path's in random tests, above that for about 1 in 10^4 tiny grids
and at most 4.5 %, with the example of costs ``[[2, 1, inf], [2, inf, 1],
[3.5, 1, inf]]`` (4 against 3.83), and that the unsmoothed path of an 8 × 4
grid costs 16.71 on four of its eight drawings and 16.29 on the other four;
the ``lookahead`` parameter gives how far above the 8-connected cost a path
without it came in random tests (review 49 re-measured them: 15 % and 35 %,
not 7 % and 30 %).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit import NoPathError
from navkit.planning import field_dstar

INF = np.inf


def test_the_worst_example_costs_4_against_3_83() -> None:
    costs = np.array([[2.0, 1.0, INF], [2.0, INF, 1.0], [3.5, 1.0, INF]])
    field = field_dstar(costs, (2, 0), (1, 2)).cost
    exact = field_dstar(costs, (2, 0), (1, 2), interpolate=False).cost
    assert field == pytest.approx(4.0, abs=0.005)
    assert exact == pytest.approx(3.83, abs=0.005)
    assert 1.01 < field / exact <= 1.045


def _drawings(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> list[float]:
    """The unsmoothed, lookahead-free costs over the grid's eight mirrorings and quarter turns."""
    rows, cols = costs.shape

    def moved(node: tuple[int, int], turns: int, flip: bool) -> tuple[int, int]:
        r, c = node
        nr, nc = rows + 1, cols + 1
        if flip:
            c = nc - 1 - c
        for _ in range(turns):  # np.rot90 turns (r, c) into (nc - 1 - c, r)
            r, c, nr, nc = nc - 1 - c, r, nc, nr
        return r, c

    out = []
    for turns in range(4):
        for flip in (False, True):
            grid = np.rot90(np.fliplr(costs) if flip else costs, turns)
            s, g = moved(start, turns, flip), moved(goal, turns, flip)
            out.append(field_dstar(grid, s, g, lookahead=False, smooth=False).cost)
    return out


def test_the_tie_example_costs_16_71_on_four_drawings_and_16_29_on_four() -> None:
    costs = np.array(
        [[3, 4, 3, 5], [2, 2, 1, 4], [3, 5, 1, 3], [1, 1, 1, 5],
         [2, 5, INF, INF], [INF, 5, 1, 3], [INF, 4, 1, 3], [1, 5, 2, 3]],
        dtype=float,
    )  # fmt: skip
    rounded = sorted(round(cost, 2) for cost in _drawings(costs, (8, 0), (2, 1)))
    assert rounded == [16.29] * 4 + [16.71] * 4


def test_random_tiny_grids_stay_within_the_quoted_bound() -> None:
    # Grids up to 8 x 8 (20 % impassable): "at most 4.5 %" above the exact
    # 8-connected cost, and above 1 % rarely (about 1 in 10^4: a few in 1500 at most).
    rng = np.random.default_rng(49)
    above, checked = 0, 0
    for _ in range(1500):
        rows, cols = (int(v) for v in rng.integers(2, 9, 2))
        costs = rng.uniform(1.0, 5.0, size=(rows, cols))
        costs[rng.random((rows, cols)) < 0.2] = INF
        start = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
        goal = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
        if start == goal:
            continue
        try:
            field = field_dstar(costs, start, goal).cost
        except (NoPathError, ValueError):  # walled off, or an end enclosed by impassable cells
            continue
        exact = field_dstar(costs, start, goal, interpolate=False).cost
        checked += 1
        assert field <= exact * 1.045
        above += field > exact * 1.01
    assert checked > 1000
    assert above <= 3


@pytest.mark.parametrize(
    ("varying", "unsmoothed", "smoothed"),
    [(False, 0.15, 0.04), (True, 0.35, 0.14)],
    ids=["free-blocked", "varying-costs"],
)
def test_without_the_lookahead_the_path_stays_within_the_quoted_excess(
    varying: bool, unsmoothed: float, smoothed: float
) -> None:
    # The lookahead parameter's figures (grids up to 12 x 12, a quarter impassable):
    # up to about 15 % (4 % smoothed) above the 8-connected cost on free/blocked
    # maps, 35 % (14 %) with costs uniform in [1, 10]. With the lookahead, far less.
    rng = np.random.default_rng(7 + varying)
    worst = {False: 0.0, True: 0.0}
    for _ in range(500):
        rows, cols = (int(v) for v in rng.integers(2, 13, 2))
        costs = rng.uniform(1.0, 10.0, (rows, cols)) if varying else np.ones((rows, cols))
        costs[rng.random((rows, cols)) < 0.25] = INF
        start = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
        goal = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
        if start == goal:
            continue
        try:
            exact = field_dstar(costs, start, goal, interpolate=False).cost
        except (NoPathError, ValueError):
            continue
        for smooth in (False, True):
            cost = field_dstar(costs, start, goal, lookahead=False, smooth=smooth).cost
            worst[smooth] = max(worst[smooth], cost / exact - 1.0)
        assert field_dstar(costs, start, goal).cost <= exact * 1.045
    assert 0.0 < worst[False] <= unsmoothed
    assert worst[True] <= smoothed


def test_a_free_blocked_map_without_the_lookahead_goes_well_past_the_old_7_percent() -> None:
    # Found by review 49's random tests (the same at the commit that wrote "7 %"):
    # 14.6 % above the 8-connected cost unsmoothed; the lookahead removes it.
    costs = np.array(
        [[INF, 1, 1, 1, INF, 1, 1, 1], [1, 1, INF, 1, 1, 1, 1, 1],
         [1, INF, INF, INF, 1, INF, 1, INF], [1, INF, 1, 1, 1, INF, 1, INF],
         [1, 1, 1, 1, 1, 1, INF, 1]],
        dtype=float,
    )  # fmt: skip
    exact = field_dstar(costs, (2, 7), (5, 2), interpolate=False).cost
    walked = field_dstar(costs, (2, 7), (5, 2), lookahead=False, smooth=False).cost
    assert 1.10 < walked / exact <= 1.15
    assert field_dstar(costs, (2, 7), (5, 2)).cost <= exact * 1.045
