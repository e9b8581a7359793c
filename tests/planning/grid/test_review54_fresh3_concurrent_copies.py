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

And the copy decided that after copying the state: a call under way as the
copy began that ended during it left the copy's token first, and the copy kept
a search copied while the call wrote it (of copies of a 300 x 300 planner taken
back to back while another thread updated costs and replanned, 84 in 15 s; 2
of 40 of them replanned for ever). It is decided as the copy's token goes in.
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


class _Slow(FieldDStar):
    """A planner whose replan waits at its start (its token in) and whose copy, once its
    state is copied, waits for that replan to end."""

    __slots__ = ()
    in_replan = threading.Event()
    go_on = threading.Event()
    copied = threading.Event()
    replanned = threading.Event()
    waiting = threading.Event()  # set: the next replan waits

    def _require_plan(self, method: str) -> None:
        if _Slow.waiting.is_set():
            _Slow.waiting.clear()
            _Slow.in_replan.set()
            assert _Slow.go_on.wait(30.0)
        super()._require_plan(method)

    def _snapshot(self) -> Any:
        state = super()._snapshot()
        _Slow.copied.set()
        assert _Slow.replanned.wait(30.0)
        return state


def test_a_copy_begun_during_a_call_that_ends_meanwhile_keeps_no_search() -> None:
    # The copy decided "a call under way" after copying the state: a call that ended
    # during the copy left the copy's token first, and the copy kept a search it had
    # copied while the call wrote it. Copies of a 300 x 300 planner taken back to back
    # while another thread updated costs and replanned: 84 in 15 s kept such a search,
    # and 2 of 40 of them replanned for ever. A copy begun during a call keeps none.
    planner = _Slow(np.ones((8, 8)))
    planner.plan((0, 0), (8, 8))
    planner.update_costs([(3, 3)], 5.0)
    _Slow.waiting.set()
    paths: list[Any] = []
    replanner = threading.Thread(target=lambda: paths.append(planner.replan()))
    replanner.start()
    copies: list[FieldDStar] = []
    copier = None
    try:
        assert _Slow.in_replan.wait(30.0)
        copier = threading.Thread(target=lambda: copies.append(copy.deepcopy(planner)))
        copier.start()
        assert _Slow.copied.wait(30.0)  # copied while the replan's token is first
    finally:
        _Slow.go_on.set()
        replanner.join(30.0)
        _Slow.replanned.set()
        if copier is not None:
            copier.join(30.0)
    assert paths and copies
    with pytest.raises(RuntimeError, match="call plan"):
        copies[0].replan()
    np.testing.assert_array_equal(copies[0].costs, planner.costs)
