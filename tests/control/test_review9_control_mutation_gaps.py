"""Behaviour the controllers' docstrings promise that no earlier test pinned down.

Found by mutation testing (session 13): each test here fails on a one-line
change of the source that every other test let pass (a boundary rule, a term
of a formula). Expected values are computed from the docstrings' formulas.
"""

from __future__ import annotations

import math

import pytest

from navkit.control import RegulatedPurePursuit
from navkit.control._path_following import pursuit_curvature

STRAIGHT = [[0.0, 0.0], [5.0, 0.0]]


# ------------------------------------------------------------ Regulated Pure Pursuit
@pytest.mark.parametrize("velocity", [(0.3, 0.4, 0.0), (0.0, 0.4, 0.0), (-0.2, -0.1, 0.0)])
def test_rpp_omni_lookahead_uses_the_measured_planar_speed(
    velocity: tuple[float, float, float],
) -> None:
    # L = |v| × lookahead_time, |v| the robot's speed: for an omnidirectional robot
    # that includes its sideways motion. On a straight path through the robot the
    # lookahead point lies L ahead of it.
    tracker = RegulatedPurePursuit(drive="omni", lookahead_time=1.5)
    tracker.set_path(STRAIGHT)
    tracker.step((0.0, 0.0, 0.0), 0.05, velocity=velocity)
    speed = math.hypot(velocity[0], velocity[1])
    expected = min(max(speed * 1.5, 0.3), 0.9)
    assert tracker.target_xy is not None
    assert tracker.target_xy[0] == pytest.approx(expected, abs=1e-12)
    assert tracker.target_xy[1] == 0.0


@pytest.mark.parametrize("threshold", [math.pi / 2, math.pi / 4])
def test_rpp_rotates_only_when_strictly_beyond_the_rotate_angle(threshold: float) -> None:
    # "more than rotate_angle off the robot's heading": a lookahead point
    # exactly at that angle is tracked on its arc, a hair beyond it is turned to.
    path = [[0.0, 0.0], [0.0, 5.0]]  # the lookahead point lies straight up, at +π/2
    at = RegulatedPurePursuit(rotate_angle=threshold)
    at.set_path(path)
    cmd = at.step((0.0, 0.0, math.pi / 2 - threshold), 0.05)
    assert at.phase == "track"
    assert cmd.vx > 0.0
    beyond = RegulatedPurePursuit(rotate_angle=threshold)
    beyond.set_path(path)
    cmd = beyond.step((0.0, 0.0, math.pi / 2 - threshold - 1e-9), 0.05)
    assert beyond.phase == "rotate"
    assert cmd.vx == 0.0
    assert cmd.omega > 0.0


@pytest.mark.parametrize("gain", [0.5, 0.25])
def test_rpp_cost_regulation_starts_strictly_below_clearance_distance(gain: float) -> None:
    # The speed is scaled by gain × c / clearance_distance only while c < clearance_distance;
    # at c = clearance_distance the robot drives at max_speed whatever the gain.
    def make(c: float) -> RegulatedPurePursuit:
        tracker = RegulatedPurePursuit(
            clearance=lambda x, y: c, clearance_distance=0.6, clearance_gain=gain,
            curvature_regulation=False, min_regulated_speed=0.0,
        )
        tracker.set_path(STRAIGHT)
        return tracker

    assert make(0.6).step((0.0, 0.0, 0.0), 0.05).vx == 0.5
    slow = make(0.3).step((0.0, 0.0, 0.0), 0.05).vx
    assert slow == pytest.approx(min(0.5, 0.5 * gain * 0.3 / 0.6), rel=1e-12)


def test_rpp_speed_is_the_lower_of_curvature_and_cost_regulation() -> None:
    # Both regulations active: v = max(min(v_curv, v_cost), min_regulated_speed),
    # v_curv = max_speed × r / slowdown_radius, v_cost = max_speed × gain × c / clearance_distance.
    tracker = RegulatedPurePursuit(
        clearance=lambda x, y: 0.3, min_regulated_speed=0.0, min_lookahead=0.3,
        max_lookahead=0.3,
    )
    tracker.set_path([[0.0, 0.0], [0.0, 5.0]])
    heading = math.pi / 3  # the lookahead point (0, 0.3) lies 30° to the left
    cmd = tracker.step((0.0, 0.0, heading), 0.05)
    x, y = 0.3 * math.cos(math.pi / 2 - heading), 0.3 * math.sin(math.pi / 2 - heading)
    radius = (x * x + y * y) / (2.0 * y)
    v_curv = 0.5 * radius / 0.9
    v_cost = 0.5 * 1.0 * 0.3 / 0.6
    assert v_curv < v_cost
    assert cmd.vx == pytest.approx(min(v_curv, v_cost), rel=1e-9)
    assert cmd.omega == pytest.approx(cmd.vx / radius, rel=1e-9)


