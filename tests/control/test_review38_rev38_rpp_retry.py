"""A Ctrl-C at the end of RegulatedPurePursuit.step: a retried step is the clean step
(review 38, REV38).

Review 25's rule: a ``KeyboardInterrupt`` inside a step leaves the state before
or after the step, so that a loop that catches it and steps again steps once.
``RegulatedPurePursuit`` stored its memory of the step (the last command, an
omnidirectional robot's direction of travel) and then built the returned
``Twist2D``, whose checks are Python calls, where a Ctrl-C lands: the step's
memory was kept with its command lost, and the step tried again limited its
turn from that command instead of the one before (omnidirectional, and
differential with a ``clearance`` callable; review 25's cases, a differential
robot with a clearance grid, happened to be clean).
The command is now built before the stores.
"""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from interrupt_points import delivery_points, interrupted_at
from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

PATH = np.array([[0.0, 0.0], [2.0, 0.5], [3.0, 2.0], [1.0, 3.0]])


def _wall(x: float, y: float) -> float:
    return 0.5 + 0.1 * x


def _tracker(steps: int, **options: Any) -> tuple[RegulatedPurePursuit, Pose2D]:
    tracker = RegulatedPurePursuit(**options)
    tracker.set_path(PATH)
    pose = Pose2D(0.1, -0.1, 0.3)
    for _ in range(steps):
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    return tracker, pose


CASES: dict[str, Callable[[], tuple[RegulatedPurePursuit, Pose2D]]] = {
    "omni": lambda: _tracker(5, drive="omni"),
    "omni-later": lambda: _tracker(60, drive="omni"),
    "diff-clearance-callable": lambda: _tracker(5, clearance=_wall),
    "diff": lambda: _tracker(30),
}


def _state(tracker: RegulatedPurePursuit) -> bytes:
    # The state's fields (a tracker with a clearance callable of a test's does not pickle).
    state = tracker._state
    return pickle.dumps({name: getattr(state, name) for name in state.fields()})


@pytest.mark.parametrize("case", sorted(CASES))
def test_an_interrupted_step_tried_again_is_the_clean_step(case: str) -> None:
    subject, pose = CASES[case]()
    clean = copy.copy(subject)
    clean_out = clean.step(pose, 0.05)
    after = _state(clean)
    points = delivery_points(lambda: copy.copy(subject).step(pose, 0.05))
    assert points > 20
    for k in range(1, points + 1):
        twin = copy.copy(subject)
        if not interrupted_at(k, lambda twin=twin: twin.step(pose, 0.05)):
            continue  # a point of the copy's own (delivery_points ran one)
        assert twin._callers == []  # the one-step guard let go
        out = twin.step(pose, 0.05)  # Ctrl-C caught, the step tried again
        assert (out.vx, out.vy, out.omega) == (clean_out.vx, clean_out.vy, clean_out.omega), k
        assert _state(twin) == after, k
        assert not math.isnan(out.omega)
