"""The indoor scenarios' snap from a point on a wall's face (review of review 10).

Round coordinates lie on cell edges: a start or goal on the face of a wall whose
own cell is only inflated touched the wall's closed cell at the start of every
step, so no step qualified and ``plan_between`` raised the planner's "within
robot_radius" error (the earlier snap, by distance alone, took the centre beside
it). A cell the point lies on now counts only when a step enters its inside.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.sim.scenarios._indoor_nav_mapping import _passable, _segments_touch, plan_between


def corridor() -> MapPlanner:
    """A 1-cell wall in column 10 (x in [0.5, 0.55]) of 0.05 m cells, robot radius 0.1 m."""
    occupied = np.zeros((16, 16), dtype=bool)
    occupied[:, 10] = True
    occupied[6:, 5] = True
    return MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=0.05), robot_radius=0.1)


@pytest.mark.parametrize("y", [0.075, 0.475])
def test_a_point_on_a_walls_face_is_snapped_away_from_it(y: float) -> None:
    planner = corridor()
    point = (0.55, y)  # the wall's right face; its cell (column 11) is inflated
    assert planner.grid.world_to_cell(np.array(point)).tolist()[1] == 11
    snapped = _passable(planner, point)
    assert snapped == pytest.approx((0.675, y))
    path = plan_between(planner, point, (0.725, 0.075))
    assert path.points[0].tolist() == list(point)
    assert path.points[1].tolist() == pytest.approx(list(snapped))


def test_steps_from_a_cells_edge() -> None:
    cell = (np.array([0]), np.array([0]))  # the square [-1/2, 1/2]^2
    q = np.array([0.0, 0.5])  # on its right edge
    ends_r, ends_c = np.array([0, 0, 3, 1]), np.array([3, -3, 1, -1])
    # straight away, into it, obliquely away, obliquely into it
    assert _segments_touch(q, ends_r, ends_c, *cell).tolist() == [False, True, False, True]
    # A point clear of a cell still sees it touched through a corner.
    far = np.array([-1.0, 1.0])
    assert _segments_touch(far, np.array([1]), np.array([-1]), *cell).tolist() == [True]


def _clip(q: tuple[float, float], end: tuple[int, int], cell: tuple[int, int], half: Fraction,
          strict: bool) -> bool:  # fmt: skip
    """Whether segment q-end meets the closed (strict: open) square of side 2 half: exact."""
    t0, t1 = Fraction(0), Fraction(1)
    for k in range(2):
        o = Fraction(q[k])
        d = end[k] - o
        lo, hi = cell[k] - half - o, cell[k] + half - o
        if d == 0:
            if not (lo < 0 < hi if strict else lo <= 0 <= hi):
                return False
        else:
            a, b = sorted((lo / d, hi / d))
            t0, t1 = max(t0, a), min(t1, b)
    return t0 < t1 if strict else t0 <= t1


coordinate = st.one_of(
    st.floats(-4.0, 4.0), st.integers(-8, 8).map(lambda v: v / 2)  # cell edges and centres
)
cells = st.tuples(st.integers(-3, 3), st.integers(-3, 3))
HALF = Fraction(1, 2)
MARGIN = Fraction(1, 10**8)  # the grazing margin (1e-9 cells), rounded up


@settings(max_examples=60)
@given(st.tuples(coordinate, coordinate), st.lists(cells, min_size=1, max_size=3),
       st.lists(cells, min_size=1, max_size=4))  # fmt: skip
def test_segments_touch_agrees_with_exact_arithmetic(
    q: tuple[float, float], ends: list[tuple[int, int]], blocked: list[tuple[int, int]]
) -> None:
    got = _segments_touch(
        np.array(q), np.array([e[0] for e in ends]), np.array([e[1] for e in ends]),
        np.array([b[0] for b in blocked]), np.array([b[1] for b in blocked]),
    )  # fmt: skip
    for i, end in enumerate(ends):
        # A cell whose closed square holds q counts when the step enters its inside.
        on = [all(abs(Fraction(q[k]) - b[k]) <= HALF for k in range(2)) for b in blocked]
        want = any(_clip(q, end, b, HALF, strict) for b, strict in zip(blocked, on, strict=True))
        if got[i] != want:  # only within the grazing margin of some square
            if got[i]:
                assert any(_clip(q, end, b, HALF + MARGIN, False) for b in blocked)
            else:
                assert not any(_clip(q, end, b, HALF - MARGIN, True) for b in blocked)
