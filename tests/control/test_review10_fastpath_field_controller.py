"""PotentialFieldController's per-step fast paths give what the general path gives.

Each step the controller moves its attraction to the goal and builds the
obstacles' Khatib repulsion from inputs it has checked already, so it builds
both without the fields' own checks and evaluates them without the public
``force`` check; it returns a zero push without evaluating the repulsion when
no obstacle is within reach; a target given as a tuple of three finite floats
becomes a pose without an array; the stall timer is updated on floats. Every
result must be the general path's to the bit, and every error its error.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, as_pose
from navkit.planning import AttractiveField, BlendedAttraction, ConicAttraction, KhatibRepulsion

_coord = st.floats(-3.0, 3.0)
# Offsets of obstacles from the robot, with the edge cases of the reach test:
# exactly the influence radius (hypot(r, 0) == r), on the robot, a subnormal away.
_offset = st.one_of(st.floats(-2.0, 2.0), st.sampled_from([0.0, -0.0, 5e-324, 1e-12, 0.6, -0.6]))
_bad = st.sampled_from([math.nan, math.inf, -math.inf])


class _OwnWithGoal(BlendedAttraction):
    """Overrides with_goal (as a user's subclass may), which takes the general path."""

    def with_goal(self, goal_xy: Any) -> _OwnWithGoal:
        return super().with_goal(goal_xy)


class _ShiftedGoal(BlendedAttraction):
    """Overrides with_goal to do more: the controller must call it."""

    def with_goal(self, goal_xy: Any) -> _ShiftedGoal:
        return super().with_goal(np.asarray(goal_xy) + np.array([0.25, -0.125]))


class _OwnForce(ConicAttraction):
    """Overrides force: the controller must call it (a quarter of the pull, below max_speed)."""

    def force(self, points_xy: Any) -> np.ndarray:
        out: np.ndarray = 0.25 * super().force(points_xy)
        return out


def _general_desired(
    ctl: PotentialFieldController, pose: Pose2D, goal: np.ndarray, obstacles: Any
) -> np.ndarray:
    """Steps 1-3 through the public field API only: what the fast path must give."""
    here = np.array([[pose.x, pose.y]])
    f_att = ctl.attraction.with_goal(goal).force(here)[0]
    norm = float(np.hypot(f_att[0], f_att[1]))
    if norm > ctl.max_speed:
        f_att = f_att * (ctl.max_speed / norm)
    rep = np.zeros(2)
    if obstacles is not None:
        pts = np.asarray(obstacles, dtype=np.float64).reshape(-1, 2)
        valid = pts[np.all(np.isfinite(pts), axis=1)]
        field = KhatibRepulsion(valid, k_rep=ctl.k_rep, influence_radius=ctl.influence_radius)
        rep = field.force(here)[0]
    v: np.ndarray = f_att + rep
    if not np.all(np.isfinite(v)):
        v = np.where(np.isinf(v), np.sign(v), 0.0)
    speed = float(np.hypot(v[0], v[1]))
    if speed > ctl.max_speed:
        v = v * (ctl.max_speed / speed)
    return v


def _same(a: np.ndarray, b: np.ndarray) -> None:
    assert a.dtype == b.dtype == np.float64 and a.shape == b.shape == (2,)
    assert a.tobytes() == b.tobytes(), (a, b)  # bit for bit, signs of zeros included


@settings(max_examples=25, deadline=None)
@given(
    x=_coord,
    y=_coord,
    theta=st.floats(-4.0, 4.0),
    goal=st.tuples(_coord, _coord),
    offsets=st.lists(st.tuples(_offset, _offset), max_size=5),
    bad_rows=st.lists(st.tuples(_bad, _coord), max_size=2),
    k_rep=st.floats(1e-3, 10.0),
    radius=st.sampled_from([0.6, 1.5, 0.05]),
    kind=st.sampled_from([BlendedAttraction, ConicAttraction, _ShiftedGoal, _OwnForce]),
)
def test_desired_velocity_matches_the_public_field_api(
    x: float, y: float, theta: float, goal: tuple[float, float],
    offsets: list[tuple[float, float]], bad_rows: list[tuple[float, float]],
    k_rep: float, radius: float, kind: type[AttractiveField],
) -> None:  # fmt: skip
    ctl = PotentialFieldController(kind(np.zeros(2)), k_rep=k_rep, influence_radius=radius)
    pose = Pose2D(x, y, theta)
    obstacles = [(x + dx, y + dy) for dx, dy in offsets] + bad_rows
    goal_xy = np.array(goal)
    for obs in (obstacles, np.array(obstacles).reshape(-1, 2), None):
        want = _general_desired(ctl, pose, goal_xy, obs)
        _same(ctl.desired_velocity(pose, goal, obstacles=obs), want)


test_desired_velocity_matches_the_public_field_api_thoroughly = slow_twin(
    test_desired_velocity_matches_the_public_field_api, max_examples=60
)


def test_an_obstacle_exactly_at_the_reach_and_one_beyond() -> None:
    ctl = PotentialFieldController(k_rep=1.0, influence_radius=0.6)
    pose = Pose2D(0.25, -0.5, 0.0)
    for obs in ([[0.85, -0.5]], [[0.25, 0.1]], [[0.85 + 1e-12, -0.5]], [[0.25, -0.5]]):
        want = _general_desired(ctl, pose, np.array([2.0, 0.0]), obs)
        _same(ctl.desired_velocity(pose, (2.0, 0.0), obstacles=obs), want)


@settings(max_examples=40, deadline=None)
@given(
    steps=st.lists(
        st.tuples(st.sampled_from([0.0, 0.0, 0.01, 0.05, 0.2]), st.floats(-4.0, 4.0),
                  st.sampled_from([0.02, 0.5])),
        min_size=1, max_size=12,
    ),
    goal=st.tuples(_coord, _coord, st.floats(-4.0, 4.0)),
    drive=st.sampled_from(["omni", "diff"]),
)  # fmt: skip
# A robot exactly 0.05 m along x from a goal 2.2e-16 m off the axis: beyond the tolerance
# (by 5e-31 m), though np.hypot rounds the offset to 0.05 (thorough profile, seed 777).
@example(steps=[(0.05, 0.0, 0.02), (0.0, 0.0, 0.02)], goal=(0.0, 2.220446049250313e-16, 0.0),
         drive="omni")  # fmt: skip
def test_steps_as_tuple_pose_list_and_with_own_with_goal_agree(
    steps: list[tuple[float, float, float]],
    goal: tuple[float, float, float],
    drive: Any,
) -> None:
    options: dict[str, Any] = {"drive": drive, "stall_timeout": 0.05, "goal_tolerance": 0.05}
    fast = PotentialFieldController(**options)
    general = PotentialFieldController(_OwnWithGoal(np.zeros(2)), **options)
    x = y = 0.0
    obstacles = np.array([[0.3, 0.2], [5.0, 5.0]])
    anchor: np.ndarray | None = None
    still = 0.0
    for move, theta, dt in steps:
        x += move
        pose = Pose2D(x, y, theta)
        a = fast.step(pose, goal, dt=dt, obstacles=obstacles)
        b = general.step(pose, Pose2D(*goal), dt=dt, obstacles=obstacles)
        assert (a.vx, a.vy, a.omega) == (b.vx, b.vy, b.omega)
        _same(fast.previous_velocity, general.previous_velocity)
        # The stall timer against its definition on arrays.
        here = np.array([x, y])
        # Within goal_tolerance as `done` documents it: the offset goal - robot as
        # floats, its length exact at the boundary (squares in rationals), where
        # hypot rounds (0.05 beside a goal 2.2e-16 m off the x axis: 0.05 rounded,
        # but beyond it, so not arrived).
        dx, dy = Fraction(goal[0] - x), Fraction(goal[1] - y)
        if dx * dx + dy * dy <= Fraction(0.05) ** 2:
            anchor, still = None, 0.0
        elif anchor is None or float(np.hypot(*(here - anchor))) > 0.05:
            anchor, still = here, 0.0
        else:
            still += dt
        assert fast.stall_time == general.stall_time == still
        assert fast.stalled == (still >= 0.05 * (1.0 - 1e-9))  # the stall clock's slack


@pytest.mark.parametrize(
    "target",
    [
        (math.nan, 0.0, 0.0),
        (0.0, math.inf, 0.0),
        (0.0, 0.0, -math.inf),
        (True, 0.0, 0.0),
        (1, 2, 3),
        (np.float64(1.0), 0.0, 0.0),
        (1.0, 2.0),
        (1.0, 2.0, 3.0, 4.0),
        ("a", 0.0, 0.0),
        (0.0, 2e9, 0.0),
        (-0.0, -0.0, math.pi),
        (0.0, 0.0, -math.pi),
        (1.0, 2.0, 7.0),
    ],
)
def test_tuple_targets_behave_as_the_general_conversion(target: tuple[Any, ...]) -> None:
    try:
        expected: Any = as_pose(target, "target_pose")
    except (TypeError, ValueError) as exc:
        expected = exc
    ctl = PotentialFieldController()
    if isinstance(expected, Exception):
        with pytest.raises(type(expected)) as info:
            ctl.step((0.0, 0.0, 0.0), target, dt=0.1)
        assert str(info.value) == str(expected)
        assert ctl.previous_velocity.tolist() == [0.0, 0.0]  # state unchanged
        return
    if not (abs(expected.x) <= 1e9 and abs(expected.y) <= 1e9):
        with pytest.raises(ValueError, match="target_pose"):
            ctl.step((0.0, 0.0, 0.0), target, dt=0.1)
        return
    other = PotentialFieldController()
    a = ctl.step((0.0, 0.0, 0.0), target, dt=0.1)
    b = other.step((0.0, 0.0, 0.0), expected, dt=0.1)
    assert (a.vx, a.vy, a.omega) == (b.vx, b.vy, b.omega)


@pytest.mark.parametrize(
    ("obstacles", "message"),
    [
        ([[0.0, 2e9]], r"obstacles: positions must have \|x\|, \|y\| <= 1e\+09 m"),
        ([[math.nan, 0.0], [-2e9, 0.0]], r"obstacles: positions must have"),
        ([[1.0, 2.0, 3.0]], r"obstacles must have shape"),
    ],
)
def test_obstacle_errors_are_unchanged(obstacles: Any, message: str) -> None:
    ctl = PotentialFieldController()
    with pytest.raises(ValueError, match=message):
        ctl.step((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), dt=0.1, obstacles=obstacles)
    assert ctl.previous_velocity.tolist() == [0.0, 0.0]


def test_private_constructors_build_what_the_public_ones_build() -> None:
    goal = np.array([1.0, -2.0])
    field = BlendedAttraction(np.zeros(2), width=0.3, m=0.7)
    fast = field._with_checked_goal(goal)
    slow = field.with_goal(goal)
    assert type(fast) is type(slow) and repr(fast) == repr(slow)
    assert not fast.goal_xy.flags.writeable and not np.shares_memory(fast.goal_xy, goal)
    goal[0] = 5.0  # the caller's array stays the caller's
    assert fast.goal_xy.tolist() == [1.0, -2.0]

    pts = np.array([[0.5, 0.5], [1.0, -1.0]])
    fast_rep = KhatibRepulsion._checked(pts, 0.3, 0.8)
    slow_rep = KhatibRepulsion(pts, k_rep=0.3, influence_radius=0.8)
    assert repr(fast_rep) == repr(slow_rep)
    assert fast_rep.obstacles_xy.tobytes() == slow_rep.obstacles_xy.tobytes()
    assert not fast_rep.obstacles_xy.flags.writeable
    assert not np.shares_memory(fast_rep.obstacles_xy, pts)
    grid = np.array([[0.0, 0.0], [0.7, 0.6], [3.0, 3.0]])
    assert fast_rep.force(grid).tobytes() == slow_rep.force(grid).tobytes()
