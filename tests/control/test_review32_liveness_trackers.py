"""Review 32 (LIVENESS): a path tracker driven in a closed loop always finishes.

A robot's loop calls ``step`` until ``done``; the silent failure is a command
that stays useless (zero, or an endless oscillation round the goal) while
``done`` stays False, as ``FollowTheCarrot`` did on a path doubling back through
the robot (commit 94aa269). Each case here drives the three trackers, both
drives, with and without a goal yaw, with :func:`navkit.geometry.integrate` on
adversarial but valid paths and poses (doubling back, repeated points, one
point, a start far off or behind, headings at ±π, goal tolerances far below a
step's travel, scales from 1 mm to 10 km, large ``dt``) for a generous budget
of steps (four times what the path's length at the slowest commanded speed and
half a turn in place per 1.3-fold cut of the distance to the goal need), and asserts
the tracker is done at its goal.

Not covered: ``RegulatedPurePursuit(rotate_to_heading=False)``, documented to
drive away from a lookahead point behind the robot for ever (as Nav2 does).
"""

from __future__ import annotations

import math
from itertools import pairwise
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

SCALES = (1e-3, 1.0, 1e3, 1e4)


def _tracker(kind: str, drive: str, scale: float, slow: float, tight: bool) -> Any:
    """A tracker with every length scaled by ``scale`` and its speeds by ``slow``."""

    def speed(v: float) -> float:
        return min(100.0, v * scale * slow)

    if kind == "carrot":
        return FollowTheCarrot(
            drive=drive,  # type: ignore[arg-type]
            carrot_distance=0.3 * scale,
            max_speed=speed(0.18),
            goal_tolerance=(1e-9 if tight else 0.05) * scale,
        )
    if kind == "onoff":
        return OnOffTracker(
            drive=drive,  # type: ignore[arg-type]
            max_speed=speed(0.2),
            goal_tolerance=(1e-9 if tight else 0.05) * scale,
        )
    return RegulatedPurePursuit(
        drive=drive,  # type: ignore[arg-type]
        max_speed=speed(0.5),
        min_lookahead=0.3 * scale,
        max_lookahead=0.9 * scale,
        slowdown_radius=0.9 * scale,
        min_regulated_speed=speed(0.25),
        approach_distance=0.6 * scale,
        min_approach_speed=speed(0.05),
        goal_tolerance=(1e-9 if tight else 0.25) * scale,
    )


def _slowest(tracker: Any) -> float:
    """The slowest speed (m/s) the tracker commands while it drives."""
    v = float(tracker.max_speed)
    for name in ("_min_regulated_speed", "_min_approach_speed"):
        v = min(v, float(getattr(tracker, name, v)))
    return v


def _drive_to_done(
    tracker: Any,
    path: list[list[float]],
    pose: Pose2D,
    dt: float,
    goal_yaw: float | None,
    measured: bool,
) -> tuple[Pose2D, int, int]:
    """Step ``tracker`` along ``path`` from ``pose`` until done: (pose, steps, budget)."""
    tracker.set_path(path, goal_yaw=goal_yaw)
    length = sum(math.dist(p, q) for p, q in pairwise(path))
    length += math.dist(path[0], (pose.x, pose.y))
    # A goal tolerance far below a step's travel is reached in cycles of a turn in
    # place then a straight run (a turn-or-drive tracker near its target): each cuts
    # the distance left by a factor of at least 1 / (2 sin(rotate_angle / 2)) (1.3
    # for RegulatedPurePursuit's 45 degrees), so log(distance / tolerance) of them.
    cycles = 3.0 + math.log(max(length, tracker.goal_tolerance) / tracker.goal_tolerance) / 0.26
    omega = min(getattr(tracker, "max_omega", None) or 0.5, 0.5)
    turn_time = cycles * math.pi / omega
    budget = int(4.0 * (length / _slowest(tracker) + turn_time) / dt) + 200
    last = None
    for k in range(budget):
        if measured and isinstance(tracker, RegulatedPurePursuit):
            cmd = tracker.step(pose, dt, velocity=last)
        else:
            cmd = tracker.step(pose, dt)
        if tracker.done:
            return pose, k, budget
        last = cmd
        pose = integrate(pose, cmd, dt)
    return pose, budget, budget


def _check(
    tracker: Any,
    path: list[list[float]],
    pose: Pose2D,
    dt: float,
    goal_yaw: float | None,
    measured: bool = False,
) -> None:
    end, _, budget = _drive_to_done(tracker, path, pose, dt, goal_yaw, measured)
    assert tracker.done, (
        f"not done after {budget} steps: phase {tracker.phase}, pose {end}, "
        f"target {tracker.target_xy}, progress {tracker.progress}"
    )
    gx, gy = path[-1]
    assert math.hypot(end.x - gx, end.y - gy) <= tracker.goal_tolerance
    if goal_yaw is not None:
        err = math.remainder(goal_yaw - end.theta, 2.0 * math.pi)
        assert abs(err) <= tracker.yaw_tolerance


# ------------------------------------------------------------- hand-made cases
KINDS = ("carrot", "onoff", "rpp")
DRIVES = ("diff", "omni")

