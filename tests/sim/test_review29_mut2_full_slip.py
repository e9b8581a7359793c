"""Slip only slows a wheel: it never turns the ground under it backwards (mutation gap).

Mutation testing (session 33, round two): clamping the lost fraction ``|s|`` at 2 instead of
1 (so a wheel with ``|s| > 1`` drives the ground backwards) passed every test; the existing
mean-distance check tells the two apart by only 2.5 %.
"""

from __future__ import annotations

import math

import numpy as np

from constant_controller import run_constant
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot


def test_full_slip_never_moves_a_forward_driven_robot_backwards() -> None:
    # Both wheels are driven forward; each keeps 1 - min(|s|, 1) >= 0 of its speed, so the
    # body's forward speed is >= 0 and each step's chord points along the mid-step heading.
    # With |s| unclamped beyond 1 both wheels reverse together in about 1 step in 10.
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
                  wheel_slip=1.0)  # fmt: skip
    trace, _ = run_constant(robot, Twist2D(0.2), 10.0, seed=7)
    poses = trace.poses
    assert poses.shape[0] > 100
    step = np.diff(poses, axis=0)
    turn = np.remainder(step[:, 2] + math.pi, 2.0 * math.pi) - math.pi
    mid = poses[:-1, 2] + 0.5 * turn
    along = step[:, 0] * np.cos(mid) + step[:, 1] * np.sin(mid)
    assert along.min() >= -1e-12
    # Slip happened (the robot is slower than commanded) and it still went forward.
    assert 0.0 < float(along.sum()) < 0.2 * 10.0