def test_rpp_approach_scaling_counts_the_path_left_from_the_robot() -> None:
    # "when less than approach_distance of path is left": path left from the
    # robot's closest point, not from the lookahead point. Here 1.3 m of path are
    # left (>= 0.6) though the goal is 0.3 m away and the lookahead point 0.4 m
    # before it: no approach scaling, full speed toward the lookahead point.
    path = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.3], [0.5, 0.3]]
    tracker = RegulatedPurePursuit(min_lookahead=0.9, max_lookahead=0.9)
    tracker.set_path(path)
    # The lookahead point is 0.9 m of path ahead (the rest of the path lies in the
    # circle): (0.9, 0.3). Face it, so the arc is straight.
    heading = math.atan2(0.3, 0.4)
    cmd = tracker.step((0.5, 0.0, heading), 0.05)
    assert tracker.progress == pytest.approx(0.5)
    assert tracker.target_xy == pytest.approx((0.9, 0.3))
    assert cmd.vx == pytest.approx(0.5, rel=1e-9)
    # Once less than 0.6 m of path is left, the speed is scaled by distance / 0.6.
    near = RegulatedPurePursuit(min_lookahead=0.9, max_lookahead=0.9)
    near.set_path([[0.0, 0.0], [1.0, 0.0]])
    cmd = near.step((0.55, 0.0, 0.0), 0.05)
    assert cmd.vx == pytest.approx(0.5 * 0.45 / 0.6, rel=1e-9)


def test_rpp_approach_scaling_uses_the_straight_distance_to_the_goal() -> None:
    # The approach factor is (distance to the goal) / approach_distance: the
    # straight distance, not the 0.4 m of path left round the corner.
    tracker = RegulatedPurePursuit()
    tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 0.3]])
    lateral = math.sqrt(0.3**2 - 0.1**2)  # the lookahead circle (L = 0.3) meets x = 1 there
    cmd = tracker.step((0.9, 0.0, math.atan2(lateral, 0.1)), 0.05)
    assert tracker.target_xy == pytest.approx((1.0, lateral))
    assert cmd.vx == pytest.approx(0.5 * math.hypot(0.1, 0.3) / 0.6, rel=1e-9)


def test_rpp_never_passes_the_lookahead_point_within_one_step() -> None:
    # "v <= distance / dt to the lookahead point": binds at a low control rate.
    tracker = RegulatedPurePursuit()
    tracker.set_path(STRAIGHT)
    cmd = tracker.step((0.0, 0.0, 0.0), 2.0)
    assert tracker.target_xy == pytest.approx((0.3, 0.0))
    assert cmd.vx == pytest.approx(0.3 / 2.0, rel=1e-12)


def test_rpp_lookahead_point_is_lookahead_further_when_the_rest_fits_in_the_circle() -> None:
    # "when the whole rest of the path is nearer, the point L further along the
    # path": a path folding back inside the circle (all of it within 0.37 m of the
    # robot, L = 0.5) is followed in order, not cut to its end.
    path = [[0.0, 0.0], [0.3, 0.0], [0.3, 0.1], [0.0, 0.1], [0.0, 0.2], [0.3, 0.2]]
    tracker = RegulatedPurePursuit(min_lookahead=0.5, max_lookahead=0.5)
    tracker.set_path(path)
    tracker.step((0.0, 0.0, 0.0), 0.05)
    # 0.5 m along: 0.3 + 0.1 + 0.1 m, on the third segment.
    assert tracker.target_xy == pytest.approx((0.2, 0.1), abs=1e-12)


def test_pursuit_curvature_is_zero_up_to_and_including_the_threshold() -> None:
    # 0 when x² + y² <= 0.001 (Nav2), 2 y / (x² + y²) beyond.
    x, y = 0.01, 0.03
    assert x * x + y * y == 1e-3
    assert pursuit_curvature(x, y) == 0.0
    assert pursuit_curvature(x, 0.031) == pytest.approx(2.0 * 0.031 / (x * x + 0.031**2))


def test_rpp_in_place_turn_never_passes_the_target_heading_within_one_step() -> None:
    # "|ω| <= |angle| / dt in place": at 1 Hz a quarter turn is commanded at π/2 rad/s,
    # below rotate_omega (1.8) and the braking bound sqrt(2 a |angle|) (3.17).
    tracker = RegulatedPurePursuit()
    tracker.set_path([[0.0, 0.0], [0.0, 5.0]])
    cmd = tracker.step((0.0, 0.0, 0.0), 1.0, velocity=(0.0, 0.0, 1.8))
    assert tracker.phase == "rotate"
    assert cmd.omega == pytest.approx(math.pi / 2, rel=1e-12)