WORST_PATHS = {
    "one point": [[0.4, 0.3]],
    "repeated points": [[0.0, 0.0], [0.0, 0.0], [0.5, 0.0], [0.5, 0.0], [0.5, 0.5]],
    "out and back": [[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]],
    "out and back inside the lookahead": [[0.0, 0.0], [-0.2, 0.0], [0.0, 0.0]],
    "back through the start": [[0.0, 0.0], [0.15, 0.0], [0.0, 0.0], [0.0, 1.0]],
    "there and back twice": [[0.0, 0.0], [0.6, 0.0], [0.0, 0.0], [0.6, 0.0]],
    "self-crossing": [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]],
    "goal on the start": [[0.0, 0.0], [0.5, 0.5], [1.0, 0.0], [0.0, 0.0]],
    "zig-zag of 5 cm": [[0.05 * i, 0.05 * (i % 2)] for i in range(8)],
}


@pytest.mark.parametrize("path_name", sorted(WORST_PATHS))
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("drive", DRIVES)
@pytest.mark.parametrize("tight", [False, True], ids=["tolerance", "tolerance 1e-9"])
def test_worst_case_paths_finish(path_name: str, kind: str, drive: str, tight: bool) -> None:
    """Every tracker reaches the end of each hand-made path, facing away at π at the start."""
    tracker = _tracker(kind, drive, 1.0, 1.0, tight)
    _check(tracker, WORST_PATHS[path_name], Pose2D(0.0, 0.0, math.pi), 0.05, -math.pi)


@pytest.mark.parametrize("path_name", sorted(WORST_PATHS))
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("drive", DRIVES)
@pytest.mark.parametrize("scale", [1e-3, 1e3])
def test_worst_case_paths_finish_at_scale(
    path_name: str, kind: str, drive: str, scale: float
) -> None:
    """The same paths 1000 times smaller or larger, speeds scaled at a fifth of that.

    At 1 km the short out-and-back path (200 m and back, inside
    RegulatedPurePursuit's 300 m lookahead) stopped RegulatedPurePursuit for ever
    where the robot met its lookahead point; at 1 m rounding let it escape
    (tests/control/test_review32_liveness_rpp_fold.py).
    """
    tracker = _tracker(kind, drive, scale, 0.2, False)
    path = [[scale * x, scale * y] for x, y in WORST_PATHS[path_name]]
    _check(tracker, path, Pose2D(0.0, 0.0, math.pi), 0.05, None)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("drive", DRIVES)
@pytest.mark.parametrize("dt", [1e-3, 2.0])
def test_a_goal_tolerance_below_a_steps_travel_ends_without_oscillation(
    kind: str, drive: str, dt: float
) -> None:
    """At 10 m/s a step of 2 s travels 20 m, 2e10 goal tolerances: no orbit round the goal."""
    tracker = _tracker(kind, drive, 1.0, 20.0, True)
    _check(tracker, [[0.0, 0.0], [3.0, 0.0], [3.0, 3.0]], Pose2D(-1.0, 0.5, 3.0), dt, 1.0)


# ------------------------------------------------------------ random cases
@st.composite
def _cases(draw: st.DrawFn) -> tuple[Any, list[list[float]], Pose2D, float, float | None, bool]:
    kind = draw(st.sampled_from(KINDS))
    drive = draw(st.sampled_from(DRIVES))
    scale = draw(st.sampled_from(SCALES))
    slow = draw(st.sampled_from([1.0, 0.1, 10.0]))
    tight = draw(st.booleans())
    # Points on a 5 cm lattice (scaled) so that repeats, doubling back and
    # zero-length segments are common.
    coord = st.integers(-10, 10).map(lambda i: 0.05 * i * scale)
    base = draw(st.lists(st.tuples(coord, coord), min_size=1, max_size=5))
    pts = [list(p) for p in base for _ in range(draw(st.integers(1, 2)))]
    if draw(st.booleans()):
        pts += [list(p) for p in reversed(base[:-1])]  # back the way it came
    start = draw(st.sampled_from(["on", "off", "far"]))
    x0, y0 = pts[0]
    if start == "off":
        x0 += draw(st.floats(-0.3, 0.3)) * scale
        y0 += draw(st.floats(-0.3, 0.3)) * scale
    elif start == "far":
        x0 += 3.0 * scale
    theta = draw(st.sampled_from([math.pi, -math.pi + 1e-15, 0.0, 2.0]))
    goal_yaw = draw(st.sampled_from([None, math.pi, -math.pi, 0.5]))
    dt = draw(st.sampled_from([0.05, 0.5]))
    measured = draw(st.booleans())
    tracker = _tracker(kind, drive, scale, slow, tight)
    return tracker, pts, Pose2D(x0, y0, theta), dt, goal_yaw, measured


@settings(max_examples=60, deadline=None)
@given(_cases())
def test_random_adversarial_paths_finish(
    case: tuple[Any, list[list[float]], Pose2D, float, float | None, bool],
) -> None:
    tracker, path, pose, dt, goal_yaw, measured = case
    _check(tracker, path, pose, dt, goal_yaw, measured)
