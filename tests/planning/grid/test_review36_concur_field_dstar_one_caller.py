"""A FieldDStar takes one call at a time: another thread's or a signal handler's is refused.

A planner keeps its search state between calls and is documented as used by
one thread at a time. Two threads planning on one planner at once (a ROS 2
timer replanning while a map callback updates costs and plans) ran both
searches on the same arrays: wrong paths, or errors about something else
("no path", a node "off the grid"). A signal handler planning on the planner
its main thread was using did the same. Now its plans, replans and cost
updates refuse to start while another is under way (``RuntimeError``, saying
whether the other call is another thread's or the same thread's), change
nothing, and the call under way finishes as if alone; copies and pickles of a
planner in use are not in use.

The interleavings are forced: a subclass holds a call inside its search until
the test has made the second call.
"""

from __future__ import annotations

import copy
import pickle
import signal
import sys
import threading
from typing import Any

import numpy as np
import pytest

from navkit.planning import FieldDStar
from thread_runs import run_switching_often


def _costs() -> np.ndarray:
    rng = np.random.default_rng(36)
    costs = np.where(rng.random((30, 40)) < 0.2, np.inf, 1.0 + rng.random((30, 40)))
    costs[0, :] = costs[-1, :] = 1.0
    costs[:, 0] = costs[:, -1] = 1.0
    return costs


class _Held(FieldDStar):
    """A planner whose searches run ``inside`` (once) before they search."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.inside: list[Any] = []

    def _search(self, ends: Any) -> Any:
        while self.inside:
            self.inside.pop()()
        return super()._search(ends)


def _same(a: Any, b: Any) -> bool:
    return a.points.tobytes() == b.points.tobytes() and a.cost == b.cost


def test_a_call_from_another_thread_during_a_plan_is_refused_and_changes_nothing() -> None:
    costs = _costs()
    planner = _Held(costs)
    planner.plan((0, 0), (30, 40))
    inside, go_on = threading.Event(), threading.Event()

    def hold() -> None:
        inside.set()
        assert go_on.wait(60)

    planner.inside.append(hold)
    answers: list[Any] = []
    thread = threading.Thread(target=lambda: answers.append(planner.plan((30, 0), (0, 40))))
    thread.start()
    try:
        assert inside.wait(60)
        refused = []
        for call in (
            lambda: planner.replan((1, 1)),
            lambda: planner.plan((0, 0), (30, 40)),
            lambda: planner.plan_cells((0, 0), (29, 39)),
            lambda: planner.plan_world((0.5, 0.5), (20.5, 30.5)),
            lambda: planner.replan_world((0.5, 0.5)),
            lambda: planner.update_costs([(5, 5)], 100.0),
        ):
            with pytest.raises(RuntimeError, match="another thread was in this _Held's plan"):
                call()
            refused.append(True)
    finally:
        go_on.set()
        thread.join(60)
    assert len(refused) == 6
    # The other thread's plan is a fresh planner's, and nothing was changed.
    fresh = FieldDStar(costs)
    assert _same(answers[0], fresh.plan((30, 0), (0, 40)))
    assert planner.costs.tobytes() == costs.tobytes()
    assert _same(planner.replan(), fresh.replan())
    assert planner._callers == []


@pytest.mark.skipif(sys.platform == "win32", reason="needs SIGUSR1")
def test_a_signal_handlers_call_during_a_plan_is_refused_and_the_plan_goes_on() -> None:
    costs = _costs()
    planner = _Held(costs)
    refused: list[str] = []

    def handler(signum: int, frame: Any) -> None:
        try:
            planner.plan((30, 0), (0, 40))
        except RuntimeError as error:
            refused.append(str(error))

    previous = signal.signal(signal.SIGUSR1, handler)
    try:
        # Python runs the handler at once, inside the plan's search.
        planner.inside.append(lambda: signal.raise_signal(signal.SIGUSR1))
        path = planner.plan((0, 0), (30, 40))
    finally:
        signal.signal(signal.SIGUSR1, previous)
    assert len(refused) == 1
    assert "_Held.plan was called during this _Held's own plan, in the same" in refused[0]
    assert _same(path, FieldDStar(costs).plan((0, 0), (30, 40)))
    assert planner._callers == []


def test_a_handlers_uncaught_refusal_ends_the_call_it_interrupted_cleanly() -> None:
    costs = _costs()
    planner = _Held(costs)
    planner.inside.append(lambda: planner.update_costs([(5, 5)], 3.0))
    with pytest.raises(RuntimeError, match="own plan, in the same thread"):
        planner.plan((0, 0), (30, 40))
    assert planner._callers == []
    # Usable again, and the refused update changed nothing.
    assert planner.costs.tobytes() == costs.tobytes()
    assert _same(planner.plan((0, 0), (30, 40)), FieldDStar(costs).plan((0, 0), (30, 40)))


def test_copies_and_pickles_of_a_planner_in_use_are_not_in_use() -> None:
    costs = _costs()
    planner = _Held(costs)
    copies: list[Any] = []

    def take() -> None:
        copies.extend((copy.copy(planner), copy.deepcopy(planner)))
        copies.append(pickle.loads(pickle.dumps(planner)))

    planner.inside.append(take)
    planner.plan((0, 0), (30, 40))
    for other in copies:
        assert other._callers == []
        assert _same(other.plan((30, 0), (0, 40)), FieldDStar(costs).plan((30, 0), (0, 40)))


def test_two_threads_on_one_planner_get_right_paths_or_the_refusal() -> None:
    costs = _costs()
    planner = FieldDStar(costs)
    ends = [((0, 0), (30, 40)), ((30, 0), (0, 40))]
    want = [FieldDStar(costs).plan(*e) for e in ends]
    outcomes: list[list[str]] = [[], []]

    def run(k: int) -> None:
        # Until 60 plans ran (a refused call is quick: the other thread's plan runs on).
        for _ in range(200_000):
            if outcomes[k].count("right") >= 60:
                return
            try:
                got = planner.plan(*ends[k])
            except RuntimeError as error:
                outcomes[k].append("refused" if "another thread" in str(error) else repr(error))
                continue
            except Exception as error:  # what the old code raised
                outcomes[k].append(repr(error))
                continue
            outcomes[k].append("right" if _same(got, want[k]) else "wrong path")

    run_switching_often(run)
    for seen in outcomes:
        assert set(seen) <= {"right", "refused"}, sorted(set(seen))
        assert seen.count("right") == 60
    assert planner._callers == []
