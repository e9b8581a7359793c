"""A FieldDStar being copied refuses the calls other threads start meanwhile (review 53, FRESH).

2c44fc9 takes a copy or pickle of a FieldDStar as a short call of the planner,
so that the arrays it copies cannot change under it: a plan, replan or cost
update that another thread starts meanwhile raises RuntimeError naming the
copy, as a call meeting another call does. Its class docstring said only what
a copy taken during a call holds; a thread saving snapshots of a planner that
another thread plans with (a visualiser, a checkpoint) made that thread's calls
fail now and then (90,533 refusals against 2,180 calls with copies taken back
to back). This pins the refusal the docstring now states, and that the planner
and the copy go on as alone once the copy is made.
"""

from __future__ import annotations

import copy
import threading
from typing import Any

import numpy as np
import pytest

from navkit.planning import FieldDStar


class _Held(FieldDStar):
    """A planner whose copies wait, inside the copy's guard, until told to go on.

    (The events are the class's: a copy is a deep copy, and events do not copy.)
    """

    __slots__ = ()
    entered = threading.Event()
    release = threading.Event()

    def _snapshot(self) -> Any:
        _Held.entered.set()
        assert _Held.release.wait(30.0)
        return super()._snapshot()


def test_a_call_started_while_another_thread_copies_is_refused() -> None:
    planner = _Held(np.ones((6, 6)))
    first = planner.plan((0, 0), (6, 6))
    copies: list[FieldDStar] = []
    copier = threading.Thread(target=lambda: copies.append(copy.copy(planner)))
    copier.start()
    assert _Held.entered.wait(30.0)
    calls = {
        "plan": lambda: planner.plan((0, 6), (6, 0)),
        "replan": lambda: planner.replan((1, 1)),
        "update_costs": lambda: planner.update_costs([(2, 2)], np.inf),
    }
    try:
        for name, call in calls.items():
            with pytest.raises(RuntimeError, match="__getstate__") as refused:
                call()
            assert f"_Held.{name} was called while another thread" in str(refused.value)
    finally:
        _Held.release.set()
        copier.join(30.0)
    assert not copier.is_alive()
    # Nothing was changed by the refused calls; the copy holds the search.
    np.testing.assert_array_equal(planner.costs, np.ones((6, 6)))
    for twin in (planner, copies[0]):
        again = twin.replan()
        np.testing.assert_array_equal(again.points, first.points)
        assert again.cost == first.cost
