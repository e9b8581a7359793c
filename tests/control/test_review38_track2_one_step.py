"""A path tracker takes one ``step`` at a time (review 38, TRACK2).

Review 37 made a ``set_path`` landing in a ``step`` safe but left two steps at
once unguarded. Both read the progress before either wrote it, and the later
store won: a signal handler's step (or another thread's) at a later pose
recorded a progress of 4.6 m, then the interrupted step stored its own 4.0 m
over it — the progress, documented never to decrease, went back, and
RegulatedPurePursuit's memory of its lookahead point and (omni) direction of
travel mixed the two steps, so the next commands differed from those of any
order of the two (7 to 50 of the 25 to 59 interleavings of one step). A step
called while another is under way now raises ``RuntimeError`` (saying whether
the other is another thread's or the same thread's, a signal handler's),
changes nothing, and the step under way goes on as alone.

``RegulatedPurePursuit`` with a ``clearance`` function: a ``set_path`` while
the function ran made the step raise "clearance(x, y) called step or set_path
of the tracker it serves", also when another thread or a signal handler had
called it. The message now says what happened and names the possible callers.

Each test here fails on the code before the guard (checked: the nested step
was run, the progress went back; the thread's step was run; the message).
"""

from __future__ import annotations

import copy
import pickle
import threading
from typing import Any

import numpy as np
import pytest

from interrupt_points import interleaved
from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D, integrate

PATH = np.column_stack([np.arange(11.0), np.zeros(11)])  # waypoints 1 m apart
MAIN = Pose2D(4.0, 0.02, 0.1)  # the interrupted step's pose
LATER = Pose2D(5.0, 0.05, 0.0)  # the handler's: farther along


def _clearance(x: float, y: float) -> float:
    return 0.3 + 0.1 * abs(x - y)


MAKERS: dict[str, Any] = {
    "FollowTheCarrot": FollowTheCarrot,
    "FollowTheCarrot(omni)": lambda: FollowTheCarrot(drive="omni"),
    "RegulatedPurePursuit": RegulatedPurePursuit,
    "RegulatedPurePursuit(omni)": lambda: RegulatedPurePursuit(drive="omni"),
    "RegulatedPurePursuit(clearance)": lambda: RegulatedPurePursuit(clearance=_clearance),
    "OnOffTracker": OnOffTracker,
}


def _state(tracker: Any) -> tuple[Any, ...]:
    """Everything a step reads and writes, private memory included."""
    state = tracker._state
    values = [getattr(state, name) for name in state.fields()]
    return tuple(v.points_xy.tobytes() if name == "line" else v
                 for name, v in zip(state.fields(), values, strict=True))  # fmt: skip


def _in_use(make: Any) -> Any:
    tracker = make()
    tracker.set_path(PATH, goal_yaw=0.5)
    for i in range(41):
        tracker.step(Pose2D(0.1 * i, 0.02, 0.1), 0.05)
    return tracker


def _follow(tracker: Any, pose: Pose2D, count: int) -> list[Twist2D]:
    out = []
    for _ in range(count):
        cmd = tracker.step(pose, 0.05)
        out.append(cmd)
        pose = integrate(pose, cmd, 0.05)
    return out


@pytest.mark.parametrize("name", list(MAKERS))
def test_a_step_inside_a_step_is_refused_and_the_step_under_way_goes_on(name: str) -> None:
    base = _in_use(MAKERS[name])
    alone = copy.deepcopy(base)
    main_cmd = alone.step(MAIN, 0.05)
    # The handler's step before or after the main one (where it lands outside it).
    after = copy.deepcopy(alone)
    late_after = after.step(LATER, 0.05)
    before = copy.deepcopy(base)
    late_before = before.step(LATER, 0.05)
    main_after = before.step(MAIN, 0.05)
    assert alone.progress < after.progress  # the later pose is farther along
    then = _follow(copy.deepcopy(alone), LATER, 20)
    probe = copy.deepcopy(base)
    points = interleaved(0, lambda: probe.step(MAIN, 0.05), lambda: None)["points"]
    refused = 0
    for k in range(1, points + 1):
        tracker = copy.deepcopy(base)
        out = interleaved(k, lambda t=tracker: t.step(MAIN, 0.05),  # type: ignore[misc]
                          lambda t=tracker: t.step(LATER, 0.05))  # type: ignore[misc]  # fmt: skip
        if isinstance(out["h"], RuntimeError):
            refused += 1
            message = str(out["h"])
            assert "step was called during this" in message and "own step" in message, k
            assert "in the same thread (from a signal handler?)" in message, k
            # The refused step changed nothing; the one under way went on as alone.
            assert out["m"] == main_cmd and _state(tracker) == _state(alone), k
            assert _follow(tracker, LATER, 20) == then, k
        else:
            # Landed before the step's guard or after it: one step, then the other.
            assert (out["m"], out["h"], _state(tracker)) in (
                (main_cmd, late_after, _state(after)),
                (main_after, late_before, _state(before)),
            ), k
        assert getattr(tracker, "_callers", []) == [], k
    # Most points are inside the guarded step.
    assert refused > points // 2


