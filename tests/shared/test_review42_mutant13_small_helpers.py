"""Gaps a mutation review of ``navkit._shared``'s small helpers found (review 42, MUTANT13).

Each test fails with a mutant that passed every earlier test and passes on the
real code:

- ``relative_to_cwd`` with its ``return ""`` for a removed working directory
  deleted fell through to an unbound name (``UnboundLocalError`` in a "does
  not exist" message, in place of the message);
"""

from __future__ import annotations

import os
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit._shared.grid_coords import inside
from navkit._shared.products import ordered_dot, scaled_product
from navkit._shared.relative_paths import relative_to_cwd
from navkit.mapping import LocalGrid, OccupancyGrid

#: Largest finite float64, exactly.
_MAX = Fraction(float(np.finfo(np.float64).max))


@pytest.mark.skipif(sys.platform == "win32", reason="Windows cannot remove the working directory")
def test_relative_to_cwd_says_nothing_when_the_working_directory_was_removed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    with pytest.raises(FileNotFoundError):
        os.getcwd()  # the case under test
    assert relative_to_cwd("map.yaml") == ""
    assert relative_to_cwd(Path("maps") / "map.yaml") == ""
    assert relative_to_cwd(tmp_path / "map.yaml") == ""


@pytest.mark.parametrize("n", [1, 2, 14, 15, 16, 17, 40])
def test_ordered_dot_adds_up_to_15_terms_itself_and_leaves_more_to_np_dot(
    n: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(n)
    a, b = rng.normal(size=n), rng.normal(size=n)
    calls: list[int] = []
    plain = np.dot

    def watched(x: Any, y: Any) -> Any:
        calls.append(len(x))
        return plain(x, y)

    monkeypatch.setattr(np, "dot", watched)
    got = ordered_dot(a, b)
    monkeypatch.undo()
    assert calls == ([] if n <= 15 else [n])
    if n > 15:
        assert got == float(np.dot(a, b))
    else:
        total = 0.0
        for x, y in zip(a.tolist(), b.tolist(), strict=True):
            total += x * y
        assert got == total


def _exact_row_product(row: np.ndarray, matrix_t: np.ndarray) -> list[Fraction]:
    """``row @ matrix_t`` summed exactly."""
    return [
        sum(
            (Fraction(x) * Fraction(y) for x, y in zip(row.tolist(), col, strict=True)), Fraction(0)
        )
        for col in matrix_t.T.tolist()
    ]


def test_scaled_product_scales_each_overflowing_row_by_its_own_largest_input() -> None:
    matrix_t = np.array([[1.0, 0.5], [1.0, -2.0], [0.25, 1e-3]])
    rows = np.array(
        [
            [1.5e308, -1.2e308, 3.0],  # a sum that fits, one beyond the range
            [1e-300, 4e307, -4e307],  # tiny and huge inputs in one row
            [1.0, 2.0, 3.0],  # plain
            [8e307, 8e307, 1e300],
            [-3e306, 1.7e308, -1.7e308],
        ]
    )
    for batch in (rows, rows[[1, 3]], rows[[0, 4, 1]], rows[None, 3], rows[1]):
        got = scaled_product(batch, matrix_t)
        assert got.shape == (*batch.shape[:-1], 2)
        for row, out in zip(np.atleast_2d(batch), np.atleast_2d(got), strict=True):
            # Each term and partial sum is rounded once at the row's scale: a few ulps of
            # the largest term, far below the error of any other scale's overflow or loss.
            terms = [
                abs(Fraction(x) * Fraction(y))
                for x in row.tolist()
                for y in matrix_t.ravel().tolist()
            ]
            bound = 4 * Fraction(2) ** -52 * max(terms)
            for g, w in zip(out.tolist(), _exact_row_product(row, matrix_t), strict=True):
                if abs(w) > _MAX:
                    assert g == (np.inf if w > 0 else -np.inf), (row, out)
                else:
                    assert np.isfinite(g) and abs(Fraction(g) - w) <= bound, (row, out)
    assert np.isinf(scaled_product(rows, matrix_t)[0, 1])


@pytest.mark.parametrize("shape", [(2, 4), (4, 2), (1, 1), (3, 3)])
def test_inside_takes_each_cell_of_the_grid_and_none_of_the_ring_around_it(
    shape: tuple[int, int],
) -> None:
    rows, cols = shape
    ring = [(r, c) for r in range(-1, rows + 1) for c in range(-1, cols + 1)]
    cells = np.array(ring, dtype=np.int64)
    want = [0 <= r < rows and 0 <= c < cols for r, c in ring]
    assert inside(cells, shape).tolist() == want
    if rows == 2 and cols == 4:  # the same through the grids' public contains()
        grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.5)
        assert grid.shape == shape
        assert grid.contains(grid.cell_to_world(cells)).tolist() == want
    local = LocalGrid.from_points([])
    n = local.size
    edge = np.array([[0, n - 1], [0, n], [n - 1, 0], [n, 0], [n - 1, n - 1], [-1, 0]])
    assert local.contains(local.cell_to_world(edge)).tolist() == [
        True,
        False,
        True,
        False,
        True,
        False,
    ]
