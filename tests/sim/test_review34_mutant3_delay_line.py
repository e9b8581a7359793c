"""The sensor streams' delay line at its tolerance edges (review 34, mutation testing of _latency).

``DelayLine`` promises: an item queued with ``push_at(due, item)`` is due at ``due``;
``pop_due(now)`` returns, in order, every item due by ``now`` within 1e-9 s and
nothing later; copies hold their own queue. Times here are dyadic rationals
(exact in float64), so each expectation is decided by exact arithmetic, with
the tolerance probed at 0.5e-9 inside and 2e-9 outside it.
"""

from __future__ import annotations

import copy
import math

from navkit.sim._latency import DelayLine


def test_due_time_is_kept_within_the_tolerance() -> None:
    line: DelayLine[str] = DelayLine(0.25)
    assert line.delay == 0.25
    line.push_at(1.25, "a")  # sampled at 1.0
    assert line.pop_due(1.25 - 2e-9) == []
    assert len(line) == 1
    assert line.pop_due(1.25 - 0.5e-9) == [(1.25, "a")]
    assert len(line) == 0
    assert line.pop_due(10.0) == []


def test_an_item_due_at_the_tolerance_edge_is_delivered() -> None:
    line: DelayLine[str] = DelayLine(0.0)
    edge = 1.0 + DelayLine._EPS  # the very float pop_due compares with
    line.push_at(edge, "e")
    line.push_at(math.nextafter(edge, math.inf), "later")
    assert line.pop_due(1.0) == [(edge, "e")]
    assert len(line) == 1


def test_every_due_item_leaves_in_order_and_no_later_one() -> None:
    line: DelayLine[int] = DelayLine(0.5)
    for k in range(6):
        line.push_at(0.5 + k * 0.125, k)  # due 0.5, 0.625, ..., 1.125
    assert line.pop_due(0.75) == [(0.5, 0), (0.625, 1), (0.75, 2)]
    assert len(line) == 3
    assert line.pop_due(0.875 + 0.5e-9) == [(0.875, 3)]
    assert line.pop_due(2.0) == [(1.0, 4), (1.125, 5)]


def test_push_at_queues_at_the_given_due_time() -> None:
    line: DelayLine[str] = DelayLine(3.0)
    line.push_at(0.5, "x")  # not 3.5: the due time given, whatever the delay
    line.push_at(3.0, "y")
    assert line.pop_due(0.5) == [(0.5, "x")]
    assert line.pop_due(2.999) == []
    assert line.pop_due(3.0) == [(3.0, "y")]


def test_a_zero_delay_delivers_at_the_stamp() -> None:
    line: DelayLine[str] = DelayLine(0.0)
    line.push_at(-1.5, "n")
    assert line.pop_due(-1.5 - 2e-9) == []
    assert line.pop_due(-1.5) == [(-1.5, "n")]


def test_copies_hold_their_own_queue() -> None:
    line: DelayLine[str] = DelayLine(1.0)
    line.push_at(1.0, "a")
    twin = copy.copy(line)
    deep = copy.deepcopy(line)
    assert twin.delay == 1.0
    assert twin.pop_due(1.0) == [(1.0, "a")]
    twin.push_at(3.0, "t")
    assert twin.pop_due(3.0) == [(3.0, "t")]
    assert len(line) == 1 and len(deep) == 1
    line.push_at(1.5, "b")
    assert len(twin) == 0 and len(deep) == 1
    assert line.pop_due(5.0) == [(1.0, "a"), (1.5, "b")]
    assert deep.delay == 1.0 and deep.pop_due(1.0) == [(1.0, "a")]
