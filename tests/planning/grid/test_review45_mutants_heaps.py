"""The grid searches' queues where their mutants survived (review 45, MUTANT24).

A mutation review of :mod:`navkit.planning.grid._search_heap`,
:mod:`navkit.planning.grid._dstar_heap` and :mod:`navkit.planning.grid._prefetch`
found these behaviours unpinned:

* ``F_TIE_BITS``: the tests read the constant back (``F_BAND`` is the mask of
  ``F_TIE_BITS`` bits), so clearing 10 bits instead of 12 passed them all,
  though the module documents that 10 still split plateaus at a band's edge
  on open grids. A query that does: with 10 bits A* expanded 1949 cells for a
  path of 168 on an open 256 x 256 grid, with 12 the path alone;
* ``clear_box``'s two thresholds (half the grid's width, the blank block's
  4096 records) and a box one column wide, whose count Field D*'s reset
  reports;
* the documented cache-line layout of both heaps (slot 1 starting a 64-byte
  line), which no search result shows;
* a D* Lite key raised above a child tied with it in the first component
  sinks below that child (the tie-breaking by the second component on the
  way down; the model tests' random draws never needed it);
* ``_lazy_zeros``' threshold: exactly ``_LAZY_BYTES`` bytes are mapped pages.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.planning import AStarPlanner, astar

SQRT2 = math.sqrt(2.0)


@pytest.mark.parametrize("corner_cutting", [False, True])
def test_a_plateau_split_by_a_ten_bit_band_is_expanded_as_the_path_alone(
    corner_cutting: bool,
) -> None:
    """Mutant ``F_TIE_BITS = 10``: 1949 cells expanded (found among 400 random queries)."""
    costs = np.ones((256, 256))
    start, goal = (46, 194), (213, 40)
    path = astar(costs, start, goal, corner_cutting=corner_cutting)
    assert path.expanded == len(path.cells) == 168
    assert math.isclose(path.cost, 13 + 154 * SQRT2, rel_tol=1e-13)
    assert AStarPlanner(costs).plan(start, goal).expanded == 168


def _used_records(nrows: int, ncols: int) -> np.ndarray:
    from navkit.planning.grid._dstar_heap import node_records

    records = node_records(nrows * ncols)[0]
    records[:, :2] = 1.0  # g and rhs of a search
    return records


def _blank(records: np.ndarray) -> np.ndarray:
    """Which records are blank (g = rhs = inf, unqueued), as (nodes,) booleans."""
    slots = records.view(np.int64)[:, 2]
    return np.isinf(records[:, 0]) & np.isinf(records[:, 1]) & (slots == -1)


@pytest.mark.parametrize(
    ("ncols", "span", "whole"), [(8, 4, True), (8, 3, False), (9, 4, False), (8, 1, False)]
)
def test_a_box_half_the_grid_wide_or_wider_blanks_its_rows_whole(
    ncols: int, span: int, whole: bool
) -> None:
    """``clear_box``'s count (what Field D*'s reset reports) and records at the documented
    threshold (mutants: ``2 * span > ncols``, which left a box of exactly half the width a
    box; ``right <= left``, which blanked nothing of a box one column wide)."""
    from navkit.planning.grid._dstar_heap import clear_box

    records = _used_records(5, ncols)
    assert clear_box(records, ncols, (1, 2), (1, span)) == 2 * (ncols if whole else span)
    blank = _blank(records).reshape(5, ncols)
    want = np.zeros((5, ncols), dtype=bool)
    if whole:
        want[1:3, :] = True
    else:
        want[1:3, 1 : span + 1] = True
    np.testing.assert_array_equal(blank, want)


@pytest.mark.parametrize(("span", "whole"), [(4096, False), (4097, True)])
def test_a_box_wider_than_the_blank_block_blanks_its_rows_whole(span: int, whole: bool) -> None:
    """Up to the block's 4096 records a narrow box is copied row by row (mutant:
    ``span >= size``, which blanked a row of 8193 records for a box of 4096)."""
    from navkit.planning.grid._dstar_heap import clear_box

    ncols = 2 * 4096 + 2
    records = _used_records(2, ncols)
    assert clear_box(records, ncols, (1, 1), (0, span - 1)) == (ncols if whole else span)
    blank = _blank(records).reshape(2, ncols)
    assert not blank[0].any()
    assert blank[1].sum() == (ncols if whole else span)


def test_aligned_heap_puts_every_family_of_children_on_one_cache_line() -> None:
    """Slot 1, the root's first child, starts a 64-byte line (mutant: a 32-byte alignment,
    which no search result shows: the layout is the module's documented contract)."""
    from navkit.planning.grid._search_heap import REC_BASE, aligned_heap

    for entries in [*range(1, 40), 1000, 4097]:
        heap = aligned_heap(entries)
        assert heap.dtype == np.uint64 and heap.shape == (2 * (entries + REC_BASE),)
        assert heap.flags.c_contiguous and heap.flags.writeable
        assert heap.ctypes.data % 64 == 0
        assert (heap.ctypes.data + 16 * (REC_BASE + 1)) % 64 == 0


def test_node_records_keys_put_every_family_of_children_on_one_cache_line() -> None:
    """The D* Lite heap's keys likewise: slot 1's key starts a 64-byte line."""
    from navkit.planning.grid._dstar_heap import node_records

    for n in [*range(1, 40), 1000, 70_000]:
        _records, (nodes, keys, _pos, size) = node_records(n)
        assert keys.shape == (n, 2) and keys.dtype == np.float64 and keys.flags.c_contiguous
        assert (keys.ctypes.data + 16) % 64 == 0
        assert not keys.any() and not nodes.any() and size.tolist() == [0]


def test_a_raised_key_sinks_below_a_child_tied_in_its_first_component() -> None:
    """Requeued with a larger key, a node moves below a child whose first component
    equals its own and whose second is smaller (mutant: the descent compared first
    components only and left it on top: the child was popped second)."""
    from navkit.planning.grid._dstar_heap import heap_new, heap_pop, heap_push

    nodes, keys, pos, size = heap_new(4)
    heap_push(nodes, keys, pos, size, 0, 1.0, 0.0)
    heap_push(nodes, keys, pos, size, 1, 2.0, 1.0)
    heap_push(nodes, keys, pos, size, 0, 2.0, 2.0)  # raised: (2, 2) after (2, 1)
    assert [heap_pop(nodes, keys, pos, size) for _ in range(2)] == [1, 0]
    assert size.tolist() == [0]


@pytest.mark.parametrize("dtype", [np.int64, np.float64])
def test_zeros_of_exactly_the_threshold_are_mapped_pages(dtype: type[np.generic]) -> None:
    """Zeros of at least ``_LAZY_BYTES`` bytes are mapped pages, as documented (mutant:
    ``nbytes > _LAZY_BYTES``; the earlier tests took one element below and three above)."""
    from test_review37_FDFRESH_lazy_heap import _mapped

    from navkit.planning.grid._dstar_heap import _LAZY_BYTES, _lazy_zeros

    out = _lazy_zeros(_LAZY_BYTES // 8, dtype)
    assert out.shape == (_LAZY_BYTES // 8,) and out.dtype == dtype
    assert _mapped(out) and out.flags.writeable and not out.any()
