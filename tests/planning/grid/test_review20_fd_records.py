"""Field D* (review 20): node records blanked in one pass (``clear_records``).

``node_records`` (a new planner's records) blanks them by copying a block of
blank records along them instead of two fills; ``clear_records`` does it in
place, for records used before. Every record must come out g = rhs =
inf and unqueued (slot -1) bit for bit, whatever the count (below, at and
across the block's size), a non-contiguous array must be refused rather than
a copy filled, and a used planner must plan exactly as a new one.
"""

from __future__ import annotations

import contextlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.errors import NoPathError
from navkit.planning import FieldDStar
from navkit.planning.grid._dstar_heap import (
    _BLANK_BLOCK,
    POS,
    RECORD,
    clear_records,
    node_records,
    positions,
)

_BLOCK = _BLANK_BLOCK.shape[0] // RECORD


def _blank_bits(n: int) -> np.ndarray:
    """The int64 bit patterns of ``n`` blank records, made the plain way."""
    records = np.full((n, RECORD), np.inf)
    records.view(np.int64)[:, POS] = -1
    return records.view(np.int64)


@pytest.mark.parametrize("n", [0, 1, 2, _BLOCK - 1, _BLOCK, _BLOCK + 1, 3 * _BLOCK + 5])
def test_new_records_are_blank_bit_for_bit(n: int) -> None:
    records, (_, _, pos, _) = node_records(n)
    assert records.shape == (n, RECORD) and records.flags.c_contiguous
    np.testing.assert_array_equal(records.view(np.int64), _blank_bits(n))
    assert pos.shape == (n,) and np.all(pos == -1)
    if n:
        assert np.shares_memory(pos, records)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 3 * _BLOCK), st.integers(0, 2**32 - 1))
def test_clear_records_blanks_used_records(n: int, seed: int) -> None:
    records = node_records(n)[0]
    rng = np.random.default_rng(seed)
    records.view(np.int64)[:] = rng.integers(-(2**62), 2**62, size=(n, RECORD))
    clear_records(records)
    np.testing.assert_array_equal(records.view(np.int64), _blank_bits(n))


def test_clear_records_refuses_a_non_contiguous_array() -> None:
    wide = np.zeros((10, 2 * RECORD))
    with pytest.raises(ValueError):
        clear_records(wide[:, :RECORD])
    assert np.all(wide == 0.0)


def test_blank_block_is_read_only() -> None:
    assert not _BLANK_BLOCK.flags.writeable
    assert np.all(positions(_BLANK_BLOCK.reshape(-1, RECORD)) == -1)


@settings(max_examples=15, deadline=None)
@given(st.integers(2, 30), st.integers(2, 30), st.integers(0, 2**32 - 1))
def test_a_used_planner_plans_as_a_new_one(rows: int, cols: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    costs = rng.uniform(1.0, 4.0, (rows, cols))
    costs[rng.random((rows, cols)) < 0.25] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    used = FieldDStar(costs)
    with contextlib.suppress(NoPathError, ValueError):  # only the reset matters
        used.plan((rows, cols), (0, 0))
    for start, goal in (((0, 0), (rows, cols)), ((rows, 0), (0, cols))):
        try:
            want = FieldDStar(costs).plan(start, goal)
        except (NoPathError, ValueError) as exc:  # the used planner must fail alike
            with pytest.raises(type(exc)):
                used.plan(start, goal)
            continue
        got = used.plan(start, goal)
        np.testing.assert_array_equal(got.points, want.points)
        assert (got.cost, got.expanded) == (want.cost, want.expanded)
