"""Line traversal kernels shared with the planners (Bresenham, inclusive, symmetric)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.lines import line_cells, line_is_free

coords = st.integers(-30, 30)


@settings(max_examples=50, deadline=None)
@given(coords, coords, coords, coords)
def test_line_cells_is_a_bresenham_line(r0: int, c0: int, r1: int, c1: int) -> None:
    cells = line_cells(r0, c0, r1, c1)
    assert cells.shape == (max(abs(r1 - r0), abs(c1 - c0)) + 1, 2)
    assert tuple(cells[0]) == (r0, c0)
    assert tuple(cells[-1]) == (r1, c1)
    steps = np.diff(cells, axis=0)
    # 8-connected, one step along the major axis each time.
    assert np.all(np.abs(steps) <= 1)
    major = 0 if abs(r1 - r0) >= abs(c1 - c0) else 1
    assert np.all(np.abs(steps[:, major]) == 1) or len(cells) == 1
    # Every cell is the nearest one to the exact line on the minor axis.
    t = (cells[:, major] - (r0, c0)[major]) / max(1, abs((r1, c1)[major] - (r0, c0)[major]))
    t = np.abs(t)
    exact_minor = (r0, c0)[1 - major] + t * ((r1, c1)[1 - major] - (r0, c0)[1 - major])
    assert np.all(np.abs(cells[:, 1 - major] - exact_minor) <= 0.5 + 1e-9)


test_line_cells_is_a_bresenham_line_thoroughly = slow_twin(
    test_line_cells_is_a_bresenham_line, max_examples=150
)


@settings(max_examples=100, deadline=None)
@given(coords, coords, coords, coords)
def test_line_is_symmetric(r0: int, c0: int, r1: int, c1: int) -> None:
    forward = {tuple(c) for c in line_cells(r0, c0, r1, c1)}
    backward = {tuple(c) for c in line_cells(r1, c1, r0, c0)}
    assert forward == backward


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 11),
    st.integers(0, 13),
    st.integers(0, 11),
    st.integers(0, 13),
    st.integers(0, 2**32 - 1),
)
def test_line_is_free_matches_cells(r0: int, c0: int, r1: int, c1: int, seed: int) -> None:
    occ = np.random.default_rng(seed).random((12, 14)) < 0.15
    expected = not occ[tuple(line_cells(r0, c0, r1, c1).T)].any()
    assert line_is_free(occ, r0, c0, r1, c1) == expected
    assert line_is_free(occ, r1, c1, r0, c0) == expected


test_line_is_free_matches_cells_thoroughly = slow_twin(
    test_line_is_free_matches_cells, max_examples=100
)


def test_line_is_free_includes_both_ends_and_rejects_outside() -> None:
    occ = np.zeros((5, 5), dtype=np.bool_)
    assert line_is_free(occ, 0, 0, 4, 4)
    occ[4, 4] = True
    assert not line_is_free(occ, 0, 0, 4, 4)
    assert not line_is_free(occ, 4, 4, 0, 0)
    assert line_is_free(occ, 0, 0, 3, 3)
    assert not line_is_free(occ, 0, 0, 0, 5)
    assert not line_is_free(occ, -1, 0, 2, 2)


def test_line_slips_between_diagonal_obstacles() -> None:
    # Documented limitation of the 8-connected line: corners touching diagonally.
    occ = np.zeros((2, 2), dtype=np.bool_)
    occ[0, 1] = occ[1, 0] = True
    assert line_is_free(occ, 0, 0, 1, 1)
