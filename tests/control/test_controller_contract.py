"""Issue 12 in navkit.control: documented ranges, types, overflow as ValueError, never NaN."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import PotentialFieldController, limit_velocity_change
from navkit.geometry import Pose2D


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda c: c.desired_velocity(None, (2, 1), obstacles=[[1, 0.5]]), "pose"),
        (lambda c: c.desired_velocity(3, (2, 1)), "pose"),
        (lambda c: c.desired_velocity((0, 0, 0), "ab"), "goal_xy"),
        (lambda c: c.desired_velocity((0, 0, 0), (2 + 1j, 1)), "goal_xy"),
        (lambda c: c.desired_velocity((0, 0, 0), (2, 1), obstacles="wall"), "obstacles"),
        (lambda c: c.step((0, 0, 0), (1, 0, 0), dt="0.1"), "dt"),
        (lambda c: c.step((0, 0, 0), (1, 0, 0), dt=True), "dt"),
        (lambda c: c.step((0, 0, 0), None, dt=0.1), "target_pose"),
        (lambda c: c.step((0, 0, 0), (1, 0, 0), dt=0.1, velocity="fast"), "velocity"),
    ],
)
def test_wrong_types_are_type_errors_naming_the_argument(call, name) -> None:  # type: ignore[no-untyped-def]
    ctl = PotentialFieldController()
    ctl.step((0, 0, 0), (1, 0, 0), dt=0.1)
    before = ctl.previous_velocity
    with pytest.raises(TypeError, match=name):
        call(ctl)
    np.testing.assert_array_equal(ctl.previous_velocity, before)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("k_rep", 1e-13), ("k_rep", 1e13), ("influence_radius", 1e-7), ("influence_radius", 1e7),
        ("max_speed", 5e-324), ("max_speed", 1e308), ("max_accel", 1e-7), ("max_decel", 2e6),
        ("max_omega", 0.0), ("kp", -1.0), ("ki", 1e13), ("kd", 1e300),
        ("integral_limit", 1e-9), ("goal_tolerance", 1e7), ("stall_radius", 0.0),
        ("stall_timeout", 1e9),
    ],
)
def test_parameters_outside_their_documented_range_are_refused(name: str, value: float) -> None:
    with pytest.raises(ValueError, match=f"{name} must be in"):
        PotentialFieldController(**{name: value})  # type: ignore[arg-type]


@pytest.mark.parametrize("name", ["k_rep", "max_speed", "kp", "stall_timeout"])
def test_bool_complex_and_string_parameters_are_type_errors(name: str) -> None:
    for bad in (True, 1 + 0j, "1.0"):
        with pytest.raises(TypeError, match=name):
            PotentialFieldController(**{name: bad})  # type: ignore[arg-type]


def test_mode_must_be_a_string_and_range_edges_are_accepted() -> None:
    with pytest.raises(TypeError, match="drive"):
        PotentialFieldController(drive=1)  # type: ignore[arg-type]
    ctl = PotentialFieldController(k_rep=1e12, influence_radius=1e6, max_speed=1e-6, kp=0.0,
                                   ki=1e12, kd=1e12, integral_limit=1e6, stall_timeout=1e6)
    cmd = ctl.step((0, 0, 0), (1, 0, 0.5), dt=1e-6, obstacles=[[0.1, 0.0]])
    assert all(math.isfinite(v) for v in (cmd.vx, cmd.vy, cmd.omega))


def test_control_period_outside_its_range_is_refused_and_leaves_the_state() -> None:
    ctl = PotentialFieldController()
    ctl.step((0, 0, 0), (1, 0, 0), dt=0.1)
    before = ctl.previous_velocity
    for dt in (5e-324, 1e-7, 1e7):
        with pytest.raises(ValueError, match="dt must be in"):
            ctl.step((0, 0, 0), (1, 0, 0), dt=dt)
    np.testing.assert_array_equal(ctl.previous_velocity, before)


def test_a_measured_velocity_that_overflows_is_a_value_error() -> None:
    ctl = PotentialFieldController(drive="diff")
    with pytest.raises(ValueError, match="velocity"):
        ctl.step((0, 0, math.pi / 4), (1, 0, 0), dt=0.1, velocity=[1.7e308, 1.7e308, 0.0])
    assert ctl.previous_velocity.tolist() == [0.0, 0.0]


def test_limit_velocity_change_handles_huge_differences() -> None:
    # |desired - previous| = 1e200: its squared norm overflows; before issue 12 the
    # direction became 0 and the previous velocity came back unchanged.
    out = limit_velocity_change([0.0, 0.0], [1e200, 0.0], max_accel=1e6, max_decel=1e6, dt=1.0)
    np.testing.assert_allclose(out, [1e6, 0.0])
    with pytest.raises(ValueError, match="previous, desired: the velocity change overflows"):
        limit_velocity_change([-1e308, 0.0], [1e308, 0.0], max_accel=1.0, max_decel=1.0, dt=1.0)
    with pytest.raises(ValueError, match="max_accel must be in"):
        limit_velocity_change([0.0], [1.0], max_accel=5e-324, max_decel=1.0, dt=1.0)
    with pytest.raises(TypeError, match="previous"):
        limit_velocity_change(np.array([1 + 1j]), [1.0], max_accel=1.0, max_decel=1.0, dt=1.0)


points = st.tuples(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6))


@settings(max_examples=50, deadline=None)
@given(
    points,
    st.floats(-10.0, 10.0),
    points,
    st.lists(points, max_size=5),
    st.sampled_from(["omni", "diff"]),
    st.floats(1e-6, 1e6),
)
def test_in_range_steps_are_finite(
    xy: tuple[float, float],
    theta: float,
    goal: tuple[float, float],
    obstacles: list[tuple[float, float]],
    mode: str,
    dt: float,
) -> None:
    ctl = PotentialFieldController(drive=mode)  # type: ignore[arg-type]
    for _ in range(2):
        cmd = ctl.step(Pose2D(*xy, theta), Pose2D(*goal, 0.0), dt=dt,
                       obstacles=np.array(obstacles).reshape(-1, 2))
        assert all(math.isfinite(v) for v in (cmd.vx, cmd.vy, cmd.omega))
        assert math.hypot(cmd.vx, cmd.vy) <= ctl.max_speed * (1 + 1e-9)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda c: c.desired_velocity((1e10, 0, 0), (2, 1)), "pose"),
        (lambda c: c.desired_velocity((0, 0, 0), (2, -1e300)), "goal_xy"),
        (lambda c: c.desired_velocity((0, 0, 0), (2, 1), obstacles=[[1e10, 0.0]]), "obstacles"),
        (lambda c: c.step((0, 0, 0), (1.7e308, 0, 0), dt=0.1), "target_pose"),
        (lambda c: c.step((0, -2e9, 0), (1, 0, 0), dt=0.1), "pose"),
    ],
)
def test_positions_beyond_the_fields_range_name_the_argument(call, name) -> None:  # type: ignore[no-untyped-def]
    ctl = PotentialFieldController()
    with pytest.raises(ValueError, match=f"{name}: positions must have"):
        call(ctl)
    # Rows with NaN or inf are still skipped, as documented.
    v = ctl.desired_velocity((0, 0, 0), (2, 0), obstacles=[[math.inf, 0.0], [math.nan, 1.0]])
    np.testing.assert_allclose(v, ctl.desired_velocity((0, 0, 0), (2, 0)))
