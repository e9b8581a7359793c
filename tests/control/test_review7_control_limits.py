"""Control: exact values in range errors; velocity changes whose length overflows.

* The options of :class:`PotentialFieldController`, ``dt`` of
  :func:`limit_velocity_change` and positions printed a refused value with
  ``:g``, which rounds it back into range (``max_speed`` 1e6 + 1e-6 as
  "1e+06"; a pose 1e9 + 1e-6 m away as "1e+09").
* ``OnOffTracker(rotate_angle=...)`` (then ``heading_tolerance``) just above π/2 was refused as out
  of "(0, 1.5708]", a range that holds π/2, which is refused too.
* :func:`limit_velocity_change` refused a change whose components are finite
  but whose length exceeds the float range (from rest toward ``(1.3e308,
  1.3e308)``), documented as refused only when the difference overflows.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.control import OnOffTracker, PotentialFieldController, limit_velocity_change
from navkit.geometry import Pose2D

ABOVE_1E6 = [math.nextafter(1e6, math.inf), 1e6 + 1e-6]
BELOW_1E_6 = math.nextafter(1e-6, 0.0)


@pytest.mark.parametrize("name", ["max_speed", "influence_radius", "stall_timeout"])
@pytest.mark.parametrize("value", [*ABOVE_1E6, BELOW_1E_6])
def test_controller_option_errors_print_the_value_exactly(name: str, value: float) -> None:
    with pytest.raises(ValueError, match=name) as err:
        PotentialFieldController(**{name: value})
    assert repr(value) in str(err.value)


@pytest.mark.parametrize("value", [math.nextafter(1e12, math.inf), -5e-324])
def test_gain_errors_print_the_value_exactly(value: float) -> None:
    with pytest.raises(ValueError, match="kd") as err:
        PotentialFieldController(kd=value)
    assert repr(value) in str(err.value)


@pytest.mark.parametrize("value", ABOVE_1E6)
def test_dt_errors_print_the_value_exactly(value: float) -> None:
    with pytest.raises(ValueError, match="dt") as err:
        limit_velocity_change([0.0], [1.0], max_accel=1.0, max_decel=1.0, dt=value)
    assert repr(value) in str(err.value)
    with pytest.raises(ValueError, match="dt") as err:
        PotentialFieldController().step(Pose2D(0.0, 0.0, 0.0), Pose2D(1.0, 0.0, 0.0), dt=value)
    assert repr(value) in str(err.value)


def test_limits_themselves_are_accepted() -> None:
    ctl = PotentialFieldController(max_speed=1e6, influence_radius=1e-6, kd=1e12, kp=0.0)
    assert (ctl.max_speed, ctl.influence_radius) == (1e6, 1e-6)
    assert "kd=1000000000000.0," in repr(ctl) and "kp=0.0," in repr(ctl)
    # At the limits the steps are exact: 1e6 m/s² or 1e-6 m/s² over 1e6 s.
    got = limit_velocity_change([0.0], [1.0], max_accel=1e6, max_decel=1e-6, dt=1e6)
    np.testing.assert_array_equal(got, [1.0])
    got = limit_velocity_change([0.0], [3e12], max_accel=1e6, max_decel=1e-6, dt=1e6)
    np.testing.assert_array_equal(got, [1e12])
    got = limit_velocity_change([3.0], [0.0], max_accel=1e6, max_decel=1e-6, dt=1e6)
    np.testing.assert_array_equal(got, [2.0])


@pytest.mark.parametrize("arg", ["pose", "target_pose"])
def test_position_errors_print_the_coordinates_exactly(arg: str) -> None:
    far = 1e9 + 1e-6
    poses = {"pose": Pose2D(0.0, 0.0, 0.0), "target_pose": Pose2D(1.0, 0.0, 0.0)}
    poses[arg] = Pose2D(far, 0.0, 0.0)
    with pytest.raises(ValueError, match=arg) as err:
        PotentialFieldController().step(poses["pose"], poses["target_pose"], dt=0.1)
    assert repr(far) in str(err.value)
    PotentialFieldController().step(Pose2D(1e9, -1e9, 0.0), Pose2D(-1e9, 1e9, 0.0), dt=0.1)


@pytest.mark.parametrize("value", [math.pi / 2, math.nextafter(math.pi / 2, 4.0)])
def test_on_off_heading_tolerance_error_states_the_open_range(value: float) -> None:
    with pytest.raises(ValueError, match=r"rotate_angle must be in \(0, π/2\)") as err:
        OnOffTracker(rotate_angle=value)
    assert repr(value) in str(err.value)
    below = math.nextafter(math.pi / 2, 0.0)
    assert OnOffTracker(rotate_angle=below).rotate_angle == below


def test_a_change_longer_than_the_float_range_is_limited() -> None:
    out = limit_velocity_change(
        [0.0, 0.0], [1.3e308, 1.3e308], max_accel=2.0, max_decel=1.0, dt=0.5
    )
    # From rest, one acceleration step of max_accel·dt = 1 along the diagonal.
    assert out == pytest.approx([math.sqrt(0.5), math.sqrt(0.5)], rel=1e-15)
    # Braking from a speed whose length overflows: still on the segment, finite.
    out = limit_velocity_change(
        [1.3e308, -1.3e308], [0.0, 0.0], max_accel=1.0, max_decel=1.0, dt=1.0
    )
    assert np.all(np.isfinite(out))
    assert 0.0 <= out[0] <= 1.3e308 and -1.3e308 <= out[1] <= 0.0
    # A difference that itself overflows is still refused, as documented.
    with pytest.raises(ValueError, match="overflows"):
        limit_velocity_change([1e308], [-1e308], max_accel=1.0, max_decel=1.0, dt=1.0)


huge = st.floats(min_value=1.28e308, max_value=1.7e308)
small = st.floats(min_value=-1e3, max_value=1e3)


@settings(max_examples=50, deadline=None)
@given(small, small, huge, huge, st.sampled_from([-1.0, 1.0]), st.sampled_from([-1.0, 1.0]),
       st.floats(1e-3, 1e3), st.floats(1e-3, 1e3))
def test_huge_requests_move_by_one_limited_step_toward_them(
    px: float, py: float, wx: float, wy: float, sx: float, sy: float, acc: float, dec: float
) -> None:
    prev = np.array([px, py])
    want = np.array([sx * wx, sy * wy])
    out = limit_velocity_change(prev, want, max_accel=acc, max_decel=dec, dt=1.0)
    move = out - prev
    length = math.hypot(*move)
    # Toward a speed far above the current one, the step is an acceleration
    # (or ends one), no longer than max_accel·dt, and points at the request.
    step = max(acc, dec)
    rounding = 4.0 * math.ulp(max(abs(px), abs(py), 1.0)) + 4.0 * math.ulp(step)
    assert 0.0 < length <= step + rounding
    direction = want / np.max(np.abs(want)) - prev / np.max(np.abs(want))
    direction /= math.hypot(*direction)
    assert move / length == pytest.approx(direction, abs=1e-9)


test_huge_requests_move_by_one_limited_step_toward_them_thoroughly = slow_twin(
    test_huge_requests_move_by_one_limited_step_toward_them, max_examples=200
)
