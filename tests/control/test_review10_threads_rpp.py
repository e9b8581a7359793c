"""RegulatedPurePursuit's ``clearance`` function calling back into the tracker.

A ``clearance(x, y)`` that gave the tracker a new path (or stepped it) had the
outer step carry on with the old path and overwrite the state the nested call
left: progress beyond the new path's length, a target off it. The step now
raises ``RuntimeError`` and keeps the new path; a nested step is refused
(``RuntimeError``, review 38) and the outer step changes nothing.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D

LONG = np.array([[0.0, 0.0], [10.0, 0.0]])
SHORT = np.array([[0.0, 1.0], [0.5, 1.0]])


def _tracker(nested: Callable[[RegulatedPurePursuit], object]) -> RegulatedPurePursuit:
    calls = [0]
    tracker: RegulatedPurePursuit

    def clearance(x: float, y: float) -> float:
        calls[0] += 1
        if calls[0] == 2:  # in the second step
            nested(tracker)
        return 10.0

    tracker = RegulatedPurePursuit(clearance=clearance)
    tracker.set_path(LONG)
    return tracker


def test_set_path_from_clearance_raises_and_keeps_the_new_path() -> None:
    tracker = _tracker(lambda t: t.set_path(SHORT))
    tracker.step(Pose2D(1.0, 0.0, 0.0), 0.1)
    with pytest.raises(RuntimeError, match="clearance"):
        tracker.step(Pose2D(2.0, 0.0, 0.0), 0.1)
    np.testing.assert_array_equal(tracker.path_xy, SHORT)
    assert tracker.progress == 0.0
    assert tracker.target_xy is None
    # The next step runs on the new path as after a plain set_path.
    reference = RegulatedPurePursuit(clearance=lambda x, y: 10.0)
    reference.set_path(SHORT)
    pose = Pose2D(2.0, 0.0, 0.0)
    assert tracker.step(pose, 0.1) == reference.step(pose, 0.1)
    assert tracker.progress == reference.progress <= 0.5
    assert tracker.target_xy == reference.target_xy


def test_step_from_clearance_is_refused_and_changes_nothing() -> None:
    # Review 38: a step inside a step is refused by the trackers' one-step guard
    # (before it, the nested step was applied and the outer one raised); the
    # refusal, raised in the function, ends the outer step before it changed anything.
    pose = Pose2D(2.0, 0.0, 0.0)
    tracker = _tracker(lambda t: t.step(pose, 0.1))
    tracker.step(Pose2D(1.0, 0.0, 0.0), 0.1)
    with pytest.raises(RuntimeError, match=r"own step.*clearance\(x, y\) function call step"):
        tracker.step(pose, 0.1)
    reference = RegulatedPurePursuit(clearance=lambda x, y: 10.0)
    reference.set_path(LONG)
    reference.step(Pose2D(1.0, 0.0, 0.0), 0.1)  # the only step applied
    assert (tracker.progress, tracker.target_xy, tracker.phase) == (
        reference.progress, reference.target_xy, reference.phase,
    )  # fmt: skip
    later = Pose2D(2.5, 0.0, 0.0)
    assert tracker.step(later, 0.1) == reference.step(later, 0.1)
