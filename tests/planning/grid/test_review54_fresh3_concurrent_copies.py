"""Copies of a FieldDStar taken by two threads at once both keep its search (review 54, FRESH3).

2c44fc9 takes a copy or pickle of a FieldDStar as a short call of the planner
(``__getstate__`` under the one-call guard): a plan, replan or cost update
started meanwhile is refused, and a copy made while a call is under way keeps
the costs but not the search, which that call may be writing. A copy under way
counted as such a call too, although a copy only reads: of two threads taking
copies at once (a visualiser and a checkpoint saver, say) with no plan running,
the second's copy came without the search, and its ``replan`` raised "call
plan() first". A copy drops the search only when a call that writes it is
under way; copies taken at once each keep it.
"""

from __future__ import annotations

import copy
import pickle
import threading
from typing import Any

import numpy as np
import pytest

from navkit.planning import FieldDStar


class _Held(FieldDStar):
    """A planner whose first copy waits, inside the copy's guard, until told to go on."""

    __slots__ = ()
    entered = threading.Event()
    release = threading.Event()
    hold = threading.Event()  # set: the next copy waits

    def _snapshot(self) -> Any:
        if _Held.hold.is_set():
            _Held.hold.clear()
            _Held.entered.set()
            assert _Held.release.wait(30.0)
        return super()._snapshot()


@pytest.mark.parametrize("take", [copy.deepcopy, lambda p: pickle.loads(pickle.dumps(p))])
def test_a_copy_taken_while_another_thread_copies_keeps_the_search(take: Any) -> None:
    _Held.entered.clear()
    _Held.release.clear()
    _Held.hold.set()
    planner = _Held(np.ones((6, 6)))
    first = planner.plan((0, 0), (6, 6))
    planner.update_costs([(2, 2), (3, 3)], 4.0)
    held: list[FieldDStar] = []
    copier = threading.Thread(target=lambda: held.append(copy.deepcopy(planner)))
    copier.start()
    try:
        assert _Held.entered.wait(30.0)
        second = take(planner)  # this thread's copy, while the other's is under way
        # A plan started meanwhile is still refused (the copy is a call).
        with pytest.raises(RuntimeError, match="__getstate__"):
            planner.plan((0, 6), (6, 0))
    finally:
        _Held.release.set()
        copier.join(30.0)
    assert not copier.is_alive()
    want = planner.replan()
    assert want.cost > first.cost
    for twin in (held[0], second):
        again = twin.replan()  # raised "call plan() first" for the second copy
        np.testing.assert_array_equal(again.points, want.points)
        assert again.cost == want.cost
