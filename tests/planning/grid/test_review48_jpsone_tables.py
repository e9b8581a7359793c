"""Jump point search's bit tables from one pass over the grid (review 48, JPSONE).

:func:`navkit.planning.grid._jps_kernels.jps_tables` builds the row and
column bit tables and checks the values in one compiled pass
(:func:`~navkit.planning.grid._jps_kernels._build_tables`): each row's cells
go through bytes packed 8 at a time by a multiplication, the columns are
the rows' 64 x 64 bit blocks transposed. Checked here against a NumPy
reference (``np.packbits`` of the padded traversable mask and of its
transpose), on shapes whose padded lines end just before, at or after a
64-bit word edge, and for the values: the same range and the same
exceptions as :func:`~navkit.planning.grid._limits.checked_cost_range`.

The one pass also means no grid-sized temporary: before review 48 the rows
were marked into a bool array of ``(rows + 2) x 64 W`` bytes (eight times
the row table, kept per thread and made again for each new shape) and
packed from there. The memory a call takes is now the two tables and one
bit row's bytes.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from navkit import NoPathError
from navkit.planning import AStarPlanner, astar
from navkit.planning.grid._jps_kernels import jps_tables
from navkit.planning.grid._limits import checked_cost_range

#: Sizes around the word edges of a padded line (cells + 2 border cells).
EDGE_SIZES = (1, 2, 3, 61, 62, 63, 64, 65, 66, 125, 126, 127, 128, 129, 130)


def _packed(mask: np.ndarray) -> np.ndarray:
    """The bit lines of a padded mask as :func:`jps_tables` lays them out (padding words around)."""
    lines, length = mask.shape
    words = ((length + 63) >> 6) + 2
    bools = np.zeros((lines, 64 * words), dtype=bool)
    bools[:, 64 : 64 + length] = mask
    return np.packbits(bools.reshape(-1), bitorder="little").view("<u8")


def _reference(costs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(row table, column table) of ``costs`` from ``np.packbits``."""
    rows, cols = costs.shape
    padded = np.zeros((rows + 2, cols + 2), dtype=bool)
    padded[1:-1, 1:-1] = np.isfinite(costs)
    return _packed(padded), _packed(np.ascontiguousarray(padded.T))


def _grid(rows: int, cols: int, seed: int, blocked: float = 0.3) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.where(rng.random((rows, cols)) < blocked, np.inf, 1.0)


@pytest.mark.parametrize("rows", EDGE_SIZES)
def test_tables_match_packbits_at_word_edges(rows: int) -> None:
    for cols in EDGE_SIZES:
        costs = _grid(rows, cols, seed=rows * 1000 + cols)
        row_bits, col_bits, lowest, highest = jps_tables(costs)
        want_rows, want_cols = _reference(costs)
        assert np.array_equal(row_bits, want_rows), (rows, cols)
        assert np.array_equal(col_bits, want_cols), (rows, cols)
        finite = costs[np.isfinite(costs)]
        assert (lowest, highest) == ((1.0, 1.0) if finite.size else (np.inf, -np.inf)), (rows, cols)


@pytest.mark.parametrize("fill", [np.inf, 1.0, 7.5])
def test_uniform_grids_all_blocked_or_all_free(fill: float) -> None:
    """Blocks of 64 x 64 cells all blocked or all free take the transposition's shortcuts."""
    costs = np.full((130, 200), fill)
    row_bits, col_bits, lowest, highest = jps_tables(costs)
    want_rows, want_cols = _reference(costs)
    assert np.array_equal(row_bits, want_rows)
    assert np.array_equal(col_bits, want_cols)
    assert (lowest, highest) == ((np.inf, -np.inf) if fill == np.inf else (fill, fill))


def test_cost_range_of_varying_grids_is_checked_cost_range() -> None:
    """The range decides ``method="auto"`` (A* when the costs vary): the same as the cost check."""
    rng = np.random.default_rng(5)
    for shape in [(1, 1), (3, 70), (70, 3), (129, 65)]:
        costs = np.where(rng.random(shape) < 0.2, np.inf, rng.uniform(1.0, 1e12, shape))
        costs.flat[rng.integers(costs.size)] = 1e12  # the largest cost allowed
        _, lowest, highest = checked_cost_range(costs)
        got = jps_tables(np.ascontiguousarray(costs))
        assert (got[2], got[3]) == (lowest, highest), shape
        want_rows, want_cols = _reference(costs)
        assert np.array_equal(got[0], want_rows) and np.array_equal(got[1], want_cols)


@pytest.mark.parametrize(
    "bad", [np.nan, -np.nan, -1.0, 0.0, 0.5, -np.inf, 1e12 * (1 + 2**-40), 2e12]
)
def test_invalid_values_raise_as_the_cost_check(bad: float) -> None:
    """A value anywhere (here the last cell of a row past a word edge) is refused, by name."""
    costs = _grid(70, 130, seed=3)
    costs[41, 129] = bad
    with pytest.raises(ValueError) as want:
        checked_cost_range(costs, "grid")
    with pytest.raises(ValueError) as got:
        jps_tables(costs, "grid")
    assert str(got.value) == str(want.value)
    assert "grid" in str(got.value)
    with pytest.raises(ValueError, match="costs"):
        astar(costs, (0, 0), (1, 1), method="jps")


def test_tables_take_no_grid_sized_scratch() -> None:
    """A call's memory is its tables and one bit row's bytes (before: 8 x the row table more).

    Fails before review 48, whose ``np.less`` marked the rows into a
    ``(rows + 2) x 64 W`` bool array, made anew for each shape.
    """
    costs = _grid(300, 333, seed=9)
    rows, cols = costs.shape
    table_bytes = 8 * (
        (rows + 2) * (((cols + 2 + 63) >> 6) + 2) + (cols + 2) * (((rows + 2 + 63) >> 6) + 2)
    )
    jps_tables(_grid(8, 8, seed=1))  # the kernel loaded (its first call allocates for numba)
    tracemalloc.start()
    try:
        tables = jps_tables(costs)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert tables[0].nbytes + tables[1].nbytes == table_bytes
    # One bit row's bytes and a 64-word block, plus a few small objects.
    assert peak <= table_bytes + 8 * (8 * ((cols + 2 + 63) >> 6) + 64) + 4096


def test_one_shot_answers_as_the_prepared_planner() -> None:
    """The one-shot search (tables built per call) and a prepared planner: the same paths."""
    for seed, shape in enumerate([(64, 130), (129, 63), (100, 100)]):
        costs = _grid(*shape, seed=seed, blocked=0.25)
        costs[0, :] = costs[-1, :] = 1.0
        planner = AStarPlanner(costs, method="jps")
        rng = np.random.default_rng(seed)
        free = np.argwhere(np.isfinite(costs))
        for _ in range(20):
            s, t = (tuple(int(v) for v in free[i]) for i in rng.integers(len(free), size=2))
            try:
                want = planner.plan(s, t)
            except NoPathError:
                with pytest.raises(NoPathError):
                    astar(costs, s, t, method="jps")
                continue
            got = astar(costs, s, t, method="jps")
            assert got.cost == want.cost and got.expanded == want.expanded
            assert np.array_equal(got.cells, want.cells)
            assert got.cost == pytest.approx(astar(costs, s, t).cost, rel=1e-12)


def test_inputs_unchanged() -> None:
    costs = _grid(40, 90, seed=4)
    costs[0, 0] = costs[39, 89] = 1.0
    before = costs.copy()
    jps_tables(costs)
    for method in ("jps", "auto"):
        astar(costs, (0, 0), (0, 0), method=method)
    assert np.array_equal(costs, before)
