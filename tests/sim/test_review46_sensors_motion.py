"""Review 46: the simulator's motion against the closed-form arc of a constant twist.

A body twist ``(vx, vy, ω)`` held from pose ``(x0, y0, θ0)`` moves the robot
along ``θ(t) = θ0 + ω t`` and, integrating the body velocity rotated into the
world,

    x(t) = x0 + vx S - vy C,    y(t) = y0 + vx C + vy S,
    S = (sin θ(t) - sin θ0) / ω,    C = (cos θ0 - cos θ(t)) / ω,

(``S = t cos θ0``, ``C = t sin θ0`` at ``ω = 0``), evaluated here in mpmath to
40 digits through the sum-to-product identities, which stay exact as ω -> 0
(no SE(2) code of navkit's). The twist itself comes
from the drives' equations: a differential drive's ``v = (r_l w_l + r_r w_r) / 2``,
``ω = (r_r w_r - r_l w_l) / D`` on the true radii, an omnidirectional drive's
least-squares inverse of ``w_i = (-sin θi vx + cos θi vy + L ω) / r``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from constant_controller import Constant
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Robot, Simulation, World

mpmath.mp.dps = 40


def arc(start: tuple[float, float, float], twist: tuple[float, float, float],
        t: float) -> tuple[float, float, float]:  # fmt: skip
    """The closed-form pose after holding ``twist`` for ``t`` s (heading not wrapped)."""
    x0, y0, th0 = (mpmath.mpf(v) for v in start)
    vx, vy, w = (mpmath.mpf(v) for v in twist)
    tt = mpmath.mpf(t)
    # S and C by the sum-to-product identities (no cancellation as ω -> 0, where
    # sin(h) / ω -> t / 2): S = 2 cos(θ0 + h) sin(h) / ω, C = 2 sin(θ0 + h) sin(h) / ω.
    h = w * tt / 2
    half = tt / 2 if w == 0 else mpmath.sin(h) / w
    s = 2 * mpmath.cos(th0 + h) * half
    c = 2 * mpmath.sin(th0 + h) * half
    return float(x0 + vx * s - vy * c), float(y0 + vx * c + vy * s), float(th0 + w * tt)


def run(robot: Robot, twist: tuple[float, float, float], start: tuple[float, float, float],
        duration: float, rate: float = 100.0) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    trace = Simulation(World(), robot, Constant(Twist2D(*twist)), start=start,
                       duration=duration, rate=rate, control_rate=min(rate, 20.0),
                       stop_at_goal=False).run()  # fmt: skip
    return trace.times, trace.poses


def assert_on_arc(times: np.ndarray, poses: np.ndarray, start: tuple[float, float, float],
                  twist: tuple[float, float, float], tol: float) -> None:  # fmt: skip
    assert np.all((poses[:, 2] > -math.pi) & (poses[:, 2] <= math.pi))
    for t, (x, y, th) in zip(times.tolist(), poses.tolist(), strict=True):
        ex, ey, eth = arc(start, twist, t)
        assert abs(x - ex) <= tol and abs(y - ey) <= tol, (t, x - ex, y - ey)
        assert abs(math.remainder(th - eth, 2.0 * math.pi)) <= tol, (t, th, eth)


DIFF = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.062)
OMNI3 = OmniDrive.three_wheel(wheel_radius=0.04, base_radius=0.2)
OMNI5 = OmniDrive(np.radians([10.0, 80.0, 170.0, 200.0, 300.0]), wheel_radius=0.035,
                  base_radius=0.25)  # fmt: skip


@pytest.mark.parametrize("omega", [2.0, -0.7, 1e-3, 1e-6, 1e-9, -1e-12, 0.0])
@pytest.mark.parametrize("drive", [DIFF, OMNI3, OMNI5], ids=["diff", "omni3", "omni5"])
def test_constant_twist_follows_the_closed_form_arc(drive: DiffDrive | OmniDrive,
                                                    omega: float) -> None:  # fmt: skip
    twist = (0.6, 0.0 if isinstance(drive, DiffDrive) else -0.25, omega)
    start = (1.5, -2.0, 2.9)  # a positive turn crosses +π at once
    times, poses = run(Robot(drive=drive, footprint=0.1), twist, start, 10.0)
    assert times.shape == (1001,)
    assert_on_arc(times, poses, start, twist, 1e-11)


@settings(max_examples=20, deadline=None)
@given(
    twist=st.tuples(st.floats(-2.0, 2.0), st.floats(-2.0, 2.0), st.floats(-5.0, 5.0)),
    start=st.tuples(st.floats(-50.0, 50.0), st.floats(-50.0, 50.0), st.floats(-math.pi, math.pi)),
    rate=st.sampled_from([5.0, 30.0, 100.0]),
)
def test_any_twist_on_an_omni_robot_follows_its_arc(
    twist: tuple[float, float, float], start: tuple[float, float, float], rate: float
) -> None:
    # Low rates make long steps: one arc per step, exact however long.
    times, poses = run(Robot(drive=OMNI3, footprint=0.1, encoders=None), twist, start, 2.0,
                       rate=rate)  # fmt: skip
    assert_on_arc(times, poses, start, twist, 1e-10)


def test_wheel_radius_errors_move_the_robot_by_the_true_radii() -> None:
    """Nominal wheel speeds on true radii r (1 + e): the twist of the forward equations."""
    errors = (0.04, -0.02)
    robot = Robot(drive=DIFF, footprint=0.1, wheel_radius_error=errors)
    cmd = (0.5, 0.0, 0.8)
    d, rl, rr = DIFF.track, DIFF.left_radius, DIFF.right_radius
    wl = (cmd[0] - cmd[2] * d / 2.0) / rl
    wr = (cmd[0] + cmd[2] * d / 2.0) / rr
    gl, gr = wl * rl * (1.0 + errors[0]), wr * rr * (1.0 + errors[1])
    true_twist = ((gl + gr) / 2.0, 0.0, (gr - gl) / d)
    start = (0.0, 0.0, -1.0)
    times, poses = run(robot, cmd, start, 8.0)
    assert_on_arc(times, poses, start, true_twist, 1e-11)


def test_a_command_beyond_the_wheel_limit_is_scaled_along_its_direction() -> None:
    """Every wheel speed scaled by max / peak: the twist by that factor, its arc's shape kept."""
    cmd = (1.0, 0.5, 3.0)
    a = np.radians([30.0, 150.0, 270.0])  # three_wheel's layout, as documented
    wheels = -np.sin(a) * cmd[0] + np.cos(a) * cmd[1] + OMNI3.base_radius * cmd[2]
    wheels /= OMNI3.wheel_radius
    limit = 20.0
    scale = limit / float(np.max(np.abs(wheels)))
    assert scale < 1.0
    robot = Robot(drive=OMNI3, footprint=0.1, max_wheel_speed=limit)
    start = (0.3, 0.1, 0.5)
    times, poses = run(robot, cmd, start, 5.0)
    assert_on_arc(times, poses, start, tuple(scale * c for c in cmd), 1e-11)


