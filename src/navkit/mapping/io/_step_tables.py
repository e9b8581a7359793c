"""Step functions of float32 log-odds by table look-up, without an ``exp`` per cell.

What ROS messages and map images store of a cell (a percentage, a grey level)
is a non-decreasing step function of its float32 log-odds. :func:`step_table`
finds where each step starts, once, with the grid's own formula as the oracle;
:class:`StepLookUp` then gives any float32's level with a bucket look-up and a
comparison, the same as the formula for every float32 (the tests check every
bit pattern).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from navkit.mapping import OccupancyGrid

# Cells per block of a look-up (:class:`StepLookUp`, and of the images and
# messages made with it): its temporaries (a few tens of bytes a cell, at most
# 2 MiB) stay in the processor's cache whatever the grid's size.
LOOK_UP_BLOCK = 1 << 16


class StepTable(NamedTuple):
    """Look-up tables of a step function of float32 log-odds (see :func:`step_table`)."""

    base: NDArray[np.uint8]
    thresholds: NDArray[np.float32]
    rounds: int


def _order_keys(values: NDArray[np.float32]) -> NDArray[np.int64]:
    """Positions of float32 ``values`` in the float32 order: integers that sort as they do.

    The int32 view of a non-negative float32 grows with it; that of a negative
    one grows with its magnitude, so flipping its 31 low bits orders it (-0 at
    -1, +0 at 0, -inf and +inf at the ends). Its own inverse:
    :func:`_order_values`.
    """
    keys = values.view(np.int32).astype(np.int64)
    keys ^= (keys >> 31) & 0x7FFFFFFF
    return keys


def _order_values(keys: NDArray[np.int64]) -> NDArray[np.float32]:
    """The float32 values at positions ``keys`` of the float32 order (see :func:`_order_keys`)."""
    bits = keys ^ ((keys >> 31) & 0x7FFFFFFF)
    return bits.astype(np.int32).view(np.float32)


def step_table(
    level_of: Callable[[NDArray[np.float32]], NDArray[np.integer[Any]]], levels: int
) -> StepTable:
    """Look-up tables giving the level (0..``levels`` <= 255) of any float32 log-odds.

    ``level_of`` is the formula the tables replace: a non-decreasing step
    function of log-odds within the grid's range (±1e6), 0 at -1e6 and
    ``levels`` at 1e6. Level ``k`` starts at the first float32 ``t[k - 1]``
    where ``level_of`` reaches ``k`` (found by bisection over the float32
    order, with ``level_of`` itself as the oracle). A value's 16 high bits
    (sign, exponent and 7 bits of mantissa) name a bucket of float32s in which
    ``base`` is the level of its smallest value; ``base[bucket]`` plus the
    number of thresholds the value reaches within the bucket (``rounds``
    comparisons ``value >= t[level]``, with ``t[levels] = nan``) is its level.
    A bucket spans under 1 % of its values, so ``rounds`` is 1 when the
    thresholds lie further apart than that (it is the most any bucket holds).
    Values below -1e6 get level 0, above 1e6 ``levels``, NaN that of ±inf.

    Made in a few milliseconds, on the machine that uses it, with its own
    ``exp``; the tests compare it with ``level_of``'s formula for every
    float32 bit pattern.
    """
    ends = np.array([-1e6, 1e6], dtype=np.float32)  # the grid's range, ±1e6
    if np.asarray(level_of(ends)).tolist() != [0, levels]:  # pragma: no cover - exp(1e6) = inf
        raise AssertionError(f"the formula does not span 0..{levels} over the grid's range")
    keys = _order_keys(ends)
    # All bisections at once: for level k = 1..levels, the value at position
    # low[k - 1] has a smaller level, that at high[k - 1] k or more.
    steps = np.arange(1, levels + 1)
    low = np.full(levels, keys[0])
    high = np.full(levels, keys[1])
    while np.any(high - low > 1):
        mid = (low + high) // 2
        reached = np.asarray(level_of(_order_values(mid))) >= steps
        high = np.where(reached, mid, high)
        low = np.where(reached, low, mid)
    # After the last step, NaN: no value (+inf included) is >= it.
    thresholds = np.append(_order_values(high), np.float32(np.nan))
    thresholds.flags.writeable = False
    # Smallest and largest float32 of each bucket of 65536 bit patterns (the
    # buckets of +inf and -inf hold NaNs besides; those of NaNs alone stay 0).
    top = np.arange(1 << 16, dtype=np.int64) << 16
    negative = top >= 1 << 31
    first = np.where(negative, np.minimum(top | 0xFFFF, 0xFF800000), top)
    last = np.where(negative, top, np.minimum(top | 0xFFFF, 0x7F800000))
    numbers = (top & 0x7FFFFFFF) <= 0x7F800000
    steps_at = thresholds[:levels]
    count_first = np.searchsorted(steps_at, first.astype(np.uint32).view(np.float32), "right")
    count_last = np.searchsorted(steps_at, last.astype(np.uint32).view(np.float32), "right")
    base = np.where(numbers, count_first, 0).astype(np.uint8)
    base.flags.writeable = False
    rounds = int(np.max(np.where(numbers, count_last - count_first, 0)))
    return StepTable(base, thresholds, rounds)


class StepLookUp:
    """The levels of a :class:`StepTable` for blocks of up to ``size`` float32 values.

    Holds its scratch arrays (13 bytes a value), reused from block to block.
    """

    def __init__(self, table: StepTable, size: int) -> None:
        self._table = table
        self._index = np.empty(size, dtype=np.intp)
        self._reached = np.empty(size, dtype=np.float32)
        self._mask = np.empty(size, dtype=np.bool_)

    def __call__(self, block: NDArray[np.float32], out: NDArray[np.uint8]) -> None:
        """Write the level of each value of 1-D ``block`` into ``out`` (uint8, same size)."""
        base, thresholds, rounds = self._table
        m = block.size
        index, reached, mask = self._index[:m], self._reached[:m], self._mask[:m]
        # The bucket: the 16 high bits of the float32 (sign, exponent, 7 bits of mantissa).
        np.right_shift(block.view(np.uint32), 16, out=index, casting="unsafe")
        np.take(base, index, out=out, mode="clip")
        for _ in range(rounds):
            np.take(thresholds, out, out=reached, mode="clip")
            np.greater_equal(block, reached, out=mask)
            out += mask


def row_probability(logodds: NDArray[np.float32]) -> NDArray[np.float64]:
    """:meth:`OccupancyGrid.probability` of float32 values within the grid's range (1-D)."""
    return OccupancyGrid(logodds.reshape(1, -1), resolution=1.0).probability().reshape(-1)
