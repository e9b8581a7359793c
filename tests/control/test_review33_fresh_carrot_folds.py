"""Review 33 (FRESH): ``FollowTheCarrot``'s carrot-on-the-robot search always ends.

Review 32 moved the robot's arc on by ``carrot_distance`` for as long as the
carrot landed exactly on the robot, with no bound: where ``s + carrot_distance``
rounds back to ``s`` (a carrot distance below half an ulp of the arc length,
the robot on the path), the loop never ended and :meth:`step` never returned.
The search is now bounded as RegulatedPurePursuit's is (64 folds a step), and
:attr:`progress` moves with it, so that a path with more folds through the
robot is still followed (the next step goes on from there). Checked: against
``_follow_the_carrot.py`` of HEAD the first test times out (the probe never
prints); the second passes there (the unbounded loop passed all folds at once)
and fails with the bound but without moving :attr:`progress`.
"""

from __future__ import annotations

import math

import pytest

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, integrate
from subprocess_probe import probe_outcome

DT = 0.05

# A fresh process: a step that never returns fails the test instead of hanging the run.
_TINY_CARROT = """
import json, sys
from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D
carrot, x, length, drive = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
tracker = FollowTheCarrot(carrot_distance=carrot, drive=drive)
try:
    tracker.set_path([(0.0, 0.0), (length, 0.0)])
except ValueError as exc:
    print(json.dumps(["ValueError", str(exc).split()[0]]))
    raise SystemExit(0)
cmd = tracker.step(Pose2D(x, 0.0, 0.0), 0.05)
print(json.dumps([cmd.vx, cmd.vy, cmd.omega, tracker.progress]))
"""


@pytest.mark.parametrize(
    ("carrot", "x", "length"),
    [
        (1e-17, 0.5, 1.0),  # 0.5 + 1e-17 == 0.5: the arc never moved
        (1e-16, 1.5, 2.0),  # below half an ulp of 1.5 m
    ],
)
@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_a_carrot_distance_below_the_arcs_ulp_ends_the_step(
    carrot: float, x: float, length: float, drive: str
) -> None:
    # Session 39 (SMALLS): set_path now refuses a carrot distance this short for the
    # path (below 2**-46 of its extent: the robot, steered to its own closest point,
    # never moved); the probe gets that ValueError at once, and no step hangs.
    outcome = probe_outcome(_TINY_CARROT, repr(carrot), repr(x), repr(length), drive, timeout=120)
    assert outcome == ["ValueError", "carrot_distance"]


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_more_folds_through_the_robot_than_one_step_passes_are_followed(drive: str) -> None:
    """100 out-and-backs of half the carrot distance from the robot, then 1 m on.

    Powers of two: every arc length and carrot point is exact, so the carrot
    lands exactly on the robot at each fold.
    """
    carrot = 0.25
    path = [[0.0, 0.0]]
    for _ in range(100):
        path += [[0.5 * carrot, 0.0], [0.0, 0.0]]
    path.append([0.0, 1.0])
    tracker = FollowTheCarrot(drive=drive, carrot_distance=carrot)  # type: ignore[arg-type]
    tracker.set_path(path)
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(2000):
        pose = integrate(pose, tracker.step(pose, DT), DT)
        if tracker.done:
            break
    assert tracker.done
    assert math.hypot(pose.x, pose.y - 1.0) <= tracker.goal_tolerance