class _Blocking:
    """A clearance function that holds the step inside it until told to go on."""

    def __init__(self) -> None:
        self.inside = threading.Event()
        self.go_on = threading.Event()
        self.hold = False

    def __call__(self, x: float, y: float) -> float:
        if self.hold and threading.current_thread() is not threading.main_thread():
            self.inside.set()
            assert self.go_on.wait(60.0)
        return 0.3 + 0.1 * abs(x - y)


def _held_step(tracker: RegulatedPurePursuit, fn: _Blocking, pose: Pose2D) -> dict[str, Any]:
    """``tracker.step(pose)`` in a thread, stopped inside its clearance function."""
    out: dict[str, Any] = {}

    def run() -> None:
        try:
            out["cmd"] = tracker.step(pose, 0.05)
        except RuntimeError as error:
            out["cmd"] = error

    fn.hold = True
    out["thread"] = threading.Thread(target=run)
    out["thread"].start()
    assert fn.inside.wait(60.0)
    return out


def test_another_threads_step_is_refused_while_one_runs() -> None:
    fn = _Blocking()
    tracker = _in_use(lambda: RegulatedPurePursuit(clearance=fn))
    alone = _in_use(lambda: RegulatedPurePursuit(clearance=_clearance))
    main_cmd = alone.step(MAIN, 0.05)
    held = _held_step(tracker, fn, MAIN)
    try:
        with pytest.raises(RuntimeError, match="while another thread was in this "
                           "RegulatedPurePursuit's step"):  # fmt: skip
            tracker.step(LATER, 0.05)
    finally:
        fn.go_on.set()
        held["thread"].join(60.0)
    # The thread's step went on as alone: its command, and the state it left.
    assert held["cmd"] == main_cmd
    assert _state(tracker) == _state(alone) and tracker._callers == []


def test_a_set_path_from_another_thread_while_clearance_runs_is_named_as_such() -> None:
    fn = _Blocking()
    tracker = _in_use(lambda: RegulatedPurePursuit(clearance=fn))
    new = np.array([[4.0, 1.0], [4.0, 6.0]])
    held = _held_step(tracker, fn, MAIN)
    try:
        tracker.set_path(new)  # this (main) thread: not the clearance function
    finally:
        fn.go_on.set()
        held["thread"].join(60.0)
    error = held["cmd"]
    assert isinstance(error, RuntimeError)
    message = str(error)
    # It said "clearance(x, y) called step or set_path of the tracker it serves".
    assert message.startswith(
        "RegulatedPurePursuit.set_path was called while this step's clearance(x, y) ran"
    ), message
    assert "another thread" in message and "the new path is kept" in message
    # True: the new path is kept, untouched by the step.
    reference = RegulatedPurePursuit(clearance=_clearance)
    reference.set_path(new)
    assert tracker.progress == 0.0 and tracker.target_xy is None
    np.testing.assert_array_equal(tracker.path_xy, new)
    fn.hold = False
    assert _follow(tracker, MAIN, 20) == _follow(reference, MAIN, 20)


def _copies(tracker: Any) -> list[Any]:
    return [copy.copy(tracker), copy.deepcopy(tracker), pickle.loads(pickle.dumps(tracker))]


@pytest.mark.parametrize("name", ["FollowTheCarrot", "RegulatedPurePursuit", "OnOffTracker"])
def test_copies_and_pickles_made_during_a_step_are_not_in_use(name: str) -> None:
    base = _in_use(MAKERS[name])
    probe = copy.deepcopy(base)
    points = interleaved(0, lambda: probe.step(MAIN, 0.05), lambda: None)["points"]
    for k in (points // 3, points // 2, 2 * points // 3):
        tracker = copy.deepcopy(base)
        out = interleaved(k, lambda t=tracker: t.step(MAIN, 0.05),  # type: ignore[misc]
                          lambda t=tracker: _copies(t))  # type: ignore[misc]  # fmt: skip
        made = out["h"]
        assert len(made) == 3
        # Not refused (the original's step was under way as they were made), and
        # copies of one moment alike.
        runs = []
        for other in made:
            assert other._callers == [] and other._callers is not tracker._callers
            runs.append(_follow(other, LATER, 20))
        assert runs[0] == runs[1] == runs[2], k
