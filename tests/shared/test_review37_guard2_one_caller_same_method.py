"""one_caller: a signal handler's refused call of the same method leaves the runner running.

``one_caller`` (the guard of ``FieldDStar``, ``ScanMapper.update``) kept a token
``(thread, method)`` per call and took it out with ``list.remove``, which takes
the first *equal* item. A signal handler calling the same method as the call it
interrupted (same thread, same method: an equal token) was refused, as it should
be, but took the runner's token out, not its own: a handler that landed between
the runner's append and its check (and caught its refusal) left the runner
refused in its turn, "called during this planner's own plan", though nothing
else was running. Each token now holds an object of its own (review 37, GUARD2).

The interleavings are forced at every delivery point of the runner
(``interrupt_points.DELIVERY``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from interrupt_points import interleaved
from navkit._shared.locks import one_caller
from navkit.planning import FieldDStar


class _Counter:
    __slots__ = ("_callers", "n")

    def __init__(self) -> None:
        self._callers: list[Any] = []
        self.n = 0

    @one_caller
    def bump(self) -> int:
        self.n += 1
        return self.n


def test_a_handlers_refused_call_of_the_same_method_leaves_the_runner_running() -> None:
    points = interleaved(0, _Counter().bump, lambda: None)["points"]
    assert points >= 3
    refused_handlers = 0
    for k in range(1, points + 1):
        counter = _Counter()
        out = interleaved(k, counter.bump, counter.bump)
        handler = out.get("h")
        # The runner is never refused by a handler's call that was itself refused.
        if isinstance(handler, RuntimeError):
            refused_handlers += 1
            assert out["m"] == 1, (k, out["m"])
            assert counter.n == 1
        elif "h" in out:
            # The handler ran before the runner's token went in (the runner, second,
            # bumped after it or was refused) or after it came out (both bumped).
            assert (handler, out["m"]) in ((1, 2), (2, 1)) or (
                handler == 1 and isinstance(out["m"], RuntimeError)
            ), (k, handler, out["m"])
        assert counter._callers == []
    assert refused_handlers > 0


def test_a_field_dstar_plan_goes_on_when_a_handlers_plan_is_refused() -> None:
    rng = np.random.default_rng(37)
    costs = 1.0 + rng.random((12, 15))
    want = FieldDStar(costs).plan((0, 0), (12, 15))
    probe = FieldDStar(costs)
    points = interleaved(0, lambda: probe.plan((0, 0), (12, 15)), lambda: None)["points"]
    refused = 0
    # The guard's own points come first: the append's return is among the first ten.
    for k in range(1, min(points, 10) + 1):
        planner = FieldDStar(costs)
        out = interleaved(k, lambda p=planner: p.plan((0, 0), (12, 15)),  # type: ignore[misc]
                           lambda p=planner: p.plan((12, 0), (0, 15)))  # type: ignore[misc]  # fmt: skip
        if isinstance(out.get("h"), RuntimeError):
            refused += 1
            assert not isinstance(out["m"], RuntimeError), (k, out["m"])
            assert out["m"].points.tobytes() == want.points.tobytes()
        assert planner._callers == []
    assert refused > 0
