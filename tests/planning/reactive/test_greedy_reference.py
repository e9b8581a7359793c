"""greedy_step against a slow pure-Python reference written from its docstring.

The reference shares no code with navkit's kernels: its lines are the 8-connected
Bresenham lines defined by exact rational rounding (traced from the
lexicographically smaller end, halves rounded toward that end), its grids are
built from the scan's ranges directly, and ties are judged with the documented
tolerance plus a margin for the rounding of ``g + h``.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.lines import line_cells
from navkit.errors import NoPathError
from navkit.mapping import LaserScan, LocalGrid
from navkit.planning import greedy_step

Cell = tuple[int, int]


def _half_toward_start(t: Fraction) -> int:
    low = math.floor(t)
    if t - low == Fraction(1, 2):
        return low if t > 0 else low + 1
    return round(t)


def reference_line(a: Cell, b: Cell) -> list[Cell]:
    """Bresenham line between two cells: one cell per step of the major axis."""
    (r0, c0), (r1, c1) = sorted([a, b])
    dr, dc = r1 - r0, c1 - c0
    if abs(dc) >= abs(dr):
        step = 1 if dc >= 0 else -1
        return [
            (r0 + _half_toward_start(Fraction(k * dr, abs(dc)) if dc else Fraction(0)),
             c0 + k * step)
            for k in range(abs(dc) + 1)
        ]
    step = 1 if dr >= 0 else -1
    return [(r0 + k * step, c0 + _half_toward_start(Fraction(k * dc, abs(dr))))
            for k in range(abs(dr) + 1)]


def test_reference_line_is_the_mapping_layers_line() -> None:
    # The documented lines are the mapping layer's: the reference must trace the same cells.
    for r1 in range(-9, 10):
        for c1 in range(-9, 10):
            want = {(int(r), int(c)) for r, c in line_cells(0, 0, r1, c1)}
            assert set(reference_line((0, 0), (r1, c1))) == want


class Undecidable(Exception):
    """A cell's progress test is decided by the last bit of two hypot implementations."""


def feasible_cells(
    occupied: list[list[bool]], res: float, half: float, goal: tuple[float, float],
    progress: bool,
) -> tuple[dict[Cell, tuple[float, float]], int]:
    """``{cell: (g, h)}`` of every feasible candidate, and the number of candidates."""
    n = len(occupied)
    c = n // 2
    h_robot = math.hypot(*goal)
    found: dict[Cell, tuple[float, float]] = {}
    candidates = 0
    for i in range(n):
        for j in range(n):
            if (i, j) == (c, c) or occupied[i][j]:
                continue
            x, y = j * res - half, i * res - half
            h = math.hypot(goal[0] - x, goal[1] - y)
            if progress and abs(h - h_robot) <= 4.0 * math.ulp(h_robot):
                # h == h_robot to rounding: Python's hypot and the kernel's (libm)
                # may round either way, so no reference can tell (see check).
                raise Undecidable
            if progress and not h < h_robot:
                continue
            candidates += 1
            # The robot's own cell never blocks.
            if any(occupied[r][q] and (r, q) != (c, c) for r, q in reference_line((c, c), (i, j))):
                continue
            found[(i, j)] = (math.hypot(x, y), h)
    return found, candidates


def allowed(found: dict[Cell, tuple[float, float]], tol: float, slack: float) -> set[Cell]:
    """Cells the documented rule may pick: ``g + h`` within ``tol`` of the least, then least ``h``.

    ``slack`` covers the rounding of ``g + h`` and ``h`` (the kernel's and the
    reference's may differ by a few ulps).
    """
    best = min(g + h for g, h in found.values())
    h_min = min(h for g, h in found.values() if g + h <= best + tol - slack)
    return {cell for cell, (g, h) in found.items()
            if g + h <= best + tol + slack and h <= h_min + slack}


