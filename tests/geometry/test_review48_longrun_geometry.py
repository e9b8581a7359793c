"""Long runs of SE(2) integration: a circle driven for 10^5 steps (review 48, LONGRUN).

Each pose is the previous one moved by one exact SE(2) step, so what accumulates is
the rounding of the coordinates: near the origin a pose stays on its circle to about
1e-12 m after 10^5 steps (10^6 in the slow test), its heading wrapped to (-π, π] at
every step and within 1e-9 rad of ``k ω dt`` wrapped; the run is periodic, so the pose
after a whole number of turns is the start.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D, integrate, rollout

# 1 m/s at 0.5 rad/s: a 2 m radius. At 1 kHz a turn is 4π s, not a whole number of
# steps; at dt = π / 2000 s it is 8000 steps exactly (in exact arithmetic).
_V, _OMEGA, _RADIUS = 1.0, 0.5, 2.0
_DT = math.pi / 2000.0
_TURN = 8000


def _circle(steps: int) -> np.ndarray:
    twists = np.tile([_V, 0.0, _OMEGA], (steps, 1))
    return rollout(Pose2D(0.0, 0.0, 0.0), twists, _DT)


def _check(poses: np.ndarray, radius_tol: float, heading_tol: float) -> None:
    radius = np.hypot(poses[:, 0], poses[:, 1] - _RADIUS)
    assert float(np.abs(radius - _RADIUS).max()) < radius_tol
    theta = poses[:, 2]
    assert bool(np.all((theta > -math.pi) & (theta <= math.pi)))
    k = np.arange(poses.shape[0])
    exact = np.remainder(k * (_OMEGA * _DT) + math.pi, 2.0 * math.pi) - math.pi
    off = np.remainder(theta - exact + math.pi, 2.0 * math.pi) - math.pi
    assert float(np.abs(off).max()) < heading_tol
    # A whole number of turns comes back to the start.
    ends = poses[_TURN::_TURN]
    assert float(np.abs(ends[:, :2]).max()) < radius_tol + heading_tol * _RADIUS


def test_a_long_circle_stays_on_its_circle() -> None:
    poses = _circle(100_000)
    _check(poses, 1e-11, 1e-10)


@pytest.mark.slow
def test_a_million_steps_stay_on_their_circle() -> None:
    _check(_circle(1_000_000), 1e-10, 1e-9)


def test_integrate_step_by_step_is_rollout() -> None:
    # One step at a time (as a simulator or an odometry does) accumulates exactly as
    # rollout: the same rows, bit for bit, over 4 turns.
    pose = Pose2D(0.0, 0.0, 0.0)
    rows = _circle(4 * _TURN)
    for k in range(1, rows.shape[0]):
        pose = integrate(pose, (_V, 0.0, _OMEGA), _DT)
        if k % 997 == 0 or k == rows.shape[0] - 1:
            assert (pose.x, pose.y, pose.theta) == tuple(rows[k].tolist())
