"""The Bresenham line's ties and the grid's last row (MUTANT15).

Where the exact line passes half-way between two cells of the minor axis, the
line kernels take the cell on the side of the end they trace from (the
lexicographically smaller one): the minor offset ``k * d / n`` of the k-th cell
is rounded to the nearest integer, halves towards 0. The tests checked each
cell to within half a cell of the exact line, which both ties meet: the
mutants that stepped the other way at a tie (``e2 >= -dr``, ``e2 <= dc``)
survived, and with them every line of sight, ray and planner result could move
by a cell. Here the whole line is compared with that rule, in exact integers.

``line_is_free`` also refused a line only past the grid's columns and above
its first row in the tests: taking the rows from ``shape[1]`` survived (a
3 x 6 grid read rows 3 to 5 past its end).
"""

from __future__ import annotations

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit._shared.lines import line_cells, line_is_free


def _half_down(q: int, n: int) -> int:
    """``q / n`` rounded to the nearest integer, halves towards 0 (``n > 0``)."""
    a = abs(q)
    rounded = -((n - 2 * a) // (2 * n))  # ceil(a / n - 1/2), in integers
    return rounded if q >= 0 else -rounded


def _reference(r0: int, c0: int, r1: int, c1: int) -> list[tuple[int, int]]:
    (ra, ca), (rb, cb) = sorted([(r0, c0), (r1, c1)])
    dr, dc = rb - ra, cb - ca
    n = max(abs(dr), abs(dc))
    out = []
    for k in range(n + 1):
        if abs(dr) >= abs(dc):
            out.append((ra + k * np.sign(dr), ca + (_half_down(k * dc, n) if n else 0)))
        else:
            out.append((ra + _half_down(k * dr, n), ca + k * np.sign(dc)))
    return out if (ra, ca) == (r0, c0) else out[::-1]


def test_the_reference_rounds_halves_towards_0() -> None:
    assert [_half_down(q, 2) for q in range(-3, 4)] == [-1, -1, 0, 0, 0, 1, 1]
    assert [_half_down(q, 4) for q in (-6, -2, 2, 3, 6)] == [-1, 0, 0, 1, 1]


def test_every_line_in_a_box_is_the_rounded_exact_line() -> None:
    span = range(-4, 5)
    for r0 in span:
        for c0 in span:
            for r1 in span:
                for c1 in span:
                    got = [tuple(cell) for cell in line_cells(r0, c0, r1, c1).tolist()]
                    assert got == _reference(r0, c0, r1, c1), (r0, c0, r1, c1)


coords = st.integers(-1000, 1000)


@settings(max_examples=100, deadline=None)
@given(coords, coords, coords, coords)
@example(0, 0, 2, 1)  # a tie at row 1: column 0, the start's
@example(2, 1, 0, 0)
@example(0, 0, 1, 2)  # a tie at column 1: row 0
@example(0, 1, 2, 0)
def test_long_lines_are_the_rounded_exact_line(r0: int, c0: int, r1: int, c1: int) -> None:
    got = [tuple(cell) for cell in line_cells(r0, c0, r1, c1).tolist()]
    assert got == _reference(r0, c0, r1, c1)


def test_ties_step_on_the_far_side_of_the_half_way_cell() -> None:
    assert line_cells(0, 0, 2, 1).tolist() == [[0, 0], [1, 0], [2, 1]]
    assert line_cells(2, 1, 0, 0).tolist() == [[2, 1], [1, 0], [0, 0]]
    assert line_cells(0, 0, 1, 2).tolist() == [[0, 0], [0, 1], [1, 2]]
    assert line_cells(0, 1, 2, 0).tolist() == [[0, 1], [1, 1], [2, 0]]


def test_a_line_into_the_row_past_the_grid_is_not_free() -> None:
    # A 3 x 6 view of a larger free array: a kernel reading past row 2 finds free cells.
    free = np.zeros((8, 6), dtype=np.bool_)
    occ = free[:3]
    assert line_is_free(occ, 0, 0, 2, 5)
    for r1, c1 in ((3, 0), (3, 5), (5, 2), (4, 4)):
        assert not line_is_free(occ, 0, 0, r1, c1), (r1, c1)
        assert not line_is_free(occ, r1, c1, 0, 0), (r1, c1)
    # Tall and narrow: the columns past the grid's last.
    tall = np.zeros((6, 8), dtype=np.bool_)[:, :3]
    assert line_is_free(tall, 0, 0, 5, 2)
    assert not line_is_free(tall, 0, 0, 0, 3)
    assert not line_is_free(tall, 5, 0, 2, 4)