def check(grid: LocalGrid, goal: tuple[float, float], progress: bool) -> None:
    reach = 0.5 * grid.resolution * (1.0 + 1e-6)  # the robot's own cell, border included
    if abs(goal[0]) <= reach and abs(goal[1]) <= reach:
        # The goal in the robot's cell: the last step, to the goal itself.
        step = greedy_step(grid, goal, require_progress=progress)
        c = grid.size // 2
        assert step.cell == (c, c) and step.h == 0.0
        assert step.g == pytest.approx(math.hypot(*goal), rel=1e-15)
        np.testing.assert_array_equal(step.waypoint_robot_xy, goal)
        return
    try:
        found, candidates = feasible_cells(grid.occupied.tolist(), grid.resolution,
                                           grid.half_width, goal, progress)
    except Undecidable:
        # A free cell as far from a far goal as the robot (e.g. 0.1 m sideways
        # of a goal 1e9 m away): whether it makes progress is rounding.
        assume(False)
        return
    scale = math.hypot(*goal) + grid.half_width
    tol = 1e-12 * scale  # the documented tie tolerance
    # g + h and h are computed to a few ulps of scale; allow 64.
    rounding = 64.0 * 2.0**-52 * scale
    if not found:
        with pytest.raises(NoPathError) as info:
            greedy_step(grid, goal, require_progress=progress)
        assert info.value.expanded == candidates
        return
    step = greedy_step(grid, goal, require_progress=progress)
    assert step.cell in allowed(found, tol, rounding), (step.cell, found[step.cell])
    assert step.candidates == candidates
    g, h = found[step.cell]
    assert step.g == pytest.approx(g, rel=1e-14, abs=rounding)
    assert step.h == pytest.approx(h, rel=1e-14, abs=rounding)
    np.testing.assert_array_equal(step.waypoint_robot_xy, grid.cell_to_world(step.cell))


coordinate = st.one_of(
    st.floats(-3.0, 3.0),
    st.integers(-30, 30).map(lambda k: 0.05 * k),  # cell centres and cell edges
    st.sampled_from([0.0, 1e9, -1e9, 1e8, 5e-324]),
    st.floats(-1e9, 1e9),
)


@settings(max_examples=50, deadline=None)
@given(
    st.integers(0, 6),
    st.sampled_from([0.1, 0.05, 0.25, 0.07, 1.0, 1e-6, 1e6]),
    st.floats(0.0, 0.7),
    st.integers(0, 2**32 - 1),
    st.booleans(),
    st.tuples(coordinate, coordinate),
    st.booleans(),
)
def test_matches_the_reference_on_random_grids(
    half_cells: int, res: float, density: float, seed: int, mirrored: bool,
    goal: tuple[float, float], progress: bool,
) -> None:
    half_cells = min(half_cells, int(1e6 / res))  # half_width <= 1e6 m
    occupied = np.random.default_rng(seed).random((2 * half_cells + 1,) * 2) < density
    if mirrored:  # symmetric grids make exact ties of g + h and of h
        occupied = occupied | occupied[::-1] | occupied[:, ::-1]
    check(LocalGrid(occupied, resolution=res, half_width=half_cells * res), goal, progress)


test_matches_the_reference_on_random_grids_thoroughly = slow_twin(
    test_matches_the_reference_on_random_grids, max_examples=300
)


@st.composite
def scans(draw: st.DrawFn) -> LaserScan:
    n = draw(st.integers(1, 90))
    sign = draw(st.sampled_from([1.0, -1.0]))
    range_min = draw(st.sampled_from([0.0, 0.05]))
    range_max = draw(st.sampled_from([0.95, 1.0, 1.05, 3.5]))
    # Readings exactly at range_min / range_max, at the grid's edge and corner, invalid ones.
    special = st.sampled_from([math.nan, math.inf, -math.inf, range_min, range_max, 0.0, 0.95,
                               1.0, 1.05, 1.05 * math.sqrt(2.0)])
    ranges = draw(st.lists(st.one_of(special, st.floats(0.0, 2.0)), min_size=n, max_size=n))
    return LaserScan(np.array(ranges), angle_min=-math.pi * sign,
                     angle_increment=sign * 2.0 * math.pi / n, range_min=range_min,
                     range_max=range_max)