def test_turning_while_the_wheels_ramp_strays_by_order_dt_squared() -> None:
    """The Robot docstring's numbers: ramped wheels against the exact ODE (scipy, 1e-12).

    The exact motion integrates the wheels' continuous ramps (speed ``min(α t,
    w)`` toward each command); the simulator holds each step's mean twist. The
    heading is exact; the position is off by about 1 µm at 100 Hz and 26 µm at
    20 Hz after 1.5 s, a factor 25 for a step 5 times longer: order dt².
    """
    from scipy.integrate import solve_ivp

    track, radius, alpha = 0.3, 0.05, 20.0
    commands = ((0.5 - 1.5 * track) / radius, (0.5 + 1.5 * track) / radius)

    def wheel(command: float, t: float) -> float:
        return math.copysign(min(abs(command), alpha * t), command)

    def exact(t: float, state: np.ndarray) -> list[float]:
        left, right = (wheel(c, t) for c in commands)
        v, w = radius * (left + right) / 2.0, radius * (right - left) / track
        return [v * math.cos(state[2]), v * math.sin(state[2]), w]

    off = {}
    for rate in (100.0, 20.0):
        robot = Robot(drive=DiffDrive(track=track, wheel_radius=radius), footprint=0.1,
                      max_wheel_acceleration=alpha, encoders=None)  # fmt: skip
        times, poses = run(robot, (0.5, 0.0, 3.0), (0.0, 0.0, 0.0), 1.5, rate=rate)
        ref = solve_ivp(exact, (0.0, 1.5), [0.0, 0.0, 0.0], t_eval=times, rtol=1e-12,
                        atol=1e-13, max_step=1e-3).y.T  # fmt: skip
        assert np.max(np.abs(poses[:, 2] - ref[:, 2])) < 1e-9
        off[rate] = float(np.max(np.hypot(*(poses[:, :2] - ref[:, :2]).T)))
    assert 0.5e-6 < off[100.0] < 2e-6
    assert 15e-6 < off[20.0] < 40e-6
    assert 20.0 < off[20.0] / off[100.0] < 30.0
