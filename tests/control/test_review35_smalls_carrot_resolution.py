"""``FollowTheCarrot`` refuses a carrot distance too short for its path (session 39, SMALLS).

A carrot distance below half an ulp of the robot's arc length (``s + d == s``), or
below the float spacing of the path's coordinates, put the carrot on the robot's
own closest point: every step returned a command of zero (``vx = 0`` and, facing
the path, ``omega = 0``) and a robot on the path never moved, never done. Decided:
``set_path`` refuses such a path with a ``ValueError`` naming ``carrot_distance``
(the carrot must be at least ``2**-46`` of the path's extent, its length or
largest coordinate), and keeps its previous path; every carrot distance it takes
puts the carrot off a robot standing on the path. (The other way, a carrot one
representable step ahead, would move the robot by an ulp a step: no better.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import FollowTheCarrot
from navkit.control._path_following import Polyline
from navkit.geometry import Pose2D, integrate

DT = 0.05


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize(
    ("carrot", "path", "start"),
    [
        (1e-16, [[0.0, 0.0], [10.0, 0.0]], 0.0),  # 1e-16 + s == s from s = 1.8e-15
        (1e-12, [[0.0, 0.0], [1e3, 0.0]], 0.0),
        (1e-10, [[1e8, 0.0], [1e8 + 10.0, 0.0]], 1e8),  # x + 1e-10 == x at 1e8
    ],
)
def test_a_carrot_too_short_for_the_path_is_refused(
    carrot: float, path: list[list[float]], start: float, drive: str
) -> None:
    tracker = FollowTheCarrot(carrot_distance=carrot, drive=drive)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"^carrot_distance .* too short for this path"):
        tracker.set_path(path)
    with pytest.raises(RuntimeError, match="no path"):  # nothing was taken
        tracker.step(Pose2D(start, 0.0, 0.0), DT)


def test_a_refused_path_keeps_the_previous_one() -> None:
    tracker = FollowTheCarrot(carrot_distance=1e-9, drive="omni")
    tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=0.5)
    tracker.step(Pose2D(0.0, 0.0, 0.0), DT)
    progress, target = tracker.progress, tracker.target_xy
    with pytest.raises(ValueError, match="carrot_distance 1e-09 m"):
        tracker.set_path([[0.0, 0.0], [1e6, 0.0]])
    assert (tracker.progress, tracker.target_xy, tracker.goal_yaw) == (progress, target, 0.5)
    assert tracker.phase == "track"


def test_the_bound_is_exactly_2_to_the_minus_46_of_the_extent() -> None:
    for path in ([[0.0, 0.0], [3.0, 4.0]], [[-7e5, 2.0], [-7e5, 12.0]], [[1.0, 1.0]]):
        line = Polyline(np.array(path, dtype=float))
        extent = max(line.length, max(abs(v) for p in path for v in p))
        least = extent * 2.0**-46
        FollowTheCarrot(carrot_distance=least).set_path(path)  # taken
        with pytest.raises(ValueError, match="carrot_distance"):
            FollowTheCarrot(carrot_distance=math.nextafter(least, 0.0)).set_path(path)


def test_the_usual_carrots_are_taken_on_the_largest_paths() -> None:
    # The paper's 0.3 m (and 1 mm) on a path across the whole coordinate range.
    for carrot in (0.3, 1e-3):
        FollowTheCarrot(carrot_distance=carrot).set_path([[-1e9, -1e9], [1e9, 1e9]])


@settings(max_examples=60, deadline=None)
@given(
    x0=st.floats(-9.9e8, 9.9e8),
    y0=st.floats(-9.9e8, 9.9e8),
    heading=st.floats(-math.pi, math.pi),
    length=st.floats(1e-3, 1e4),
    drive=st.sampled_from(["diff", "omni"]),
)
def test_the_shortest_carrot_taken_is_never_the_robots_own_point(
    x0: float, y0: float, heading: float, length: float, drive: str
) -> None:
    end = [x0 + length * math.cos(heading), y0 + length * math.sin(heading)]
    path = [[x0, y0], end]
    line = Polyline(np.array(path))
    extent = max(line.length, float(np.max(np.abs(line.points_xy))))
    least = extent * 2.0**-46
    tracker = FollowTheCarrot(carrot_distance=least, drive=drive)  # type: ignore[arg-type]
    tracker.set_path(path)
    # The robot standing on the path at several arcs, facing along it: the carrot
    # is never where it stands, so the command is never all zero.
    for s in np.linspace(0.0, 0.5 * line.length, 7):
        x, y = line.point_at(float(s))
        cmd = tracker.step(Pose2D(x, y, heading), DT)
        if tracker.phase in ("final", "done"):
            break
        assert tracker.target_xy != (x, y)
        assert (cmd.vx, cmd.vy, cmd.omega) != (0.0, 0.0, 0.0)


def test_a_short_carrot_that_is_taken_drives_the_robot() -> None:
    # 1 µm on a 1 m path: slow (at most 1 µm a step, so as not to pass the carrot),
    # but it moves at every step, which the refused distances never did.
    tracker = FollowTheCarrot(carrot_distance=1e-6, drive="omni")
    tracker.set_path([[0.0, 0.0], [1.0, 0.0]])
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(50):
        moved = integrate(pose, tracker.step(pose, DT), DT)
        assert moved.x > pose.x
        pose = moved