def reference_grid(scan: LaserScan) -> list[list[bool]]:
    """The paper's 21 x 21 grid, i = round(10 y + 10), j = round(10 x + 10), half up."""
    occupied = [[False] * 21 for _ in range(21)]
    for r, angle in zip(scan.ranges.tolist(), scan.angles().tolist(), strict=True):
        if not (math.isfinite(r) and scan.range_min <= r < scan.range_max):
            continue
        i = math.floor((r * math.sin(angle) + 1.0) / 0.1 + 0.5)
        j = math.floor((r * math.cos(angle) + 1.0) / 0.1 + 0.5)
        if 0 <= i < 21 and 0 <= j < 21:
            occupied[i][j] = True
    return occupied


@settings(max_examples=50, deadline=None)
@given(scans(), st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)), st.booleans())
def test_matches_the_reference_on_scans(
    scan: LaserScan, goal: tuple[float, float], progress: bool
) -> None:
    grid = scan.to_local_grid()
    assert grid.occupied.tolist() == reference_grid(scan)
    check(grid, goal, progress)


test_matches_the_reference_on_scans_thoroughly = slow_twin(
    test_matches_the_reference_on_scans, max_examples=150
)


def test_a_far_goal_does_not_widen_ties_to_a_worse_cell() -> None:
    # A wall 0.1 m ahead (|y| <= 0.3 m), the goal 1e9 m straight ahead (a documented
    # input). Stepping to (0, -0.1) costs 0.1 m more than the straight line; the
    # tie tolerance was 1e-9 * ‖goal‖ = 1 m, so a cell costing 0.9 m more (at the
    # grid's edge, 1 m to the side) "tied" and won for being nearer the goal.
    occupied = np.zeros((21, 21), dtype=bool)
    occupied[7:14, 11] = True
    grid = LocalGrid(occupied, resolution=0.1, half_width=1.0)
    for distance in (3.0, 1e6, 1e8, 1e9):
        step = greedy_step(grid, (distance, 0.0))
        assert step.cell in {(9, 10), (11, 10)}  # one cell aside
        check(grid, (distance, 0.0), False)
    # On a free grid the step goes straight toward a far goal, not diagonally.
    free = LocalGrid(np.zeros((3, 3), dtype=bool), resolution=0.1, half_width=0.1)
    assert greedy_step(free, (0.0, 1e9)).cell == (2, 1)


@pytest.mark.parametrize(
    ("goal", "error", "match"),
    [
        ((1e9 + 1.0, 0.0), ValueError,
         r"^goal_robot_xy must lie within ±1e\+09 m in x and y, got 1000000001\.0$"),
        ((0.0, -math.inf), ValueError, r"^goal_robot_xy must contain only finite values"),
        ((True, 0.0), TypeError, r"^goal_robot_xy must hold real numbers"),
        ((1j, 0.0), TypeError, r"^goal_robot_xy must hold real numbers"),
        (np.float64(1.0), ValueError, r"^goal_robot_xy must be 1-D"),
        ([[1.0, 0.0]], ValueError, r"^goal_robot_xy must be 1-D"),
    ],
)
def test_bad_goals_are_refused_by_name(goal: object, error: type[Exception], match: str) -> None:
    # The value is shown in full: 1e9 + 1 used to read "got 1e+09", the limit itself.
    with pytest.raises(error, match=match):
        greedy_step(LocalGrid.from_points([]), goal)  # type: ignore[arg-type]
    # The boundary itself is a valid goal.
    assert greedy_step(LocalGrid.from_points([]), (1e9, -1e9)).cell == (0, 20)
