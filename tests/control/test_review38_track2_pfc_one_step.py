"""``PotentialFieldController``: one ``step`` at a time, and a ``reset`` in a step wins
(review 38, TRACK2).

A step computes every new value first and stores them at its end (review 25),
so an interrupted step leaves the state before or after it. But two steps at
once (a signal handler's step inside the main loop's, two threads) both
started from the state before either, and the later stores won: the other
step was lost — its time from the stall clock, its command from the base of
the velocity limits — while its command had been returned (18 of the 214
interleavings of one step below). A ``reset`` landing in a step (a new-goal
callback in another thread) was overwritten by the step's stores the same
way: the next step did not start from rest. A step called during another now
raises ``RuntimeError`` and changes nothing; a reset during a step wins (that
step's command is for the state before; the next starts from rest).

The first two tests fail on the code before (checked).
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import pytest

from interrupt_points import interleaved
from navkit.control import PotentialFieldController
from navkit.geometry import Twist2D

TARGET = (2.0, 1.0, 0.0)
MAIN = ((0.1, 0.0, 0.1), TARGET, 0.05)
OTHER = ((0.12, 0.01, 0.12), TARGET, 0.05)
OBSTACLES = [[0.6, 0.4], [1.0, 1.2]]


def _state(ctl: PotentialFieldController) -> tuple[Any, ...]:
    anchor = ctl._anchor
    return (ctl._velocity.tobytes(), ctl._integral, ctl._last_error,
            None if anchor is None else anchor.tobytes(), ctl._still_for)  # fmt: skip


def _in_use(drive: str) -> PotentialFieldController:
    ctl = PotentialFieldController(drive=drive, ki=0.5)
    for i in range(10):
        ctl.step((0.01 * i, 0.0, 0.0), TARGET, 0.05, obstacles=OBSTACLES)
    return ctl


def _step(ctl: PotentialFieldController, args: tuple[Any, ...]) -> Twist2D:
    return ctl.step(*args, obstacles=OBSTACLES)


def _follow(ctl: PotentialFieldController) -> list[Twist2D]:
    return [_step(ctl, OTHER) for _ in range(5)]


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_a_step_inside_a_step_is_refused_and_the_step_under_way_goes_on(drive: str) -> None:
    base = _in_use(drive)
    alone = copy.deepcopy(base)
    main_cmd = _step(alone, MAIN)
    then = _follow(copy.deepcopy(alone))
    main_other = copy.deepcopy(alone)
    other_after = _step(main_other, OTHER)
    other_main = copy.deepcopy(base)
    other_before = _step(other_main, OTHER)
    main_after = _step(other_main, MAIN)
    probe = copy.deepcopy(base)
    points = interleaved(0, lambda: _step(probe, MAIN), lambda: None)["points"]
    refused = 0
    for k in range(1, points + 1):
        ctl = copy.deepcopy(base)
        out = interleaved(k, lambda c=ctl: _step(c, MAIN),  # type: ignore[misc]
                          lambda c=ctl: _step(c, OTHER))  # type: ignore[misc]  # fmt: skip
        if isinstance(out["h"], RuntimeError):
            refused += 1
            assert "own step, in the same thread (from a signal handler?)" in str(out["h"])
            assert out["m"] == main_cmd and _state(ctl) == _state(alone), k
            assert _follow(ctl) == then, k
        else:
            # Before the step's guard or after its stores: one step, then the other.
            assert (out["m"], out["h"], _state(ctl)) in (
                (main_cmd, other_after, _state(main_other)),
                (main_after, other_before, _state(other_main)),
            ), k
        assert getattr(ctl, "_callers", []) == [], k
    assert refused > points // 2


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_a_reset_inside_a_step_wins(drive: str) -> None:
    base = _in_use(drive)
    main_cmd = _step(copy.deepcopy(base), MAIN)
    fresh = copy.deepcopy(base)
    fresh.reset()
    after_reset = _follow(copy.deepcopy(fresh))
    probe = copy.deepcopy(base)
    points = interleaved(0, lambda: _step(probe, MAIN), lambda: None)["points"]
    for k in range(1, points + 1):
        ctl = copy.deepcopy(base)
        out = interleaved(k, lambda c=ctl: _step(c, MAIN),  # type: ignore[misc]
                          lambda c=ctl: c.reset())  # type: ignore[misc]  # fmt: skip
        assert "h" in out and out["h"] is None, k
        # The step's command: for the state before the reset, or (the reset first,
        # where it landed before the step read the state) from rest.
        assert out["m"] in (main_cmd, _step(copy.deepcopy(fresh), MAIN)), k
        if out["m"] == main_cmd:
            # The reset is not overwritten: the next steps start from rest.
            assert _state(ctl) == _state(fresh), k
            assert _follow(ctl) == after_reset, k


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_a_step_inside_a_reset_is_reset(drive: str) -> None:
    base = _in_use(drive)
    fresh = copy.deepcopy(base)
    fresh.reset()
    probe = copy.deepcopy(base)
    points = interleaved(0, probe.reset, lambda: None)["points"]
    assert points > 0
    for k in range(1, points + 1):
        ctl = copy.deepcopy(base)
        out = interleaved(k, ctl.reset, lambda c=ctl: _step(c, MAIN))  # type: ignore[misc]
        assert isinstance(out["h"], Twist2D), k
        assert _state(ctl) == _state(fresh), k


def test_copies_and_pickles_are_not_in_use_and_pickle_as_before() -> None:
    ctl = _in_use("diff")
    made: list[Any] = []
    probe = copy.deepcopy(ctl)
    points = interleaved(0, lambda: _step(probe, MAIN), lambda: None)["points"]
    interleaved(points // 2, lambda: _step(ctl, MAIN),
                lambda: made.extend([copy.copy(ctl), pickle.loads(pickle.dumps(ctl))]))  # fmt: skip
    assert len(made) == 2
    for other in made:
        assert other._callers == [] and other._callers is not ctl._callers
        assert isinstance(_step(other, OTHER), Twist2D)
    instance, slots = ctl.__getstate__()  # type: ignore[misc]
    assert "_callers" not in slots
    # A pickle's state without the list (an older release's) loads, not in use.
    twin = PotentialFieldController.__new__(PotentialFieldController)
    twin.__setstate__((instance, slots))
    assert twin._callers == [] and _follow(twin) == _follow(copy.deepcopy(ctl))
